#include "job/job_stream.hpp"

#include "drivers/fanuc_streamer.hpp"
#include "drivers/live_program.hpp"

namespace subfeed::job {

LinkRequest link_request_for(const JobRecord& o, const post::MachineConfig& machine) {
  LinkRequest request;
  request.port = o.port;
  request.tcp = o.tcp;
  request.sim = o.sim ? simulator_for(machine) : std::string();
  request.protocol = std::string(post::to_string(machine.controller.protocol));
  request.sim_speed = o.sim_speed;
  request.sim_baud = o.sim_baud;
  if (machine.controller.protocol == post::Protocol::fanuc && o.sim_baud == 0) {
    request.sim_baud = 115200; // drip feed paces itself by the wire: it needs a speed
  }
  return request;
}

Expected<drivers::StreamSummary> stream_job(const JobRecord& o, int sim_baud,
                                            const post::MachineConfig& machine, Link& link,
                                            JobPipeline& job, drivers::ControlInbox& inbox,
                                            drivers::StreamObserver& observer) {
  const std::string name = job_files(o).nc.string();
  if (machine.controller.protocol == post::Protocol::fanuc) {
    if (!o.tcp.empty()) {
      return fail(ErrorCode::usage, "fanuc drip feed runs over a serial port, not --tcp",
                  {{}, 0, "--tcp"});
    }
    drivers::LiveBlocks program(name, job.program());
    drivers::FanucStreamOptions dnc;
    dnc.serial = serial_options_for(machine);
    if (o.sim && sim_baud > 0) {
      dnc.serial.baud = sim_baud; // the sender paces itself at the simulated wire's speed
    }
    dnc.program_number = machine.controller.program_number;
    return drivers::stream_fanuc(*link.transport, program, dnc, &inbox, observer);
  }
  drivers::LiveGcode program(name, job.program());
  drivers::GrblStreamOptions grbl;
  grbl.line_limit = machine.controller.line_length;
  grbl.rx_buffer = machine.controller.rx_buffer;
  return drivers::stream_grbl(*link.transport, program, grbl, &inbox, observer);
}

} // namespace subfeed::job

#pragma once
// How `run` gets a job's program to the controller: the link it asks for (the simulator
// that matches the machine for a dry run; a DNC simulator needs a wire speed, since drip
// feed paces itself by it), and the stream of the pipeline's lines by the machine's
// protocol as they are posted.

#include "base/error.hpp"
#include "job/controller_link.hpp"
#include "job/job_pipeline.hpp"
#include "job/job_record.hpp"

#include "drivers/control_inbox.hpp"
#include "drivers/grbl_streamer.hpp"

namespace subfeed::job {

[[nodiscard]] LinkRequest link_request_for(const JobRecord& record,
                                           const post::MachineConfig& machine);

// `sim_baud`: the link's (link_request_for), which the DNC sender paces itself at.
[[nodiscard]] Expected<drivers::StreamSummary>
stream_job(const JobRecord& record, int sim_baud, const post::MachineConfig& machine, Link& link,
           JobPipeline& job, drivers::ControlInbox& inbox, drivers::StreamObserver& observer);

} // namespace subfeed::job

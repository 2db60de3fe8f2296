#pragma once
// A simulated Fanuc-style control reading a program by DNC drip feed (docs/PROTOCOLS.md): a
// receive buffer drained by an execution model (block time from feed and length), DC3
// (XOFF) at the high-water mark and DC1 (XON) at the low-water mark, an overrun alarm when
// the sender writes more than `overrun_tolerance` characters after the DC3 has left
// (alarm 087 on many controls; what was already in the pty is not the sender's fault), a
// TH alarm for characters outside ISO 840 or stop bits that differ from the control's (a
// pty carries no data-bit or parity setting: Linux forces 8N on ptys), and a record of the
// executed blocks. It shares no code with the sender.

#include "sim/byte_channel.hpp"
#include "sim/delivery_hash.hpp"
#include "sim/machine_record.hpp"
#include "sim/motion_planner.hpp"
#include "sim/serve_thread.hpp"

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace subfeed::sim {

struct FanucFaults {
  // Counts are of program blocks received, from 1.
  std::optional<long> stuck_xoff_at_block;  // DC3 and never DC1 again
  std::optional<long> lose_xon_after_block; // the next DC1 it owes is never sent
  std::optional<long> drop_at_block;        // the link drops
};

struct FanucSimOptions {
  int buffer = 256;     // bytes
  int high_water = 192; // DC3 at this fill
  int low_water = 64;   // DC1 at this fill, after a DC3
  int overrun_tolerance = 10;
  // How long the link may take to carry a DC3 to the sender: characters the sender
  // writes within it are in flight, not an overrun. A UART carries it within a character
  // (0); a pty on a loaded machine, or a USB adapter's latency timer, takes milliseconds.
  std::chrono::milliseconds link_latency{0};
  int baud = 9600; // emulated wire speed; 0 = unlimited
  int data_bits = 7;
  char parity = 'E'; // 'N', 'E', 'O'
  int stop_bits = 2;
  bool request_tape = false; // send DC1 when a sender connects, asking for the tape
  bool eia_cr = false;       // blocks end with CR (EIA option) instead of LF
  MotionModel motion;
  int look_ahead_blocks = 32; // blocks the control takes from the buffer ahead of motion
  // Drain jitter: before one block in `pause_one_in` (at random) the control stalls for up
  // to `max_block_pause` of real time, as when it is busy with something else.
  std::chrono::milliseconds max_block_pause{0};
  int pause_one_in = 1;
  unsigned seed = 1;
  bool record_executed = false;
  // The blocks carried out and the machine's position (absolute encoders, standard on
  // Fanuc), kept beyond the control.
  MachineRecordOptions record;
  FanucFaults faults;
};

struct FanucSimStats {
  std::vector<std::string> executed; // blocks run, as received (without the EOB)
  long executed_count = 0;
  std::uint64_t executed_hash = delivery_hash_seed; // FNV-1a over blocks and '\n'
  long blocks_received = 0;
  long xoff_sent = 0;
  long xon_sent = 0;
  int max_after_xoff = 0; // most characters written after a DC3 had left
  int max_fill = 0;
  bool program_started = false; // '%' leader seen
  bool program_ended = false;   // '%' trailer seen
  std::string program_number;   // from the O line
  std::string alarm;            // empty, or e.g. "087 overrun", "TH character 'a'"
};

class FanucSim {
public:
  FanucSim(std::unique_ptr<ByteChannel> channel, FanucSimOptions options);
  FanucSim(const FanucSim&) = delete;
  FanucSim& operator=(const FanucSim&) = delete;
  ~FanucSim();

  void start();
  void stop();
  void run(const std::stop_token& stop);

  [[nodiscard]] std::string address() const { return address_; }
  [[nodiscard]] FanucSimStats stats() const;

private:
  class Control;
  std::unique_ptr<Control> control_;
  std::string address_;
  ServeThread thread_; // last: stops before the machine it runs goes
};

} // namespace subfeed::sim

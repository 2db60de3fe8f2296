#pragma once
// Where an interrupted job continues and how the machine gets back there, for `resume`.
//
// GRBL: once the machine stands still, its position is looked up among the program's moves
// between the last acknowledged line less a planner's reach and the last line sent
// (restart_point.hpp): at the end of a move the program continues after it; inside one,
// that move runs again from its start, so every block runs once. A position on no move
// restarts early enough that nothing is skipped, and says how many lines may be cut twice.
// DNC: the control reports nothing, so the user gives the sequence number it shows (and
// its position where the tool tilts with the head). `from` overrides either.
//
// Before the program continues the modes are restored and the tool comes back safely
// (restart_approach.hpp). A program that is gone (subfeed died before it was complete) is
// rebuilt from the journal's job record and must match what the journal says was sent.

#include "base/error.hpp"
#include "job/controller_link.hpp"
#include "job/job_record.hpp"
#include "job/logger.hpp"
#include "job/setup_flags.hpp"

#include "drivers/control_inbox.hpp"
#include "drivers/grbl_streamer.hpp"
#include "drivers/journal_reader.hpp"

#include <optional>
#include <string>
#include <vector>

namespace subfeed::job {

struct ResumeRequest {
  std::string journal;
  std::string machine;      // empty: the job's
  long from = 0;            // program line to continue from; 0: found
  long block = -1;          // DNC: the sequence number the control shows
  std::string at;           // DNC: the machine position the control shows, "X,Y,Z,..."
  double clearance = 0.0;   // mm; 0: the job's clearance, else the machine's retract
  double plunge_feed = 0.0; // mm/min; 0: the job's
  double connect_timeout_s = 5.0;
  SetupFlags setup; // must agree with the job's, which a resume never changes
};

// What the journal and the job say: the program, where it stopped, the machine.
struct Interrupted {
  drivers::JournalSummary journal;
  std::optional<JobRecord> job;
  post::MachineConfig machine;
  bool dnc = false;
};

// Where the program continues and how the machine gets there.
struct Restart {
  long after = 0;
  std::string why;
  std::vector<std::string> blocks; // the modes, the approach, the modes again
};

// Reads the journal and the machine, rebuilds a missing program, and checks the program
// against the journal.
[[nodiscard]] Expected<Interrupted> read_interrupted(const ResumeRequest& request, Logger& log);

// DNC: from the user's words alone, checked before the port is touched.
[[nodiscard]] Expected<Restart> dnc_restart(const Interrupted& r, const ResumeRequest& request);

// GRBL: waits until the machine stands still, asks where it is, and restarts there.
[[nodiscard]] Expected<Restart> grbl_restart_found(drivers::Transport& link, const Interrupted& r,
                                                   const ResumeRequest& request, Logger& log);

// Streams the restart blocks and the program after `restart.after` over the link.
[[nodiscard]] Expected<drivers::StreamSummary> stream_rest(const Interrupted& r, Restart restart,
                                                           Link& link, drivers::ControlInbox& inbox,
                                                           drivers::StreamObserver& observer);

} // namespace subfeed::job

#pragma once
// What defines a job for `run` and `resume`: the cage, the machine, the planning flags and
// where the files go; how it is built into a JobSpec; and how it is written into the
// journal (one `event job key=value ...` line) so that a resume can rebuild the very same
// program when subfeed itself died before the .nc was complete.

#include "base/error.hpp"
#include "job/job_pipeline.hpp"
#include "job/logger.hpp"
#include "job/plan_settings.hpp"
#include "job/setup_flags.hpp"

#include <filesystem>
#include <string>

namespace subfeed::job {

struct JobRecord {
  std::string cage;       // or CL data (.cl): then nothing is planned
  std::string check_cage; // with CL data: the cage its every move is checked against
  PlanSettings plan;
  SetupFlags setup; // as given; a CL file's own record wins where it has one
  std::string machine;
  std::string output;  // BASE: BASE.cl, BASE.nc, BASE.journal; default the cage without .obj
  std::string journal; // default BASE.journal
  double spindle_rpm = 0.0;
  std::string port, tcp;
  bool sim = false;
  double sim_speed = 1.0;
  int sim_baud = -1;
  bool json = false;
};

// Whether the job's input is CL data (PART.cl, from `plan` or another CAM) rather than a cage.
[[nodiscard]] bool reads_cl(const JobRecord& o);
[[nodiscard]] JobFiles job_files(const JobRecord& o);
[[nodiscard]] std::filesystem::path journal_path(const JobRecord& o);
// Loads the machine and the cage, checks the flags and builds the whole job's definition.
[[nodiscard]] Expected<JobSpec> job_spec(const JobRecord& o, Logger& log);

// "key=value ..." with %-escaped values; decode_job fills the job's fields back.
[[nodiscard]] std::string encode_job(const JobRecord& o);
[[nodiscard]] Expected<JobRecord> decode_job(std::string_view text, const Where& where);

} // namespace subfeed::job

#pragma once
// One job from cage to program text, lazily: a planning thread yields CL poses pass by pass
// (and writes the .cl) or reads them from existing CL data, a post thread turns them into program
// lines (and writes the .nc and its .map), and the lines go out through a bounded queue to whoever
// streams them. Each stage waits when the next one is full, so memory does not grow with the job's
// length and the program's first lines (modes, spindle) are ready before planning has finished.
//
// If the stream stops early (a fault, a stop), detach() lets both threads finish the files
// without a reader, so that a resume has the whole program; files appear only complete.
// The progress ledger maps program lines to cutting length and modelled machine time for
// the display; it is trimmed as lines are acknowledged.

#include "base/bounded_queue.hpp"
#include "cl/cl_pose.hpp"
#include "drivers/live_program.hpp"
#include "geometry/toolpath_planner.hpp"
#include "job/block_gate.hpp"
#include "post/machine_config.hpp"
#include "post/post_file.hpp"

#include <atomic>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

namespace subfeed::job {

struct JobFiles {
  std::filesystem::path cl, nc; // the map goes beside the .nc (post::map_path_for)
};

// What the planner needs; a job without it reads its CL data from JobFiles::cl instead.
struct PlanInput {
  geometry::Cage cage;
  geometry::LimitSurface surface;
  geometry::PlanOptions options;
};

struct JobSpec {
  std::optional<PlanInput> plan; // empty: the job's CL data exists (APT from another CAM)
  post::MachineConfig machine;
  post::PostFileOptions post;
  cl::ClHeader header;
  JobFiles files;
  std::size_t queue_lines = 256; // program lines between the post and the stream
  // Existing CL data passes this pose by pose before the post sees it (the planner has its own).
  std::optional<geometry::MotionGate> gate;
};

struct JobTotals {
  geometry::PlanSummary plan;
  post::PostStats post;
  long lines = 0;
  double cut_mm = 0.0;      // feed moves of the CL path
  double machine_min = 0.0; // modelled machine time of the whole program
  // The posted program's moves as the machine makes them, through the gate (block_gate.hpp).
  geometry::GateReport posted_gate;
};

// Totals are estimates while planning goes on (the cutting length of the planes still to
// cut taken as that of the planes cut so far, machine time at the posted lines' rate) and
// exact once it has finished.
struct JobProgress {
  bool planned = false; // the planner has finished
  long passes = 0;      // passes planned so far
  long lines_posted = 0;
  double cut_done_mm = 0.0; // along the CL path, through the last acknowledged line
  double cut_total_mm = 0.0;
  double minutes_done = 0.0; // modelled machine time through the last acknowledged line
  double minutes_total = 0.0;
  // The last stage the planner entered before slicing (none yet, or CL data read), and
  // during the deformation the solve it is on and the most there may be.
  std::optional<geometry::PlanStage> stage;
  int solve = 0, most_solves = 0;
  double stage_share = -1.0; // of that stage done, 0..1, where it tells one; else negative
};

class JobPipeline {
public:
  explicit JobPipeline(JobSpec spec);
  JobPipeline(const JobPipeline&) = delete;
  JobPipeline& operator=(const JobPipeline&) = delete;
  ~JobPipeline();

  void start();
  [[nodiscard]] drivers::ProgramQueue& program() { return lines_; }
  // Nobody reads the program any more: finish the files alone.
  void detach();
  // Waits for both threads; the files are in place when this succeeds.
  [[nodiscard]] Expected<JobTotals> finish();

  // The program line of the first move (0 until it is posted): the job's first block may
  // be a mode line the post writes before the planner has a pose.
  [[nodiscard]] long first_motion_line() const { return first_motion_line_; }

  // Thread-safe, for the display: progress through program line `acked_line`.
  [[nodiscard]] JobProgress progress(long acked_line);

private:
  struct LedgerEntry {
    long line;
    double cut_mm, minutes;
  };
  [[nodiscard]] Expected<void> plan_all();
  [[nodiscard]] Expected<void> read_all();
  [[nodiscard]] Expected<void> hand_over(const cl::ClPose& pose, std::optional<cl::ClPose>& last,
                                         double& cut_mm);
  [[nodiscard]] Expected<void> post_all();
  void put_line(std::string_view text, double cut_mm, double minutes);

  JobSpec spec_;
  BoundedQueue<Expected<cl::ClPose>> poses_{4096};
  drivers::ProgramQueue lines_;
  std::atomic<bool> detached_{false};
  std::atomic<bool> planned_{false};
  std::atomic<long> passes_{0};
  std::atomic<long> lines_posted_{0};
  std::atomic<long> first_motion_line_{0};
  std::atomic<long> plane_{0}, planes_{0};
  std::atomic<int> stage_{-1}, solve_{0}, most_solves_{0};
  std::atomic<double> stage_share_{-1.0};
  std::atomic<double> cut_planned_{0.0};
  std::mutex ledger_mutex_;
  std::deque<LedgerEntry> ledger_;
  LedgerEntry acked_{0, 0.0, 0.0};
  LedgerEntry posted_{0, 0.0, 0.0}; // under ledger_mutex_
  std::optional<Error> plan_error_, post_error_;
  JobTotals totals_;
  // Every posted block passes it before it is written: made from spec_.gate, or from the
  // planner's gate by plan_all before it hands over the first pose (so the post, which
  // waits for that pose, sees it).
  std::optional<BlockGate> block_gate_;
  std::thread planner_, poster_;
};

} // namespace subfeed::job

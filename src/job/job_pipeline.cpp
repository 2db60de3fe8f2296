#include "job/job_pipeline.hpp"

#include "job/tool_spec.hpp"

#include "cl/cl_reader.hpp"
#include "cl/cl_writer.hpp"
#include "job/motion_time.hpp"
#include "job/plan_refusal.hpp"
#include "job/restart_point.hpp"
#include "post/program_sink.hpp"

#include <algorithm>
#include <cmath>

namespace subfeed::job {

namespace {

Error stopped_reading() {
  return Error{ErrorCode::stopped, "the post stopped reading", {}};
}

double distance(const cl::ClPose& a, const cl::ClPose& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    sum += (b.tip[i] - a.tip[i]) * (b.tip[i] - a.tip[i]);
  }
  return std::sqrt(sum);
}

} // namespace

namespace {

// The posted blocks' gate from the CL poses': the same part and rules, cuts allowed the
// post's tolerance deeper (it splits moves only down to that).
BlockGate block_gate_from(const post::MachineConfig& machine, const geometry::MotionGate& gate,
                          double post_tolerance_mm) {
  return {machine, gate.sibling(gate.options().tolerance + post_tolerance_mm)};
}

} // namespace

JobPipeline::JobPipeline(JobSpec spec) : spec_(std::move(spec)), lines_(spec_.queue_lines) {
  if (spec_.gate) {
    block_gate_.emplace(block_gate_from(spec_.machine, *spec_.gate, spec_.post.post.tolerance));
  }
}

JobPipeline::~JobPipeline() {
  detach();
  poses_.close();
  if (planner_.joinable()) {
    planner_.join();
  }
  if (poster_.joinable()) {
    poster_.join();
  }
}

void JobPipeline::start() {
  planner_ = std::thread([this] {
    if (auto done = plan_all(); !done) {
      plan_error_ = done.error();
      poses_.push(std::unexpected(done.error()));
    }
    planned_ = true;
    poses_.close();
  });
  poster_ = std::thread([this] {
    if (auto done = post_all(); !done) {
      post_error_ = done.error();
      if (!detached_) {
        lines_.push(std::unexpected(done.error()));
      }
      poses_.close(); // a planner waiting to hand over a pose stops
    }
    lines_.close();
  });
}

void JobPipeline::detach() {
  detached_ = true;
  lines_.close();
}

// Counts the pose toward the progress figures and passes it to the post.
Expected<void> JobPipeline::hand_over(const cl::ClPose& pose, std::optional<cl::ClPose>& last,
                                      double& cut_mm) {
  if (pose.kind == cl::MoveKind::feed && last) {
    cut_mm += distance(*last, pose);
    cut_planned_ = cut_mm;
  }
  last = pose;
  if (pose.kind == cl::MoveKind::plunge) {
    ++passes_;
  }
  if (!poses_.push(pose)) {
    return std::unexpected(stopped_reading());
  }
  return {};
}

Expected<void> JobPipeline::plan_all() {
  if (!spec_.plan) {
    return read_all();
  }
  const auto& input = *spec_.plan;
  const geometry::PlanObserver observer{.stage =
                                            [this](geometry::PlanStage s) {
                                              stage_share_ = -1.0;
                                              stage_ = static_cast<int>(s);
                                            },
                                        .solve =
                                            [this](int solve, int most) {
                                              solve_ = solve;
                                              most_solves_ = most;
                                            },
                                        .share = [this](double done) { stage_share_ = done; }};
  SUBFEED_TRY_ASSIGN(auto planner, geometry::ToolpathPlanner::prepare(input.cage, input.surface,
                                                                      input.options, observer));
  block_gate_.emplace(block_gate_from(spec_.machine, planner.gate(), spec_.post.post.tolerance));
  auto header = spec_.header;
  record_tool(header, input.options, planner.summary());
  SUBFEED_TRY_ASSIGN(auto writer, cl::ClWriter::create(spec_.files.cl, header));
  std::optional<cl::ClPose> last;
  double cut_mm = 0.0;
  const auto on_plane = [this](long plane, long planes) {
    plane_ = plane;
    planes_ = planes;
  };
  if (auto ran = planner.run(
          [&](const cl::ClPose& pose) -> Expected<void> {
            cl::ClPose numbered = pose;
            numbered.line = writer.write(pose);
            return hand_over(numbered, last, cut_mm);
          },
          on_plane);
      !ran) {
    return std::unexpected(at_refused_pose(ran.error(), planner, writer, spec_.files.cl));
  }
  SUBFEED_TRY(writer.finish());
  totals_.plan = planner.summary();
  return {};
}

// Existing CL data: the share of the file read stands in for the planes planned.
Expected<void> JobPipeline::read_all() {
  SUBFEED_TRY_ASSIGN(auto reader, cl::ClReader::open(spec_.files.cl));
  std::error_code failed;
  planes_ = static_cast<long>(std::filesystem::file_size(spec_.files.cl, failed));
  std::optional<cl::ClPose> last;
  double cut_mm = 0.0;
  long poses = 0;
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto pose, reader.next());
    if (!pose) {
      break;
    }
    if (spec_.gate) {
      if (auto checked = spec_.gate->check(*pose); !checked) {
        return std::unexpected(cl::in_cl_file(std::move(checked).error(), spec_.files.cl));
      }
    }
    SUBFEED_TRY(hand_over(*pose, last, cut_mm));
    if (++poses % 1024 == 0) {
      plane_ = static_cast<long>(reader.offset());
    }
  }
  totals_.plan.passes = passes_;
  totals_.plan.points = poses;
  return {};
}

void JobPipeline::put_line(std::string_view text, double cut_mm, double minutes) {
  const long line = ++lines_posted_;
  if (first_motion_line_ == 0 && moves_an_axis(text)) {
    first_motion_line_ = line;
  }
  if (detached_) {
    return;
  }
  {
    const std::lock_guard lock(ledger_mutex_);
    ledger_.push_back({line, cut_mm, minutes});
    posted_ = ledger_.back();
  }
  if (!lines_.push(std::string(text))) {
    detached_ = true;
  }
}

Expected<void> JobPipeline::post_all() {
  MotionTimeModel model(spec_.machine);
  double cut_mm = 0.0, minutes = 0.0;
  post::ProgramTaps taps;
  taps.block = [&](const post::MotionBlock& block) { minutes += model.add(block); };
  taps.line = [&](std::string_view line) { put_line(line, cut_mm, minutes); };
  auto options = spec_.post;
  options.check_block = [this](const post::MotionBlock& block) -> Expected<void> {
    if (!block_gate_) { // no pose reaches the post before it is made
      return fail(ErrorCode::bad_input, "a posted block came before the part's gate was built");
    }
    return block_gate_->check(block);
  };
  SUBFEED_TRY_ASSIGN(auto sink,
                     post::ProgramSink::create(spec_.machine, options, spec_.files.nc, taps));
  const auto run = [&]() -> Expected<void> {
    if (spec_.post.look_ahead && !spec_.plan) {
      // The CL data exists: read it once to choose the start, as `post` does.
      SUBFEED_TRY_ASSIGN(auto reader, cl::ClReader::open(spec_.files.cl));
      SUBFEED_TRY(sink->choose_start(reader));
    }
    SUBFEED_TRY(sink->begin());
    std::optional<cl::ClPose> last;
    while (auto item = poses_.pop()) {
      if (!*item) {
        return std::unexpected(item->error());
      }
      const cl::ClPose& pose = **item;
      if (pose.kind == cl::MoveKind::feed && last) {
        cut_mm += distance(*last, pose);
      }
      last = pose;
      SUBFEED_TRY(sink->add(pose));
    }
    if (!planned_) {
      return std::unexpected(stopped_reading());
    }
    return sink->finish();
  };
  if (auto done = run(); !done) {
    return std::unexpected(cl::in_cl_file(std::move(done).error(), spec_.files.cl));
  }
  if (plan_error_) {
    return std::unexpected(*plan_error_);
  }
  SUBFEED_TRY(sink->commit());
  const auto summary = sink->summary();
  totals_.post = summary.stats;
  totals_.lines = summary.lines;
  totals_.cut_mm = cut_mm;
  totals_.machine_min = minutes;
  totals_.posted_gate = block_gate_ ? block_gate_->report() : geometry::GateReport{};
  return {};
}

Expected<JobTotals> JobPipeline::finish() {
  if (planner_.joinable()) {
    planner_.join();
  }
  if (poster_.joinable()) {
    poster_.join();
  }
  if (plan_error_) {
    return std::unexpected(*plan_error_);
  }
  if (post_error_) {
    return std::unexpected(*post_error_);
  }
  return totals_;
}

JobProgress JobPipeline::progress(long acked_line) {
  JobProgress p;
  p.planned = planned_;
  p.passes = passes_;
  p.lines_posted = lines_posted_;
  if (const int stage = stage_; stage >= 0) {
    p.stage = static_cast<geometry::PlanStage>(stage);
  }
  p.solve = solve_;
  p.most_solves = most_solves_;
  p.stage_share = stage_share_;
  const std::lock_guard lock(ledger_mutex_);
  while (!ledger_.empty() && ledger_.front().line <= acked_line) {
    acked_ = ledger_.front();
    ledger_.pop_front();
  }
  p.cut_done_mm = acked_.cut_mm;
  p.minutes_done = acked_.minutes;
  const double planned_mm = cut_planned_;
  const long plane = plane_, planes = planes_;
  p.cut_total_mm = p.planned || plane <= 0
                       ? planned_mm
                       : planned_mm * static_cast<double>(planes) / static_cast<double>(plane);
  const double rate = posted_.cut_mm > 0.0 ? posted_.minutes / posted_.cut_mm : 0.0;
  p.minutes_total = posted_.minutes + std::max(0.0, p.cut_total_mm - posted_.cut_mm) * rate;
  return p;
}

} // namespace subfeed::job

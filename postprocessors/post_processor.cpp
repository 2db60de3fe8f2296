#include "post/post_processor.hpp"

#include "angles.hpp"
#include "vector_math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace subfeed::post {

namespace {

constexpr int max_split_depth = 30;
// Joint-linear motion is checked at these fractions of a block; the margin covers the
// deviation between samples (the tests sample densely to hold the post to the tolerance).
// Quarters are not enough: where C turns fast while the tip creeps (passing near the pole)
// the tip runs past the segment's end late in the block and comes back.
constexpr std::array<double, 7> samples{0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875};
constexpr double sample_margin = 0.9;

struct SegmentPoint {
  double distance;         // mm from p to the segment
  std::optional<double> t; // where along it the nearest point is, 0..1; none for a point
};

SegmentPoint nearest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const Vec3 ap{p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double len2 = dot(ab, ab);
  if (len2 <= 0.0) {
    return {std::sqrt(dot(ap, ap)), std::nullopt};
  }
  const double t = std::clamp(dot(ap, ab) / len2, 0.0, 1.0);
  const Vec3 d{ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
  return {std::sqrt(dot(d, d)), t};
}

} // namespace

PostProcessor::PostProcessor(const MachineConfig& machine, const Kinematics& kinematics,
                             PostOptions options, BlockSink sink)
    : machine_(&machine), kinematics_(&kinematics), options_(options), sink_(std::move(sink)),
      tracker_(kinematics, machine) {
  // Each written coordinate may be off by half its last digit: the joints' rounding moves
  // the tip by up to sqrt(3)/2 of a unit, which the splitting must leave room for.
  const double rounding = std::sqrt(3.0) * 0.5 * std::pow(10.0, -options_.decimals);
  split_tolerance_ = std::max(options_.tolerance - rounding, 0.25 * options_.tolerance);
}

double PostProcessor::safe_z() const {
  return machine_->post.safe_z.value_or(machine_->axes[2]->max);
}

long PostProcessor::count_repositions(cl::ClReader& reader, const JointPosition& start) {
  RotaryTracker tracker(*kinematics_, *machine_);
  tracker.start_at(start);
  long count = 0;
  while (true) {
    auto pose = reader.next();
    if (!pose || !*pose) {
      return pose ? count : std::numeric_limits<long>::max();
    }
    const auto step = tracker.step(**pose);
    if (!step) {
      return std::numeric_limits<long>::max();
    }
    count += step->reposition && (*pose)->kind != cl::MoveKind::rapid ? 1 : 0;
  }
}

// At the pole C is free and the first pose offers one solution, yet the C it starts with
// decides the branch the path takes when it leaves the pole: offer the C of every solution
// of the first pose off the pole.
Expected<std::vector<JointPosition>> PostProcessor::pole_start_candidates(cl::ClReader& reader,
                                                                          const cl::ClPose& first) {
  SUBFEED_TRY_ASSIGN(auto options, tracker_.start_candidates(first));
  if (!tracker_.in_cone(first.axis)) {
    return options;
  }
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto pose, reader.next());
    if (!pose) {
      return options;
    }
    if (!tracker_.in_cone(pose->axis)) {
      auto later = tracker_.start_candidates(*pose);
      if (!later) {
        return options;
      }
      std::vector<JointPosition> starts;
      for (const auto& j : *later) {
        auto start = tracker_.nearest({first.tip, first.axis}, j);
        start[5] = j[5];
        starts.push_back(start);
      }
      return starts;
    }
  }
}

Expected<void> PostProcessor::choose_start(cl::ClReader& reader) {
  SUBFEED_TRY_ASSIGN(const auto first, reader.next());
  if (first) {
    SUBFEED_TRY_ASSIGN(auto options, pole_start_candidates(reader, *first));
    if (options.size() > 1) {
      std::vector<long> counts;
      for (const auto& start : options) {
        SUBFEED_TRY(reader.rewind());
        (void)reader.next(); // the first pose itself
        counts.push_back(count_repositions(reader, start));
      }
      const long fewest = *std::ranges::min_element(counts);
      std::vector<JointPosition> best;
      for (std::size_t i = 0; i < options.size(); ++i) {
        if (counts[i] == fewest) {
          best.push_back(options[i]);
        }
      }
      options = std::move(best);
    }
    start_ = tracker_.prefer(options);
  }
  return reader.rewind();
}

Expected<void> PostProcessor::emit(MotionBlock block, const JointPosition* joints) {
  if (joints != nullptr) {
    machine_at_ = *joints;
  } else {
    for (std::size_t i = 0; i < block.axes.size(); ++i) {
      if (block.axes[i]) {
        machine_at_[i] = *block.axes[i];
      }
    }
  }
  ++stats_.blocks;
  return sink_(block);
}

MotionBlock PostProcessor::block_for(const Placed& target, Motion motion) const {
  MotionBlock block;
  block.motion = motion;
  block.cl_line = target.pose.line;
  for (std::size_t i = 0; i < block.axes.size(); ++i) {
    block.axes[i] = target.joints[i];
  }
  if (options_.tcp != TcpMode::off) {
    block.tcp = true;
    for (std::size_t i = 0; i < 3; ++i) {
      block.axes[i] = target.pose.tip[i];
    }
    if (options_.tcp == TcpMode::vector) {
      block.vector = target.pose.axis;
      block.axes[3] = block.axes[4] = block.axes[5] = std::nullopt;
    }
  }
  return block;
}

Expected<void> PostProcessor::rapid_words(const JointPosition& target,
                                          std::initializer_list<std::size_t> axes, long line) {
  MotionBlock block;
  block.motion = Motion::rapid;
  block.cl_line = line;
  block.link = true;
  for (const auto i : axes) {
    block.axes[i] = target[i];
  }
  return emit(block);
}

Expected<void> PostProcessor::up_to_safe_z(long line) {
  JointPosition up{};
  up[2] = safe_z();
  return rapid_words(up, {2}, line);
}

PostProcessor::Placed PostProcessor::offset_along_axis(const Placed& at, double distance) const {
  Placed out = at;
  for (std::size_t i = 0; i < 3; ++i) {
    out.pose.tip[i] += distance * at.pose.axis[i];
  }
  out.joints = tracker_.nearest({out.pose.tip, out.pose.axis}, at.joints);
  return out;
}

Expected<void> PostProcessor::position(const Placed& target, bool feed_in) {
  const Placed above = feed_in ? offset_along_axis(target, machine_->post.retract) : target;
  const long line = target.pose.line;
  bool turns = !last_;
  for (std::size_t r = 3; r < 6; ++r) {
    turns = turns || std::abs(machine_at_[r] - above.joints[r]) > no_motion;
  }
  if (turns) {
    SUBFEED_TRY(up_to_safe_z(line));
    SUBFEED_TRY(rapid_words(above.joints, {3, 4, 5}, line));
    SUBFEED_TRY(rapid_words(above.joints, {0, 1}, line));
  }
  auto block = block_for(above, Motion::rapid);
  block.link = feed_in;
  if (turns && options_.tcp == TcpMode::off) {
    block.axes = {};
    block.axes[2] = above.joints[2];
  }
  SUBFEED_TRY(emit(block, &above.joints));
  if (feed_in) {
    return cut_segment(above, target, true);
  }
  return {};
}

Expected<void> PostProcessor::retract(const Placed& from) {
  const Placed away = offset_along_axis(from, machine_->post.retract);
  if (away.joints[2] < safe_z()) {
    SUBFEED_TRY(cut_segment(from, away, true));
  }
  return up_to_safe_z(from.pose.line);
}

bool PostProcessor::within_tolerance(const Placed& from, const Placed& to) const {
  if (options_.tcp != TcpMode::off) {
    return true; // the control keeps the tip on the line
  }
  bool turns = false;
  for (std::size_t r = 3; r < 6; ++r) {
    turns = turns || std::abs(from.joints[r] - to.joints[r]) > no_motion;
  }
  if (!turns) {
    return true; // linear axes alone move the tip on a straight line
  }
  const Vec3 a0 = kinematics_->forward(from.joints).axis;
  const Vec3 a1 = kinematics_->forward(to.joints).axis;
  for (const double t : samples) {
    const ToolPose p = kinematics_->forward(lerp(from.joints, to.joints, t));
    // The axis is judged where the tip is along the segment, as `check` judges it: when the
    // tip creeps while the table turns, joint time and path position part ways.
    const SegmentPoint at = nearest_on_segment(p.tip, from.pose.tip, to.pose.tip);
    if (at.distance > sample_margin * split_tolerance_ ||
        angle_deg(p.axis, slerp(a0, a1, at.t.value_or(t))) >
            sample_margin * options_.axis_tolerance) {
      return false;
    }
  }
  return true;
}

PostProcessor::Placed PostProcessor::midpoint(const Placed& from, const Placed& to) const {
  Placed mid = to;
  for (std::size_t i = 0; i < 3; ++i) {
    mid.pose.tip[i] = 0.5 * (from.pose.tip[i] + to.pose.tip[i]);
  }
  mid.pose.axis = slerp(from.pose.axis, to.pose.axis, 0.5);
  mid.joints = tracker_.nearest({mid.pose.tip, mid.pose.axis}, lerp(from.joints, to.joints, 0.5));
  return mid;
}

Expected<void> PostProcessor::cut_segment(const Placed& from, const Placed& to, bool link) {
  struct Span {
    Placed from, to;
    int depth;
  };
  // Depth-first, left half first, so blocks come out in path order; the stack holds at most
  // one pending right half per level.
  std::vector<Span> stack{{from, to, 0}};
  while (!stack.empty()) {
    Span span = std::move(stack.back());
    stack.pop_back();
    if (span.depth < max_split_depth && !within_tolerance(span.from, span.to)) {
      const Placed mid = midpoint(span.from, span.to);
      ++stats_.splits;
      stack.push_back({mid, span.to, span.depth + 1});
      stack.push_back({span.from, mid, span.depth + 1});
      continue;
    }
    const auto& b = span.to;
    const double minutes = block_minutes(span.from, b);
    if (minutes <= 0.0) {
      continue; // the same pose again
    }
    const auto length = programmed_length(span.from, b);
    bool turns = false;
    for (std::size_t r = 3; r < 6; ++r) {
      turns = turns || std::abs(span.from.joints[r] - b.joints[r]) > no_motion;
    }
    auto block = block_for(b, Motion::linear);
    block.link = link;
    // Under TCP F is the tip's feed (slowed where an axis would exceed its max_feed); a
    // turn in place has no tip feed and goes by inverse time.
    const bool inverse = options_.tcp == TcpMode::off ? turns : length <= no_motion;
    block.feed_mode = inverse ? FeedMode::inverse_time : FeedMode::per_minute;
    block.feed = inverse ? 1.0 / minutes : length / minutes;
    SUBFEED_TRY(emit(block, &b.joints));
  }
  return {};
}

double PostProcessor::rounded(double value, std::size_t axis) const {
  const double scale = std::pow(10.0, options_.decimals + (is_rotary_axis(axis) ? 1 : 0));
  return std::round(value * scale) / scale;
}

// The length the control computes from the written words: tool tip under TCP, else the tip
// path's chord (which the joints' linear axes carry when no rotary axis turns).
double PostProcessor::programmed_length(const Placed& a, const Placed& b) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    const double d = options_.tcp != TcpMode::off
                         ? rounded(b.pose.tip[i], i) - rounded(a.pose.tip[i], i)
                         : rounded(b.joints[i], i) - rounded(a.joints[i], i);
    sum += d * d;
  }
  return std::sqrt(sum);
}

// Time for the block: the CL feed along the tip's path, or longer where an axis would
// exceed its max_feed, measured on the rounded words the control will read.
double PostProcessor::block_minutes(const Placed& a, const Placed& b) const {
  const double tip = std::hypot(b.pose.tip[0] - a.pose.tip[0], b.pose.tip[1] - a.pose.tip[1],
                                b.pose.tip[2] - a.pose.tip[2]);
  double minutes = tip / b.pose.feed;
  for (std::size_t i = 0; i < 6; ++i) {
    const auto& axis = machine_->axes[i];
    const double delta = std::abs(rounded(b.joints[i], i) - rounded(a.joints[i], i));
    if (axis && delta > 0.0) {
      minutes = std::max(minutes, delta / axis->max_feed);
    }
  }
  return minutes;
}

Expected<void> PostProcessor::add(const cl::ClPose& pose) {
  ++stats_.poses;
  if (!last_) {
    if (!start_) {
      SUBFEED_TRY_ASSIGN(const auto options, tracker_.start_candidates(pose));
      start_ = tracker_.prefer(options);
    }
    tracker_.start_at(*start_);
    const Placed first{pose, *start_};
    SUBFEED_TRY(position(first, pose.kind != cl::MoveKind::rapid));
    last_ = first;
    return {};
  }
  SUBFEED_TRY_ASSIGN(const auto step, tracker_.step(pose));
  const Placed next{pose, step.joints};
  if (step.in_cone) {
    ++stats_.cone_poses;
    stats_.max_axis_hold = std::max(stats_.max_axis_hold,
                                    angle_deg(kinematics_->forward(step.joints).axis, pose.axis));
  }
  if (pose.kind == cl::MoveKind::rapid) {
    SUBFEED_TRY(position(next, false));
  } else if (step.reposition) {
    ++stats_.repositions;
    SUBFEED_TRY(retract(*last_));
    // Back along the segment from the new joints, so that the cut from `again` to `next`
    // needs no turn of the branch a reposition exists to avoid.
    const Placed again{last_->pose,
                       tracker_.follow(step.joints, {last_->pose.tip, last_->pose.axis})};
    SUBFEED_TRY(position(again, true));
    SUBFEED_TRY(cut_segment(again, next, false));
  } else {
    SUBFEED_TRY(cut_segment(*last_, next, false));
  }
  last_ = next;
  return {};
}

Expected<void> PostProcessor::finish() {
  if (last_ && last_->pose.kind != cl::MoveKind::rapid) {
    return retract(*last_);
  }
  if (last_) {
    return up_to_safe_z(last_->pose.line);
  }
  return {};
}

} // namespace subfeed::post

#include "post/program_check.hpp"

#include "angles.hpp"
#include "cl/cl_reader.hpp"
#include "gcode/words.hpp"
#include "post/kinematics.hpp"
#include "post/post_file.hpp"
#include "vector_math.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace subfeed::post {

namespace {

void note(Finding& finding, double value, long line) {
  if (value > finding.value) {
    finding = {value, line};
  }
}
void count(long& counter, Finding& first, double value, long line) {
  if (counter++ == 0) {
    first = {value, line};
  }
}

struct Mode {
  bool rapid = true;
  bool inverse_time = false;
  bool tcp = false;
  bool vector = false;
  double feed = 0.0;
};

// One line of the trace map: which CL line a G-code line serves.
struct MapEntry {
  long cl_line = 0;
  bool cut = false;
};

class Replay {
public:
  Replay(const MachineConfig& machine, const CheckOptions& options)
      : machine_(machine), options_(options), kinematics_(make_kinematics(machine)) {}

  Expected<void> open_cl() {
    if (options_.cl) {
      SUBFEED_TRY_ASSIGN(auto reader, cl::ClReader::open(*options_.cl));
      cl_.emplace(std::move(reader));
    }
    return {};
  }

  Expected<void> line(std::string_view text, long number, const MapEntry& map) {
    ++report.lines;
    line_ = number;
    const auto trimmed = text.substr(0, text.find_last_not_of(" \r") + 1);
    if (trimmed.empty() || trimmed.front() == 'O' || trimmed == "%") {
      return {};
    }
    SUBFEED_TRY_ASSIGN(const auto words, gcode::split_words(text));
    Target target;
    SUBFEED_TRY(apply(words, target));
    if (!target.moves) {
      return {};
    }
    return motion(target, map);
  }

  CheckReport report;

private:
  struct Target {
    std::array<std::optional<double>, 6> axes{};
    std::optional<Vec3> vector;
    bool moves = false;
  };

  std::unexpected<Error> error(std::string message) const {
    return fail(ErrorCode::bad_input, std::move(message), {{}, static_cast<int>(line_), {}});
  }

  Expected<void> g_word(double value) {
    const int code = static_cast<int>(std::lround(value * 10));
    switch (code) {
    case 0:
      mode_.rapid = true;
      return {};
    case 10:
      mode_.rapid = false;
      return {};
    case 930:
      mode_.inverse_time = true;
      return {};
    case 940:
      mode_.inverse_time = false;
      return {};
    case 434:
      mode_.tcp = true;
      mode_.vector = false;
      return {};
    case 435:
      mode_.tcp = true;
      mode_.vector = true;
      return {};
    case 490:
      mode_.tcp = false;
      return {};
    case 170:
    case 210:
    case 400:
    case 640:
    case 800:
    case 900:
      return {};
    default:
      break;
    }
    std::ostringstream message;
    message << "G" << value << " is not understood by check (arcs, cycles, inches and "
            << "incremental moves are not replayed)";
    return error(message.str());
  }

  Expected<void> apply(const std::vector<gcode::Word>& words, Target& target) {
    for (const auto& w : words) {
      const auto axis = axis_letters.find(w.letter);
      if (w.letter == 'G') {
        SUBFEED_TRY(g_word(w.value));
      } else if (axis != std::string_view::npos) {
        if (!machine_.axes[axis]) {
          return error(std::string("the machine has no ") + w.letter + " axis");
        }
        target.axes[axis] = w.value;
        target.moves = true;
      } else if (w.letter == 'I' || w.letter == 'J' || w.letter == 'K') {
        if (!target.vector) {
          target.vector = tool_vector_;
        }
        (*target.vector)[static_cast<std::size_t>(w.letter - 'I')] = w.value;
        target.moves = true;
      } else if (w.letter == 'F') {
        mode_.feed = w.value;
      }
    }
    return {};
  }

  // Machine joints for a block under tool-centre-point control: the tip comes from X Y Z,
  // the axis from the angles (G43.4) or from I J K (G43.5).
  JointPosition tcp_joints(const Target& target) {
    for (std::size_t i = 0; i < 3; ++i) {
      if (target.axes[i]) {
        tip_[i] = *target.axes[i];
      }
    }
    JointPosition angles = joints_;
    for (std::size_t r = 3; r < 6; ++r) {
      if (target.axes[r]) {
        angles[r] = *target.axes[r];
      }
    }
    Vec3 axis = kinematics_->forward(angles).axis;
    if (mode_.vector && target.vector) {
      tool_vector_ = *target.vector;
      const double n = std::sqrt(dot(tool_vector_, tool_vector_));
      axis = {tool_vector_[0] / n, tool_vector_[1] / n, tool_vector_[2] / n};
    }
    JointPosition best = angles;
    double best_distance = 1e300;
    for (auto j : kinematics_->inverse({tip_, axis}, angles)) {
      double d = 0.0;
      for (std::size_t r = 3; r < 6; ++r) {
        j[r] += 360.0 * std::round((angles[r] - j[r]) / 360.0);
        d += std::abs(j[r] - angles[r]);
      }
      if (d < best_distance) {
        best = j;
        best_distance = d;
      }
    }
    return best;
  }

  void check_limits(const JointPosition& j) {
    for (std::size_t i = 0; i < j.size(); ++i) {
      const auto& axis = machine_.axes[i];
      if (axis && known_[i] && !axis->cyclic &&
          (j[i] < axis->min - 1e-6 || j[i] > axis->max + 1e-6)) {
        count(report.limit_violations, report.first_limit_violation, j[i], line_);
      }
    }
  }

  Expected<void> motion(const Target& target, const MapEntry& map) {
    ++report.motion_blocks;
    const JointPosition from = joints_;
    const Vec3 from_tip = tip_;
    JointPosition to = mode_.tcp ? tcp_joints(target) : joints_;
    for (std::size_t i = 0; i < 6; ++i) {
      if (target.axes[i] && !mode_.tcp) {
        to[i] = *target.axes[i];
      }
      known_[i] = known_[i] || target.axes[i].has_value() || (mode_.tcp && i < 3);
    }
    joints_ = to;
    if (!mode_.tcp) {
      tip_ = kinematics_->forward(to).tip;
    }
    check_limits(to);
    const bool all_known = std::ranges::all_of(
        std::array{0, 1, 2}, [&](int i) { return known_[static_cast<std::size_t>(i)]; });
    if (!all_known) {
      return {};
    }
    if (mode_.rapid) {
      if (options_.on_pose) {
        for (const auto& p : poses_between(from, from_tip, to)) {
          options_.on_pose(p, line_, true);
        }
      }
      return {};
    }
    return feed_block(from, from_tip, to, map);
  }

  // How many points a block is sampled at: samples_per_block, and for a caller of on_pose
  // one each half degree a rotary axis turns.
  [[nodiscard]] int sample_count(const JointPosition& from, const JointPosition& to) const {
    int n = options_.samples_per_block;
    if (options_.on_pose) {
      for (std::size_t r = 3; r < 6; ++r) {
        n = std::max(n, static_cast<int>(std::ceil(std::abs(to[r] - from[r]) / 0.5)));
      }
    }
    return n;
  }

  // The tool's poses at t = k / n, k = 1..n, along the block.
  [[nodiscard]] std::vector<ToolPose> poses_between(const JointPosition& from, const Vec3& from_tip,
                                                    const JointPosition& to) const {
    const int n = sample_count(from, to);
    std::vector<ToolPose> out;
    for (int k = 1; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      ToolPose p = kinematics_->forward(lerp(from, to, t));
      if (mode_.tcp) {
        for (std::size_t i = 0; i < 3; ++i) {
          p.tip[i] = from_tip[i] + t * (tip_[i] - from_tip[i]);
        }
      }
      out.push_back(p);
    }
    return out;
  }

  double block_minutes(const JointPosition& from, const Vec3& from_tip,
                       const JointPosition& to) const {
    if (mode_.inverse_time) {
      return 1.0 / mode_.feed;
    }
    if (mode_.tcp) {
      return distance(from_tip, tip_) / mode_.feed;
    }
    const double linear = std::hypot(to[0] - from[0], to[1] - from[1], to[2] - from[2]);
    if (linear > no_motion) {
      return linear / mode_.feed;
    }
    return std::hypot(to[3] - from[3], to[4] - from[4], to[5] - from[5]) / mode_.feed;
  }

  Expected<void> feed_block(const JointPosition& from, const Vec3& from_tip,
                            const JointPosition& to, const MapEntry& map) {
    ++report.feed_blocks;
    if (mode_.feed <= 0.0) {
      return error("feed move without a feed rate (F)");
    }
    const double minutes = block_minutes(from, from_tip, to);
    report.cutting_minutes += minutes;
    for (std::size_t i = 0; i < 6; ++i) {
      const double delta = std::abs(to[i] - from[i]);
      if (is_rotary_axis(i) && delta > 180.0) {
        count(report.rotary_jumps, report.first_rotary_jump, delta, line_);
      }
      if (is_rotary_axis(i) && machine_.axes[i]) {
        note(report.rotary_step[i - 3], delta, line_);
      }
      const auto& axis = machine_.axes[i];
      // Under G43.5 the control derives the angles from the rounded I J K, which near the
      // pole moves C a little differently from the post's exact axis: allow 2 % there.
      const double slack = mode_.tcp && mode_.vector ? 2e-2 : 1e-3;
      if (axis && minutes > 0.0 && delta / minutes > axis->max_feed * (1 + slack) + 1e-6) {
        count(report.over_feed, report.first_over_feed, delta / minutes, line_);
      }
    }
    SUBFEED_TRY(sample(from, from_tip, to, minutes, map));
    return {};
  }

  Expected<void> advance_cl(long cl_line) {
    while (!cur_ || cur_->line < cl_line) {
      SUBFEED_TRY_ASSIGN(auto pose, cl_->next());
      if (!pose) {
        return error("the trace map names CL line " + std::to_string(cl_line) +
                     ", past the end of the CL data");
      }
      prev_ = cur_;
      cur_ = *pose;
    }
    if (cur_->line != cl_line) {
      return error("the trace map names CL line " + std::to_string(cl_line) +
                   ", which holds no pose: map and CL data do not belong together");
    }
    return {};
  }

  Expected<void> sample(const JointPosition& from, const Vec3& from_tip, const JointPosition& to,
                        double minutes, const MapEntry& map) {
    const bool compare = cl_ && map.cut;
    if (compare) {
      SUBFEED_TRY(advance_cl(map.cl_line));
      ++report.cut_blocks_compared;
    }
    const cl::ClPose& b = compare ? *cur_ : cl::ClPose{};
    const cl::ClPose& a = compare && prev_ ? *prev_ : b;
    double length = 0.0;
    Vec3 last = from_tip;
    for (const auto& p : poses_between(from, from_tip, to)) {
      length += distance(last, p.tip);
      last = p.tip;
      if (compare) {
        measure(p.tip, p.axis, a, b);
      }
      if (options_.on_pose) {
        options_.on_pose(p, line_, false);
      }
    }
    if (minutes > 0.0) {
      note(report.max_tip_feed, length / minutes, line_);
    }
    return {};
  }

  void measure(const Vec3& tip, const Vec3& axis, const cl::ClPose& a, const cl::ClPose& b) {
    const Vec3 ab{b.tip[0] - a.tip[0], b.tip[1] - a.tip[1], b.tip[2] - a.tip[2]};
    const Vec3 ap{tip[0] - a.tip[0], tip[1] - a.tip[1], tip[2] - a.tip[2]};
    const double len2 = dot(ab, ab);
    const double s = len2 > 0.0 ? std::clamp(dot(ap, ab) / len2, 0.0, 1.0) : 1.0;
    const Vec3 nearest{a.tip[0] + s * ab[0], a.tip[1] + s * ab[1], a.tip[2] + s * ab[2]};
    note(report.tip_deviation, distance(tip, nearest), line_);
    // Where along the segment the tool is, is known only to the tip's tolerance: on a short
    // segment whose axis turns (a lean eased, the pole), that is a wide range of axes. The
    // axis is held to the nearest of them.
    const double spread = len2 > 0.0 ? options_.tolerance / std::sqrt(len2) : 0.0;
    double least = 1e300;
    constexpr int tries = 8;
    for (int k = 0; k <= tries; ++k) {
      const double u = std::clamp(s + spread * (2.0 * k / tries - 1.0), 0.0, 1.0);
      least = std::min(least, angle_deg(axis, slerp(a.axis, b.axis, u)));
    }
    note(report.axis_deviation, least, line_);
  }

  const MachineConfig& machine_;
  const CheckOptions& options_;
  std::unique_ptr<Kinematics> kinematics_;
  std::optional<cl::ClReader> cl_;
  std::optional<cl::ClPose> prev_, cur_;
  Mode mode_;
  JointPosition joints_{};
  std::array<bool, 6> known_{false, false, false, true, true, true};
  Vec3 tip_{};
  Vec3 tool_vector_{0, 0, 1};
  long line_ = 0;
};

Expected<MapEntry> read_map_line(std::ifstream& map, long nc_line, const std::string& file) {
  std::string text;
  while (std::getline(map, text)) {
    if (text.empty() || text.front() == '#') {
      continue;
    }
    std::istringstream in(text);
    long n = 0;
    MapEntry entry;
    std::string kind;
    if (!(in >> n >> entry.cl_line >> kind) || n != nc_line || (kind != "cut" && kind != "link")) {
      return fail(ErrorCode::bad_input,
                  "trace map does not match the program at G-code line " + std::to_string(nc_line),
                  {file, 0, {}});
    }
    entry.cut = kind == "cut";
    return entry;
  }
  return fail(ErrorCode::bad_input, "trace map ends before the program", {file, 0, {}});
}

} // namespace

bool CheckReport::passed(double tolerance) const {
  return tip_deviation.value <= tolerance && axis_deviation.value <= allowed_axis_deviation &&
         limit_violations == 0 && rotary_jumps == 0 && over_feed == 0;
}

Expected<CheckReport> check_program(const std::filesystem::path& program,
                                    const MachineConfig& machine, const CheckOptions& options) {
  std::ifstream in(program, std::ios::binary);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot open G-code program", {program.string(), 0, {}});
  }
  std::ifstream map;
  const auto map_path = map_path_for(program);
  if (options.cl) {
    map.open(map_path);
    if (!map) {
      return fail(ErrorCode::bad_input,
                  "comparing with CL data needs the trace map subfeed post writes beside the "
                  "program",
                  {map_path.string(), 0, {}});
    }
  }
  Replay replay(machine, options);
  SUBFEED_TRY(replay.open_cl());
  std::string text;
  long number = 0;
  while (std::getline(in, text)) {
    ++number;
    MapEntry entry;
    if (options.cl) {
      SUBFEED_TRY_ASSIGN(entry, read_map_line(map, number, map_path.string()));
    }
    if (auto done = replay.line(text, number, entry); !done) {
      auto error = std::move(done).error();
      if (error.where.file.empty()) {
        error.where = {program.string(), static_cast<int>(number), {}};
      }
      return std::unexpected(std::move(error));
    }
  }
  replay.report.allowed_axis_deviation =
      std::max(options.axis_tolerance, machine.post.singularity_cone) + 1e-9;
  return replay.report;
}

} // namespace subfeed::post

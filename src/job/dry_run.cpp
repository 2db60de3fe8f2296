#include "job/dry_run.hpp"

#include "drivers/gcode_line.hpp"
#include "post/program_check.hpp"
#include "sim/delivery_hash.hpp"

#include <fmt/format.h>
#include <fstream>
#include <thread>

namespace subfeed::job {

namespace {

struct Delivery {
  long count = 0;
  std::uint64_t hash = sim::delivery_hash_seed;
};

// What a controller would have run of the program file: GRBL lines as the sender prepares
// them; Fanuc blocks as written, without the '%' framing and the O-number line.
Expected<Delivery> expected_delivery(const std::filesystem::path& nc, bool fanuc, int line_limit) {
  std::ifstream in(nc, std::ios::binary);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot read the posted program", {nc.string(), 0, {}});
  }
  Delivery d;
  std::string raw;
  bool numbered = false;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    std::string text;
    if (fanuc) {
      while (!raw.empty() && (raw.back() == '\r' || raw.back() == ' ')) {
        raw.pop_back();
      }
      if (raw.empty() || raw == "%" || (!numbered && (raw.front() == 'O' || raw.front() == ':'))) {
        numbered = numbered || (!raw.empty() && raw != "%");
        continue;
      }
      text = raw;
    } else {
      SUBFEED_TRY_ASSIGN(auto prepared,
                         drivers::prepare_line(raw, {line_limit, false}, {nc.string(), line, {}}));
      text = std::move(prepared.text);
      if (text.empty()) {
        continue;
      }
    }
    ++d.count;
    d.hash = sim::delivery_hash(d.hash, text);
  }
  return d;
}

// The control's account once it has read the whole tape: the sender is done when the last
// character has left, but a control thread that ran late still has some on the wire. It
// is waited for while it keeps taking blocks, up to 60 s without one (a long move at a slow
// --sim-speed holds the last blocks back).
sim::FanucSimStats settled(const sim::FanucSim& control) {
  using namespace std::chrono_literals;
  auto stats = control.stats();
  auto last_progress = std::chrono::steady_clock::now();
  while (!stats.program_ended && stats.alarm.empty() &&
         std::chrono::steady_clock::now() - last_progress < 60s) {
    std::this_thread::sleep_for(20ms);
    const auto now = control.stats();
    if (now.blocks_received != stats.blocks_received) {
      last_progress = std::chrono::steady_clock::now();
    }
    stats = now;
  }
  return stats;
}

std::string at(const post::Finding& f) {
  return f.line > 0 ? fmt::format(" (line {})", f.line) : "";
}

} // namespace

Expected<void> verify_dry_run(const Link& link, const DryRunFiles& files,
                              const post::MachineConfig& machine, double tolerance_mm,
                              Logger& log) {
  const bool fanuc = link.control != nullptr;
  Delivery ran;
  if (fanuc) {
    const auto s = settled(*link.control);
    ran = {s.executed_count, s.executed_hash};
  } else if (link.simulator) {
    const auto s = link.simulator->stats();
    ran = {s.executed_count, s.executed_hash};
  } else {
    return {};
  }
  SUBFEED_TRY_ASSIGN(const auto posted,
                     expected_delivery(files.nc, fanuc, machine.controller.line_length));
  const bool delivered = ran.count == posted.count && ran.hash == posted.hash;
  log.info(fmt::format("dry run: the simulated {} executed {} of {} posted blocks{}",
                       fanuc ? "control" : "controller", ran.count, posted.count,
                       delivered ? ", exactly as posted (hash equal)" : ", NOT as posted"));
  post::CheckOptions options;
  options.tolerance = tolerance_mm;
  options.cl = files.cl;
  SUBFEED_TRY_ASSIGN(const auto r, post::check_program(files.nc, machine, options));
  log.info(fmt::format(
      "  replayed through the {} kinematics: tool tip within {:.6f} mm of the CL "
      "path{} (tolerance {} mm), tool axis within {:.4f} deg{}; limit "
      "violations {}{}, rotary jumps {}{}, blocks over an axis max feed {}{}",
      post::to_string(machine.kinematics), r.tip_deviation.value, at(r.tip_deviation), tolerance_mm,
      r.axis_deviation.value, at(r.axis_deviation), r.limit_violations, at(r.first_limit_violation),
      r.rotary_jumps, at(r.first_rotary_jump), r.over_feed, at(r.first_over_feed)));
  if (!delivered) {
    return fail(ErrorCode::machine_fault,
                fmt::format("dry run: the controller ran {} blocks that differ from the {} "
                            "posted",
                            ran.count, posted.count),
                {files.nc.string(), 0, {}});
  }
  if (!r.passed(tolerance_mm)) {
    return fail(ErrorCode::bad_input, "dry run: the replay failed, see the report above",
                {files.nc.string(), 0, {}});
  }
  return {};
}

} // namespace subfeed::job

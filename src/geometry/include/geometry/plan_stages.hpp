#pragma once
// The stages a plan goes through, what a caller hears as it enters each one (for a progress
// line), and how long each took (for a summary of where the time went). Times are wall-clock
// seconds of this plan's own thread.

#include "geometry/deformation.hpp"

#include <array>
#include <chrono>
#include <functional>
#include <string_view>

namespace subfeed::geometry {

enum class PlanStage {
  meshing,     // the limit surface meshed within the chordal tolerance
  gate_mesh,   // the motion gate's own, finer mesh
  reach,       // balls lifted clear, and what the tool cannot get to (tool_reach.hpp)
  directions,  // pricing the feed directions (--direction auto)
  deformation, // the deformation solves
  clearing,    // what the balls leave in hollows narrower than them
  slicing,     // cutting the planes, linking the passes (with the gate checks and the sink)
};
inline constexpr std::size_t plan_stage_count = 7;

[[nodiscard]] std::string_view stage_name(PlanStage stage);

struct PlanTimes {
  std::array<double, plan_stage_count> stage_s{}; // by PlanStage
  double gate_checks_s = 0.0;                     // of slicing: every pose through the motion gate
  double sink_s = 0.0; // of slicing: handing poses on (writing, posting, streaming)
  double links_s = 0.0; // of slicing: links routed clear of the part (stay-down, climbs)

  [[nodiscard]] double& operator[](PlanStage s) { return stage_s[static_cast<std::size_t>(s)]; }
  [[nodiscard]] double operator[](PlanStage s) const {
    return stage_s[static_cast<std::size_t>(s)];
  }
  [[nodiscard]] double total_s() const;
};

// What prepare() tells as it goes: the stage it enters, the share of it done so far (0..1,
// for an ETA; not every stage tells one), and each deformation solve. All are called on the
// thread that called prepare().
struct PlanObserver {
  std::function<void(PlanStage)> stage;
  SolveProgress solve;
  std::function<void(double)> share;
};

// Adds the time from construction to destruction to one figure.
class StageClock {
public:
  explicit StageClock(double& seconds)
      : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~StageClock() {
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;

private:
  double& seconds_;
  std::chrono::steady_clock::time_point start_;
};

} // namespace subfeed::geometry

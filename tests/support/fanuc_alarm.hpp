#pragma once
// The alarm a simulated Fanuc control shows, waited for: its reader runs on its own thread,
// so an alarm raised by what a test just wrote appears a little later.

#include "sim/fanuc_sim.hpp"

#include <chrono>
#include <string>

namespace subfeed::testing {

// The control's alarm once it shows one, or empty after `timeout`.
[[nodiscard]] std::string alarm_within(const sim::FanucSim& control,
                                       std::chrono::milliseconds timeout);

} // namespace subfeed::testing

#pragma once
// A post stand-in for live programs: writes lines into a program queue from its own thread,
// with one long pause, as a planner working on a hard stretch would.

#include "drivers/live_program.hpp"

#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace subfeed::testing {

// Pushes `program`'s lines in order, pausing `pause` before line index `pause_after`, then
// closes the queue. Ends early when the reader closes the queue or the thread is stopped (its
// destructor stops it, so a test never waits out the pause).
[[nodiscard]] std::jthread write_slowly(drivers::ProgramQueue& queue,
                                        std::vector<std::string> program, std::size_t pause_after,
                                        std::chrono::milliseconds pause);

} // namespace subfeed::testing

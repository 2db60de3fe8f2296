#pragma once
// The GRBL 1.1 error and alarm codes the simulated controller answers with: documented
// protocol constants, in one place for the simulator's line handling and its G-code
// interpreter, and kept apart from the sender's table on purpose (a simulator sharing the
// sender's reading of a code would agree with its mistakes). Internal to the simulator.

namespace subfeed::sim::grbl_code {

constexpr int expected_command_letter = 1;
constexpr int bad_number_format = 2;
constexpr int invalid_statement = 3;
constexpr int homing_disabled = 5;
constexpr int not_idle = 8;
constexpr int locked = 9;
constexpr int line_overflow = 11;
constexpr int unsupported_command = 20;
constexpr int modal_group_violation = 21;
constexpr int undefined_feed_rate = 22;
constexpr int command_not_integer = 23;
constexpr int word_repeated = 25;
constexpr int invalid_target = 33;

constexpr int alarm_reset_in_motion = 3;

} // namespace subfeed::sim::grbl_code

#pragma once
// How a subcommand plugs into the front: it registers its options on the CLI11 app and
// returns the action to run once parsing succeeded. Actions report through the Logger and
// return an Error for main to print as one line and turn into the exit code.

#include "base/error.hpp"
#include "job/logger.hpp"

#include <functional>

namespace CLI {
class App;
}

namespace subfeed::cli {

// The front reports through the job library's Logger.
using job::Logger;
using job::Verbosity;

using Action = std::function<Expected<void>(Logger&)>;

// Each adds one subcommand to `app`; when the user picks it, `chosen` is set to its action.
void add_inspect_command(CLI::App& app, Action& chosen);
void add_config_command(CLI::App& app, Action& chosen);
void add_send_command(CLI::App& app, Action& chosen);
void add_ports_command(CLI::App& app, Action& chosen);
void add_post_command(CLI::App& app, Action& chosen);
void add_check_command(CLI::App& app, Action& chosen);
void add_plan_command(CLI::App& app, Action& chosen);
void add_verify_command(CLI::App& app, Action& chosen);
void add_run_command(CLI::App& app, Action& chosen);
void add_resume_command(CLI::App& app, Action& chosen);

} // namespace subfeed::cli

// The subfeed command-line front: parses the command line with CLI11, runs the chosen
// subcommand and turns its result into one line and an exit code (0 done, 1 usage, 2 bad
// input, 3 machine or link fault, 4 stopped by user). The only place that may throw.

#include "command.hpp"
#include "job/logger.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <exception>
#include <iostream>

namespace {

struct GlobalOptions {
  bool verbose = false;
  bool quiet = false;
  std::string log_file;
};

void add_global_options(CLI::App& app, GlobalOptions& options) {
  app.set_version_flag("--version", std::string("subfeed ") + SUBFEED_VERSION);
  auto* verbose = app.add_flag("-v,--verbose", options.verbose, "Say more about what happens");
  app.add_flag("--quiet", options.quiet, "Print nothing but errors and warnings")
      ->excludes(verbose);
  app.add_option("--log", options.log_file, "Append a timestamped log of everything to FILE")
      ->type_name("FILE");
}

int run(int argc, char** argv) {
  CLI::App app{"subfeed: constant-scallop multi-axis finishing paths from Catmull-Clark cages,\n"
               "post-processed for one machine and drip-fed to its controller.",
               "subfeed"};
  GlobalOptions options;
  add_global_options(app, options);
  app.require_subcommand(1);
  app.fallthrough();
  subfeed::cli::Action chosen;
  subfeed::cli::add_inspect_command(app, chosen);
  subfeed::cli::add_plan_command(app, chosen);
  subfeed::cli::add_run_command(app, chosen);
  subfeed::cli::add_resume_command(app, chosen);
  subfeed::cli::add_verify_command(app, chosen);
  subfeed::cli::add_config_command(app, chosen);
  subfeed::cli::add_send_command(app, chosen);
  subfeed::cli::add_ports_command(app, chosen);
  subfeed::cli::add_post_command(app, chosen);
  subfeed::cli::add_check_command(app, chosen);
  // An unknown command would otherwise read "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    const auto commands = app.get_subcommands([](CLI::App*) { return true; });
    if (std::ranges::none_of(commands, [&](CLI::App* c) { return c->get_name() == argv[1]; })) {
      std::cerr << "subfeed: usage: unknown command '" << argv[1] << "' (see subfeed --help)"
                << std::endl;
      return 1;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      return app.exit(e); // --help, --version
    }
    std::cerr << "subfeed: usage: " << e.what() << " (see subfeed --help)" << std::endl;
    return subfeed::exit_code(subfeed::ErrorCode::usage);
  }
  using subfeed::cli::Verbosity;
  const Verbosity verbosity =
      options.quiet ? Verbosity::quiet : (options.verbose ? Verbosity::verbose : Verbosity::normal);
  subfeed::cli::Logger logger(verbosity, std::cout, std::cerr);
  if (!options.log_file.empty()) {
    if (auto opened = logger.open_log(options.log_file); !opened) {
      logger.error(opened.error());
      return subfeed::exit_code(opened.error().code);
    }
  }
  if (auto result = chosen(logger); !result) {
    logger.error(result.error());
    return subfeed::exit_code(result.error().code);
  }
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  // A closed stdout (`subfeed send --json | head -1`) must not kill a sender mid-job with
  // the machine running: writes to it just fail instead.
  std::signal(SIGPIPE, SIG_IGN);
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "subfeed: internal error: " << e.what() << std::endl;
    return subfeed::exit_code(subfeed::ErrorCode::bad_input);
  }
}

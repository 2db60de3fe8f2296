// subfeed-sim: simulated controllers on a pty, for dry runs and tests. Each protocol is a
// subcommand; the pty's slave path is printed on stdout and the simulator serves until it
// is killed.

#include <CLI/CLI.hpp>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"subfeed-sim: a simulated machine controller on a pseudo-terminal", "subfeed-sim"};
  app.set_version_flag("--version", std::string("subfeed-sim ") + SUBFEED_VERSION);
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      return app.exit(e);
    }
    std::cerr << "subfeed-sim: usage: " << e.what() << " (see subfeed-sim --help)" << std::endl;
    return 1;
  }
  return 0;
}

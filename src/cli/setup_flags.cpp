#include "setup_flags.hpp"

#include "base/number_text.hpp"

#include <CLI/CLI.hpp>

namespace subfeed::cli {

namespace {

// A refusal CLI11 prints as "--up: up axis 'w' is not x, y, z, -x, -y or -z".
template <class T> T accepted(const char* flag, Expected<T> value) {
  if (!value) {
    throw CLI::ValidationError(flag, value.error().message);
  }
  return *value;
}

} // namespace

void add_setup_flags(CLI::App& cmd, job::SetupFlags& flags) {
  cmd.add_option_function<std::string>(
         "--up",
         [&flags](const std::string& word) {
           flags.up = accepted("--up", geometry::parse_up_axis(word));
         },
         "The model's axis that points up, toward the spindle: x, y, z, -x, -y or -z (default z)")
      ->type_name("AXIS");
  auto* units = cmd.add_option_function<std::string>(
                       "--units",
                       [&flags](const std::string& word) {
                         flags.scale = accepted("--units", geometry::parse_units(word));
                       },
                       "The model's unit: mm, cm, m or in (default mm)")
                    ->type_name("UNIT");
  cmd.add_option_function<std::string>(
         "--scale",
         [&flags](const std::string& text) {
           const auto problem = positive_number_problem(text, false);
           if (!problem.empty()) {
             throw CLI::ValidationError("--scale", problem);
           }
           flags.scale = parse_double(text).value_or(1.0);
         },
         "Millimetres per model unit, for a unit --units does not name")
      ->type_name("F")
      ->excludes(units);
  cmd.add_option_function<std::string>(
         "--origin",
         [&flags](const std::string& word) {
           geometry::PartSetup origin;
           if (auto ok = geometry::parse_origin(word, origin); !ok) {
             throw CLI::ValidationError("--origin", ok.error().message);
           }
           flags.origin = origin;
         },
         "Where the program's zero sits on the part: top-centre, bottom-centre, min-corner, "
         "model (the model's own zero, the default) or X,Y,Z in mm")
      ->type_name("WHERE");
}

} // namespace subfeed::cli

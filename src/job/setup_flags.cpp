#include "job/setup_flags.hpp"

#include <cmath>
#include <fmt/format.h>

namespace subfeed::job {

geometry::PartSetup SetupFlags::with_defaults() const {
  geometry::PartSetup s;
  s.up = up.value_or(s.up);
  s.scale = scale.value_or(s.scale);
  if (origin) {
    s.origin = origin->origin;
    s.origin_point = origin->origin_point;
  }
  return s;
}

Expected<geometry::PartSetup> agreed_setup(const SetupFlags& said, const std::string& recorded,
                                           const std::string& recorded_in) {
  if (recorded.empty()) {
    return said.with_defaults();
  }
  auto kept = geometry::parse_setup_text(recorded);
  if (!kept) {
    return fail(ErrorCode::bad_input, "setup '" + recorded + "': " + kept.error().message,
                {recorded_in, 0, {}});
  }
  const auto differs = [&](std::string_view flag) {
    return fail(ErrorCode::bad_input,
                fmt::format("disagrees with the setup the part was planned in ({}): leave it out "
                            "or give the same",
                            geometry::setup_text(*kept)),
                {recorded_in, 0, std::string(flag)});
  };
  if (said.up && *said.up != kept->up) {
    return differs("--up");
  }
  if (said.scale && std::abs(*said.scale - kept->scale) > 1e-12 * kept->scale) {
    return differs("--units/--scale");
  }
  if (said.origin &&
      (said.origin->origin != kept->origin || said.origin->origin_point != kept->origin_point)) {
    return differs("--origin");
  }
  return *kept;
}

Expected<geometry::Cage> read_part_agreed(const std::filesystem::path& cage, const SetupFlags& said,
                                          const std::string& recorded,
                                          const std::string& recorded_in) {
  SUBFEED_TRY_ASSIGN(const auto setup, agreed_setup(said, recorded, recorded_in));
  return geometry::read_part(cage, setup);
}

} // namespace subfeed::job

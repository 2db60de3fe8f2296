#pragma once
// What a command line says of the part's setup (--up, --units or --scale, --origin), each
// field only if given, and how that meets a setup a CL file or job record already keeps:
// a command never silently uses a setup other than the one its CL data was planned in.

#include "base/error.hpp"
#include "geometry/part_setup.hpp"

#include <filesystem>
#include <optional>
#include <string>

namespace subfeed::job {

struct SetupFlags {
  std::optional<geometry::UpAxis> up = std::nullopt;
  std::optional<double> scale = std::nullopt; // mm per model unit, from --units or --scale
  // Only its origin and origin_point are said.
  std::optional<geometry::PartSetup> origin = std::nullopt;

  [[nodiscard]] bool any() const { return up || scale || origin; }
  // The said fields over the defaults (up z, scale 1, the model's zero).
  [[nodiscard]] geometry::PartSetup with_defaults() const;
};

// The setup a command uses when its input records one (`recorded`, setup text, from
// `recorded_in`, a file): the recorded one, refused with the flag named when a said field
// differs. With nothing recorded (CL data from elsewhere, or older): the flags'.
[[nodiscard]] Expected<geometry::PartSetup>
agreed_setup(const SetupFlags& said, const std::string& recorded, const std::string& recorded_in);

// The cage, read and set up as agreed_setup() says.
[[nodiscard]] Expected<geometry::Cage> read_part_agreed(const std::filesystem::path& cage,
                                                        const SetupFlags& said,
                                                        const std::string& recorded,
                                                        const std::string& recorded_in);

} // namespace subfeed::job

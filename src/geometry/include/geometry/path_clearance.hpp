#pragma once
// The whole tool's clearance over a CL path, for `verify`: every move swept as the motion
// gate sweeps it (assembly_sweep.hpp), on a mesh of its own within 5 um of the limit surface,
// but measured on past a broken rule, and with distances searched out to 5 mm beyond
// clearance_min (the gate looks only 1 mm out).

#include "base/error.hpp"
#include "geometry/assembly_clearance.hpp"
#include "geometry/cage.hpp"
#include "geometry/limit_surface.hpp"

#include <filesystem>
#include <optional>
#include <vector>

namespace subfeed::geometry {

struct PathClearance {
  std::vector<BodyClearance> bodies;       // AssemblyClearance::blank() order, the ball first
  double searched_mm = 0.0;                // a body farther than this reads infinity
  long moves = 0;                          // moves swept
  long broken = 0;                         // measured poses that break a rule
  std::optional<ClearanceViolation> first; // the first of them
  long first_line = 0;                     // its move's CL line
};

[[nodiscard]] Expected<PathClearance> path_clearance(const Cage& cage, const LimitSurface& surface,
                                                     const std::filesystem::path& cl_file,
                                                     const ToolAssembly& tool,
                                                     const Fixture& fixture);

} // namespace subfeed::geometry

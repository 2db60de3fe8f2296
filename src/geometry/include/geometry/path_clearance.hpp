#pragma once
// The whole tool's clearance over a path, for `verify` (CL data) and `check --cage` (a
// program replayed through the machine's kinematics): every move swept as the motion gate
// sweeps it (assembly_sweep.hpp), on a mesh of its own within 5 um of the limit surface, but
// measured on past a broken rule, and with distances searched out to 5 mm beyond
// clearance_min (the gate looks only 1 mm out).

#include "base/error.hpp"
#include "geometry/assembly_clearance.hpp"
#include "geometry/cage.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/triangle_tree.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

namespace subfeed::geometry {

struct PathClearance {
  std::vector<BodyClearance> bodies;       // AssemblyClearance::blank() order, the ball first
  double searched_mm = 0.0;                // a body farther than this reads infinity
  long moves = 0;                          // moves swept
  long broken = 0;                         // measured poses that break a rule
  std::optional<ClearanceViolation> first; // the first of them
  long first_line = 0;                     // its move's line (CL data or program)
};

// Sweeps moves one after another and keeps the least clearances.
class ClearanceMeter {
public:
  // With `floor_at_lowest` the fixture's floor is the surface's lowest point (its mesh's).
  [[nodiscard]] static Expected<ClearanceMeter> build(const Cage& cage, const LimitSurface& surface,
                                                      const ToolAssembly& tool, Fixture fixture,
                                                      bool floor_at_lowest = false);
  // The tool moved from (tip, axis) `t0`, `a0` to `t1`, `a1` (mm, unit), the tip straight
  // and the axis turned in their plane; `line` names the move in the report.
  void move(const Eigen::Vector3d& t0, const Eigen::Vector3d& a0, const Eigen::Vector3d& t1,
            const Eigen::Vector3d& a1, long line);
  [[nodiscard]] const ToolAssembly& tool() const { return tool_; }
  [[nodiscard]] const Fixture& fixture() const { return fixture_; }
  [[nodiscard]] const PathClearance& result() const { return out_; }

private:
  ClearanceMeter(std::unique_ptr<const SurfaceMesh> mesh, const ToolAssembly& tool, Fixture fixture,
                 bool floor_at_lowest);

  // On the heap, so that a moved meter's tree and clearance still point at them.
  std::unique_ptr<const SurfaceMesh> mesh_;
  std::unique_ptr<const TriangleTree> tree_;
  std::unique_ptr<const AssemblyClearance> clearance_;
  ToolAssembly tool_;
  Fixture fixture_;
  PathClearance out_;
};

[[nodiscard]] Expected<PathClearance> path_clearance(const Cage& cage, const LimitSurface& surface,
                                                     const std::filesystem::path& cl_file,
                                                     const ToolAssembly& tool,
                                                     const Fixture& fixture);

} // namespace subfeed::geometry

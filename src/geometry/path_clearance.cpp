#include "geometry/path_clearance.hpp"

#include "cl/cl_reader.hpp"
#include "geometry/assembly_sweep.hpp"
#include "geometry/pose_vectors.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/triangle_tree.hpp"

namespace subfeed::geometry {

namespace {

constexpr double clearance_chord_mm = 0.5 * AssemblyClearance::resolution_mm;
constexpr double clearance_searched_beyond_mm = 5.0;
constexpr int clearance_most_segments = 256;

} // namespace

Expected<PathClearance> path_clearance(const Cage& cage, const LimitSurface& surface,
                                       const std::filesystem::path& cl_file,
                                       const ToolAssembly& tool, const Fixture& fixture) {
  SUBFEED_TRY_ASSIGN(const auto mesh, mesh_surface(cage, surface,
                                                   rates_for_tolerance(surface, clearance_chord_mm,
                                                                       clearance_most_segments)));
  const TriangleTree tree(mesh.points, mesh.triangles);
  const AssemblyClearance clearance(tool, fixture, tree);
  SUBFEED_TRY_ASSIGN(auto reader, cl::ClReader::open(cl_file));
  PathClearance out;
  out.bodies = clearance.blank();
  out.searched_mm = fixture.clearance_min + clearance_searched_beyond_mm;
  const SweepOptions options{.cap_mm = clearance_searched_beyond_mm, .stop_at_first = false};
  std::optional<cl::ClPose> last;
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto pose, reader.next());
    if (!pose) {
      break;
    }
    const auto& from = last ? *last : *pose;
    const auto found = sweep_move(clearance, tip_of(from), axis_of(from), tip_of(*pose),
                                  axis_of(*pose), options, &out.bodies);
    ++out.moves;
    out.broken += found.broken;
    if (found.first && !out.first) {
      out.first = found.first;
      out.first_line = pose->line;
    }
    last = pose;
  }
  return out;
}

} // namespace subfeed::geometry

#include "geometry/path_clearance.hpp"

#include "cl/cl_reader.hpp"
#include "geometry/assembly_sweep.hpp"
#include "geometry/pose_vectors.hpp"

namespace subfeed::geometry {

namespace {

constexpr double clearance_chord_mm = 0.5 * AssemblyClearance::resolution_mm;
constexpr double clearance_searched_beyond_mm = 5.0;
constexpr int clearance_most_segments = 256;

} // namespace

ClearanceMeter::ClearanceMeter(std::unique_ptr<const SurfaceMesh> mesh, const ToolAssembly& tool,
                               Fixture fixture, bool floor_at_lowest)
    : mesh_(std::move(mesh)),
      tree_(std::make_unique<const TriangleTree>(mesh_->points, mesh_->triangles)), tool_(tool),
      fixture_(std::move(fixture)) {
  if (floor_at_lowest) {
    fixture_.floor_z = lowest_z(*mesh_);
  }
  clearance_ = std::make_unique<const AssemblyClearance>(tool_, fixture_, *tree_);
  out_.bodies = clearance_->blank();
  out_.searched_mm = fixture_.clearance_min + clearance_searched_beyond_mm;
}

Expected<ClearanceMeter> ClearanceMeter::build(const Cage& cage, const LimitSurface& surface,
                                               const ToolAssembly& tool, Fixture fixture,
                                               bool floor_at_lowest) {
  SUBFEED_TRY_ASSIGN(auto mesh, mesh_surface(cage, surface,
                                             rates_for_tolerance(surface, clearance_chord_mm,
                                                                 clearance_most_segments)));
  return ClearanceMeter(std::make_unique<const SurfaceMesh>(std::move(mesh)), tool,
                        std::move(fixture), floor_at_lowest);
}

void ClearanceMeter::move(const Eigen::Vector3d& t0, const Eigen::Vector3d& a0,
                          const Eigen::Vector3d& t1, const Eigen::Vector3d& a1, long line) {
  const SweepOptions options{.cap_mm = clearance_searched_beyond_mm, .stop_at_first = false};
  const auto found = sweep_move(*clearance_, t0, a0, t1, a1, options, &out_.bodies);
  ++out_.moves;
  out_.broken += found.broken;
  if (found.first && !out_.first) {
    out_.first = found.first;
    out_.first_line = line;
  }
}

Expected<PathClearance> path_clearance(const Cage& cage, const LimitSurface& surface,
                                       const std::filesystem::path& cl_file,
                                       const ToolAssembly& tool, const Fixture& fixture) {
  SUBFEED_TRY_ASSIGN(auto meter, ClearanceMeter::build(cage, surface, tool, fixture));
  SUBFEED_TRY_ASSIGN(auto reader, cl::ClReader::open(cl_file));
  std::optional<cl::ClPose> last;
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto pose, reader.next());
    if (!pose) {
      break;
    }
    const auto& from = last ? *last : *pose;
    meter.move(tip_of(from), axis_of(from), tip_of(*pose), axis_of(*pose), pose->line);
    last = pose;
  }
  return meter.result();
}

} // namespace subfeed::geometry

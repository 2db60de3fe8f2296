// The planner's pieces against exact answers, and whole plans against the independent
// meter (path_verifier) on a grid bowl whose limit surface is z = a x^2 + b y^2 exactly.

#include "cl/cl_writer.hpp"
#include "geometry/deformation.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/mesh_slicer.hpp"
#include "geometry/path_verifier.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/toolpath_planner.hpp"
#include "support/grid_cage.hpp"
#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <map>

using namespace subfeed;
using subfeed::testing::TempDir;

namespace {

geometry::LimitSurface surface_of(const geometry::Cage& cage) {
  auto surface = geometry::LimitSurface::build(cage);
  REQUIRE(surface);
  return std::move(*surface);
}

int nearest_vertex(const geometry::SurfaceMesh& mesh, const Eigen::Vector3d& p) {
  int best = 0;
  for (int i = 1; i < mesh.vertex_count(); ++i) {
    if ((mesh.points[static_cast<std::size_t>(i)] - p).norm() <
        (mesh.points[static_cast<std::size_t>(best)] - p).norm()) {
      best = i;
    }
  }
  return best;
}

} // namespace

TEST_CASE("curvature radii of the exact bowl and saddle at their centre") {
  // z = a x^2 + b y^2 has normal curvature 2a along x and 2b along y at the origin; seen
  // from above a bowl is concave (rho < 0).
  for (const auto& [a, b] : {std::pair{0.02, 0.01}, std::pair{0.02, -0.02}}) {
    const auto cage = subfeed::testing::grid_cage(9, 5.0, a, b);
    const auto surface = surface_of(cage);
    const auto mesh = geometry::mesh_surface(cage, surface, 4);
    REQUIRE(mesh);
    const int centre = nearest_vertex(*mesh, Eigen::Vector3d::Zero());
    REQUIRE(mesh->points[static_cast<std::size_t>(centre)].norm() < 1e-12);
    CHECK(mesh->radius_along(centre, Eigen::Vector3d::UnitX()) ==
          Approx(-1.0 / (2 * a)).epsilon(1e-9));
    CHECK(mesh->radius_along(centre, Eigen::Vector3d::UnitY()) ==
          Approx(-1.0 / (2 * b)).epsilon(1e-9));
  }
}

TEST_CASE("slice points map back exactly: every point lies on its level and its edge") {
  const auto cage = subfeed::testing::grid_cage(5, 5.0, 0.02, 0.01);
  const auto surface = surface_of(cage);
  const auto mesh = geometry::mesh_surface(cage, surface, 6);
  REQUIRE(mesh);
  std::vector<double> values;
  for (const auto& p : mesh->points) {
    values.push_back(p.y() + 0.3 * p.x() * p.x()); // any field will do
  }
  geometry::MeshSlicer slicer(mesh->triangles, values);
  long points = 0;
  for (double level = slicer.min_value() + 0.37; level < slicer.max_value(); level += 0.9) {
    for (const auto& line : slicer.slice(level)) {
      REQUIRE(line.size() >= 2);
      for (const auto& e : line) {
        const double va = values[static_cast<std::size_t>(e.a)],
                     vb = values[static_cast<std::size_t>(e.b)];
        CHECK(e.t >= 0.0);
        CHECK(e.t <= 1.0);
        CHECK(std::abs((1 - e.t) * va + e.t * vb - level) < 1e-12);
        ++points;
      }
    }
  }
  CHECK(points > 100);
}

TEST_CASE("plan on a bowl: scallop within 5 % of the target, no gouge over 1 um, shorter than the "
          "baseline",
          "[slow]") {
  TempDir dir;
  const auto cage = subfeed::testing::grid_cage(6, 5.0, 0.04, 0.01);
  const auto surface = surface_of(cage);
  const auto plan = [&](bool baseline) {
    geometry::PlanOptions options;
    options.ball_radius = 3.0;
    options.scallop = 0.03;
    options.baseline = baseline;
    options.tolerance = 0.001;
    auto planner = geometry::ToolpathPlanner::prepare(cage, surface, options);
    REQUIRE(planner);
    const auto file = dir.path() / (baseline ? "baseline.cl" : "deformed.cl");
    auto writer = cl::ClWriter::create(file, {"BOWL", {6.0, 3.0}, true});
    REQUIRE(writer);
    REQUIRE(planner->run([&](const cl::ClPose& p) -> Expected<void> {
      writer->write(p);
      return {};
    }));
    REQUIRE(writer->finish());
    geometry::VerifyOptions verify;
    verify.ball_radius = 3.0;
    verify.scallop_target = 0.03;
    verify.sample_spacing = 0.25;
    auto report = geometry::verify_path(surface, file, verify);
    REQUIRE(report);
    return *report;
  };
  const auto deformed = plan(false);
  const auto baseline = plan(true);
  INFO("deformed max " << deformed.max_scallop << " cutting " << deformed.cutting_length
                       << "; baseline max " << baseline.max_scallop << " cutting "
                       << baseline.cutting_length);
  CHECK(deformed.max_scallop <= 1.05 * 0.03);
  CHECK(deformed.max_scallop >= 0.5 * 0.03); // the meter sees real scallops
  CHECK(deformed.max_gouge <= 1e-3);
  CHECK(baseline.max_scallop <= 1.05 * 0.03);
  CHECK(deformed.cutting_length < baseline.cutting_length);
  CHECK(deformed.uncut_samples * 1000 <= deformed.samples); // at most the odd corner sample
}

TEST_CASE("faces meshed at different rates still share every point along their edges") {
  const auto cage = subfeed::testing::grid_cage(5, 5.0, 0.02, 0.01); // 4 x 4 faces
  const auto surface = surface_of(cage);
  std::vector<int> rates;
  for (int f = 0; f < surface.face_count(); ++f) {
    rates.push_back(f % 3 == 0 ? 7 : (f % 3 == 1 ? 3 : 5));
  }
  const auto mesh = geometry::mesh_surface(cage, surface, rates);
  REQUIRE(mesh);
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : mesh->triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  long once = 0;
  for (const auto& [edge, n] : uses) {
    CHECK(n <= 2);
    once += n == 1 ? 1 : 0;
  }
  // Only the 16 cage edges on the outline are open, each cut at its one face's rate.
  long outline = 0;
  std::map<std::pair<int, int>, std::vector<int>> faces_of;
  for (int f = 0; f < cage.face_count(); ++f) {
    const auto loop = cage.face(f);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      faces_of[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  }
  for (const auto& [edge, faces] : faces_of) {
    if (faces.size() == 1) {
      outline += rates[static_cast<std::size_t>(faces[0])];
    }
  }
  CHECK(once == outline);
  CHECK(mesh->rate == 7);
}

// The planner's choice of cage (planning_cage.hpp): a level of subdivision is taken where it
// meshes the same surface with clearly fewer vertices, and not where it would not; the
// prediction it rests on follows the meshes actually made.

#include "geometry/cage_refinement.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/planning_cage.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/toolpath_planner.hpp"

#include <catch2/catch.hpp>
#include <sstream>
#include <string>

using namespace subfeed;

namespace {

const std::string source_dir = SUBFEED_SOURCE_DIR;

// A flat 3 x 3 grid of `size` mm faces with one tight semi-sharp corner in the middle: the
// curvature peaks in a small spot of large faces.
geometry::Cage peaked(double size) {
  std::string text;
  for (int j = 0; j <= 3; ++j) {
    for (int i = 0; i <= 3; ++i) {
      const double z = (i == 1 && j == 1) ? 0.3 * size : 0.0;
      text += "v " + std::to_string(i * size) + " " + std::to_string(j * size) + " " +
              std::to_string(z) + "\n";
    }
  }
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      const int a = j * 4 + i + 1;
      text += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 5) +
              " " + std::to_string(a + 4) + "\n";
    }
  }
  text += "t corner 1/1/0 5 3\n";
  std::istringstream in(text);
  auto cage = geometry::parse_obj(in, "peaked.obj");
  REQUIRE(cage);
  return std::move(*cage);
}

} // namespace

TEST_CASE("the planner subdivides a cage whose large faces peak in one spot, and not the "
          "samples",
          "[unit]") {
  for (const double size : {10.0, 40.0}) {
    for (const double chord : {4e-4, 2e-3}) {
      INFO(size << " mm faces, chord " << chord);
      const auto cage = peaked(size);
      const auto surface = geometry::LimitSurface::build(cage);
      REQUIRE(surface);
      const auto chosen = geometry::planning_cage(cage, *surface, chord, 3);
      REQUIRE(chosen);
      REQUIRE(chosen->has_value());
      const auto& finer = **chosen;
      CHECK(finer.levels >= 1);
      CHECK(finer.cage.face_count() == cage.face_count() * (1 << (2 * finer.levels)));
      // The meshes made agree: clearly fewer vertices, each within its tolerance's rates.
      const auto before = geometry::mesh_surface(
          cage, *surface, geometry::rates_for_tolerance(*surface, chord, 4096));
      const auto after = geometry::mesh_surface(
          finer.cage, finer.surface, geometry::rates_for_tolerance(finer.surface, chord, 4096));
      REQUIRE(before);
      REQUIRE(after);
      CHECK(after->vertex_count() < 0.75 * before->vertex_count());
      // The prediction is the mesh's size, within what shared edges add.
      for (const auto& [s, mesh] : {std::pair{&*surface, &*before}, {&finer.surface, &*after}}) {
        const double predicted = geometry::predicted_vertices(*s, chord);
        if (mesh->rate < 256) { // Bfr's tessellation stops at 256 segments an edge
          CHECK(mesh->vertex_count() >= 0.5 * predicted);
        }
        CHECK(mesh->vertex_count() <= 2.0 * predicted);
      }
    }
  }
  for (const char* name :
       {"plane.obj", "bowl.obj", "saddle.obj", "dome.obj", "ridge.obj", "seat.obj"}) {
    INFO(name);
    const auto cage = geometry::read_obj(source_dir + "/examples/" + name);
    REQUIRE(cage);
    const auto surface = geometry::LimitSurface::build(*cage);
    REQUIRE(surface);
    const auto chosen = geometry::planning_cage(*cage, *surface, 4e-4, 3);
    REQUIRE(chosen);
    CHECK_FALSE(chosen->has_value());
  }
}

TEST_CASE("a plan over a subdivided cage says so and passes the motion gate on the cage's "
          "own surface",
          "[unit]") {
  const auto cage = peaked(10.0);
  const auto surface = geometry::LimitSurface::build(cage);
  REQUIRE(surface);
  geometry::PlanOptions options;
  options.ball_radius = 2.0;
  options.scallop = 0.1;
  options.tolerance = 0.004;
  options.refine_iterations = 3;
  auto planner = geometry::ToolpathPlanner::prepare(cage, *surface, options);
  REQUIRE(planner);
  CHECK(planner->summary().cage_levels >= 1);
  CHECK(planner->summary().cage_faces > cage.face_count());
  // Every pose through a gate built from the user's cage, not the planner's.
  auto gate = geometry::MotionGate::build(cage, *surface, {2.0, 1e-2, false, {}, {}});
  REQUIRE(gate);
  long poses = 0;
  const auto ran = planner->run([&](const cl::ClPose& p) -> Expected<void> {
    ++poses;
    return gate->check(p);
  });
  if (!ran) {
    FAIL(ran.error().message);
  }
  CHECK(poses > 100);
  options.max_cage_levels = 0;
  auto as_given = geometry::ToolpathPlanner::prepare(cage, *surface, options);
  REQUIRE(as_given);
  CHECK(as_given->summary().cage_levels == 0);
  CHECK(as_given->summary().mesh_vertices > planner->summary().mesh_vertices);
}

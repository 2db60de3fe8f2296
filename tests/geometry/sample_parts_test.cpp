// Every sample part in examples/ planned at two scallop targets and measured by the
// independent meter (path_verifier): the scallop within 5 % of the target, no gouge deeper
// than 1 um, and on the curved parts a shorter path than the iso-planar baseline with the
// same worst scallop. Heavy: run in the optimised build only (label `parts`).

#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/path_verifier.hpp"
#include "geometry/toolpath_planner.hpp"
#include "support/plan_to_file.hpp"
#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>

using namespace subfeed;
using subfeed::testing::TempDir;

namespace {

testing::PlannedPath plan_part(const geometry::Cage& cage, const geometry::LimitSurface& surface,
                               double radius, double scallop, bool baseline, const TempDir& dir) {
  geometry::PlanOptions plan;
  plan.ball_radius = radius;
  plan.scallop = scallop;
  plan.baseline = baseline;
  geometry::VerifyOptions verify;
  verify.ball_radius = radius;
  verify.scallop_target = scallop;
  verify.sample_spacing = radius / 12.0;
  return testing::plan_and_verify(cage, surface, plan, verify,
                                  dir.path() / (baseline ? "baseline.cl" : "deformed.cl"));
}

// `bends`: the need changes along the passes (the dome's top against its walls); the passes
// bend to follow it instead of breaking into pieces with inserted passes between, so the
// links stay well under the cut (held straight, the dome's were 2.7 times the cut).
void check_part(const char* name, double radius, std::initializer_list<double> targets, bool curved,
                bool bends = false) {
  const auto cage = geometry::read_obj(std::string(SUBFEED_SOURCE_DIR) + "/examples/" + name);
  REQUIRE(cage);
  const auto surface = geometry::LimitSurface::build(*cage);
  REQUIRE(surface);
  TempDir dir;
  for (const double h : targets) {
    const auto deformed = plan_part(*cage, *surface, radius, h, false, dir);
    const auto baseline = plan_part(*cage, *surface, radius, h, true, dir);
    const auto& d = deformed.report;
    const auto& b = baseline.report;
    INFO(name << " H " << h << ": deformed max " << d.max_scallop << " gouge " << d.max_gouge
              << " cutting " << d.cutting_length << " L/L* " << d.cutting_length / d.ideal_length
              << "; baseline max " << b.max_scallop << " gouge " << b.max_gouge << " cutting "
              << b.cutting_length << "; inserted to depth " << deformed.plan.inserted_depth
              << ", links " << deformed.plan.link_length << " mm");
    CHECK(d.max_scallop <= 1.05 * h);
    CHECK(d.max_scallop >= 0.5 * h); // the meter sees real scallops
    CHECK(d.max_gouge <= 1e-3);
    CHECK(b.max_scallop <= 1.05 * h);
    CHECK(b.max_gouge <= 1e-3);
    if (curved) {
      CHECK(d.cutting_length < b.cutting_length);
    }
    if (bends) {
      CHECK(deformed.plan.link_length < 0.75 * deformed.plan.cut_length);
    }
  }
}

} // namespace

TEST_CASE("sample part plane.obj at two scallop targets", "[parts][slow]") {
  check_part("plane.obj", 3.0, {0.01, 0.03}, false);
}

TEST_CASE("sample part bowl.obj at two scallop targets", "[parts][slow]") {
  check_part("bowl.obj", 3.0, {0.01, 0.03}, true);
}

TEST_CASE("sample part saddle.obj at two scallop targets", "[parts][slow]") {
  check_part("saddle.obj", 3.0, {0.01, 0.03}, true);
}

TEST_CASE("sample part dome.obj (slopes to 70 deg) at two scallop targets", "[parts][slow]") {
  check_part("dome.obj", 3.0, {0.01, 0.03}, true, true);
}

TEST_CASE("sample part ridge.obj (sharp crease, extraordinary vertices) at two scallop targets",
          "[parts][slow]") {
  check_part("ridge.obj", 3.0, {0.01, 0.03}, true);
}

TEST_CASE("sample part seat.obj at two scallop targets", "[parts][slow]") {
  check_part("seat.obj", 1.0, {0.005, 0.01}, true);
}

// Whole plans over families of grid parts with exact limit surfaces (domes, bowls, saddles;
// curvatures, aspect ratios a != b, grid sizes, where the part stands on Z) under every
// pattern and axis option, each measured by the independent meter (path_verifier): no cut
// deeper than 1 um, no plunge or retract below the surface past it, no rapid touching the
// part. The planner's own motion gate must pass every one of them too (the plan fails
// otherwise). The first case is the convex dome that was cut 3 mm deep.

#include "geometry/limit_surface.hpp"
#include "geometry/path_verifier.hpp"
#include "geometry/toolpath_planner.hpp"
#include "support/grid_cage.hpp"
#include "support/plan_to_file.hpp"
#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <string>

using namespace subfeed;
using subfeed::testing::TempDir;

namespace {

struct Shape {
  const char* name;
  int n;       // grid points a side
  double g;    // mm between them
  double a, b; // z = a x^2 + b y^2 on interior faces
  double z0;   // mm the part is lifted
};

struct Variant {
  const char* name;
  geometry::PlanOptions options;
};

geometry::PlanOptions base_options(double radius, double scallop) {
  geometry::PlanOptions o;
  o.ball_radius = radius;
  o.scallop = scallop;
  return o;
}

void check_clean(const Shape& shape, const geometry::PlanOptions& options, double spacing,
                 const std::string& label) {
  TempDir dir;
  const auto cage = subfeed::testing::lifted(
      subfeed::testing::grid_cage(shape.n, shape.g, shape.a, shape.b), shape.z0);
  auto surface = geometry::LimitSurface::build(cage);
  REQUIRE(surface);
  geometry::VerifyOptions verify;
  verify.ball_radius = options.ball_radius;
  verify.scallop_target = options.scallop;
  verify.sample_spacing = spacing;
  INFO(label << " on " << shape.name << " (" << shape.n << " x " << shape.n << ", a " << shape.a
             << ", b " << shape.b << ", lifted " << shape.z0 << " mm)");
  const auto planned =
      subfeed::testing::plan_and_verify(cage, *surface, options, verify, dir.path() / "part.cl");
  const auto& r = planned.report;
  INFO("gouge " << r.max_gouge << " mm at (" << r.gouge_at.transpose() << "), links "
                << r.links.deepest << " mm, rapids " << r.rapids.samples << " samples, "
                << r.rapids.deepest << " mm");
  CHECK(r.max_gouge <= 1e-3);
  CHECK(r.links.deepest <= 1e-3);
  CHECK(r.rapids.samples == 0);
  CHECK(planned.plan.gate.moves > 0);
}

} // namespace

TEST_CASE("the convex dome once cut 3 mm deep: 17 x 17 points 2 mm apart, lifted 20 mm, "
          "ball 6, H 0.01",
          "[parts][slow]") {
  // z = -0.02 (x^2 + y^2) + 20: its boundary corners' normals came out as rounding.
  const Shape dome{"dome", 17, 2.0, -0.02, -0.02, 20.0};
  check_clean(dome, base_options(3.0, 0.01), 0.25, "defaults (along X)");
}

TEST_CASE("shapes, sizes and heights: no gouge, no rapid into the part", "[parts][slow]") {
  const Shape shapes[] = {
      {"dome", 9, 2.5, -0.02, -0.02, 0.0},       {"dome", 9, 2.5, -0.02, -0.02, 20.0},
      {"long dome", 9, 2.5, -0.04, -0.01, 12.0}, {"dome", 13, 2.0, -0.03, -0.03, -35.0},
      {"bowl", 9, 2.5, 0.02, 0.01, 20.0},        {"bowl", 13, 2.0, 0.03, 0.015, 0.0},
      {"saddle", 9, 2.5, 0.02, -0.02, 20.0},     {"saddle", 11, 2.0, 0.03, -0.01, -7.0},
  };
  for (const auto& shape : shapes) {
    check_clean(shape, base_options(3.0, 0.03), 0.3, "defaults");
  }
}

TEST_CASE("every pattern and axis option on a lifted dome and saddle", "[parts][slow]") {
  std::vector<Variant> variants;
  const auto with = [&](const char* name, auto change) {
    auto o = base_options(3.0, 0.03);
    change(o);
    variants.push_back({name, o});
  };
  with("along Y", [](auto& o) { o.direction_deg = 90; });
  with("at 30 deg", [](auto& o) { o.direction_deg = 30; });
  with("auto", [](auto& o) { o.choose_direction = true; });
  with("concentric", [](auto& o) { o.pattern = geometry::PassPattern::concentric; });
  with("baseline", [](auto& o) { o.baseline = true; });
  with("fixed axis", [](auto& o) { o.fixed_axis = true; });
  with("always retract", [](auto& o) { o.stay_down = 0.0; });
  with("one way, stay down 10 mm", [](auto& o) {
    o.zigzag = false;
    o.stay_down = 10.0;
  });
  with("ball 4", [](auto& o) { o.ball_radius = 2.0; });
  const Shape shapes[] = {{"dome", 9, 2.5, -0.03, -0.02, 20.0},
                          {"saddle", 9, 2.5, 0.02, -0.03, 20.0}};
  for (const auto& shape : shapes) {
    for (const auto& v : variants) {
      check_clean(shape, v.options, 0.3, v.name);
    }
  }
}

TEST_CASE("a small lifted dome plans without a gouge (the corner normals' path, every build)",
          "[slow]") {
  const Shape dome{"small dome", 9, 2.5, -0.02, -0.02, 20.0};
  auto options = base_options(3.0, 0.05);
  options.refine_iterations = 3;
  check_clean(dome, options, 0.4, "coarse");
}

// The part's setup over every up axis, unit and origin: the set-up cage is the modelled part
// turned, scaled and moved exactly as documented, its limit surface with it (normals still
// point away from the material), and the setup's text form reads back to the same setup.

#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/part_setup.hpp"
#include "geometry/surface_summary.hpp"

#include <catch2/catch.hpp>
#include <string>

namespace g = subfeed::geometry;

namespace {

const std::string examples = std::string(SUBFEED_SOURCE_DIR) + "/examples/";

// Where a machine-frame point (Z up) sits in a model whose `up` axis points up: the inverse
// of the documented turn, written out axis by axis.
Eigen::Vector3d modelled(const Eigen::Vector3d& p, g::UpAxis up) {
  switch (up) {
  case g::UpAxis::x: // model +X is up, model -Z is machine +X
    return {p.z(), p.y(), -p.x()};
  case g::UpAxis::neg_x:
    return {-p.z(), p.y(), p.x()};
  case g::UpAxis::y: // model +Y is up, model +Z is machine -Y
    return {p.x(), p.z(), -p.y()};
  case g::UpAxis::neg_y:
    return {p.x(), -p.z(), p.y()};
  case g::UpAxis::neg_z:
    return {p.x(), -p.y(), -p.z()};
  case g::UpAxis::z:
    return p;
  }
  return p;
}

g::Cage as_modelled(g::Cage cage, g::UpAxis up, double mm_per_unit) {
  for (auto& p : cage.positions) {
    p = modelled(p, up) / mm_per_unit;
  }
  return cage;
}

g::SurfaceSummary summary_of(const g::Cage& cage) {
  auto surface = g::LimitSurface::build(cage);
  REQUIRE(surface);
  auto summary = g::summarize(cage, *surface);
  REQUIRE(summary);
  return *summary;
}

} // namespace

TEST_CASE("every up axis, unit and origin puts the part back where it was, moved to the zero") {
  const auto up = GENERATE(g::UpAxis::x, g::UpAxis::y, g::UpAxis::z, g::UpAxis::neg_x,
                           g::UpAxis::neg_y, g::UpAxis::neg_z);
  const auto unit =
      GENERATE(std::string("mm"), std::string("cm"), std::string("m"), std::string("in"));
  const auto part = GENERATE(std::string("seat"), std::string("ridge"), std::string("bowl"));
  auto original = g::read_obj(examples + part + ".obj");
  REQUIRE(original);
  const auto extent = summary_of(*original);
  const Eigen::Vector3d centre = (extent.min + extent.max) / 2;
  const double mm = g::parse_units(unit).value();
  const std::vector<std::pair<std::string, Eigen::Vector3d>> origins{
      {"model", Eigen::Vector3d::Zero()},
      {"top-centre", {centre.x(), centre.y(), extent.max.z()}},
      {"bottom-centre", {centre.x(), centre.y(), extent.min.z()}},
      {"min-corner", extent.min},
      {"1.5,-2,0.25", {1.5, -2.0, 0.25}}};
  for (const auto& [word, zero] : origins) {
    CAPTURE(part, unit, g::setup_text({up, mm, {}, Eigen::Vector3d::Zero()}), word);
    g::PartSetup setup{up, mm, {}, Eigen::Vector3d::Zero()};
    REQUIRE(g::parse_origin(word, setup));
    auto cage = as_modelled(*original, up, mm);
    const auto placed = g::set_up_part(cage, setup);
    REQUIRE(placed);
    CHECK((placed->zero_in_model - zero).norm() < 1e-9);
    for (int v = 0; v < cage.vertex_count(); ++v) {
      const Eigen::Vector3d want = original->positions[v] - zero;
      REQUIRE((cage.positions[v] - want).norm() < 1e-9 * (1 + want.norm()));
    }
    if (word == "min-corner") { // the surface moved with its cage (once: it costs a summary)
      const auto after = summary_of(cage);
      CHECK(after.min.norm() < 1e-9);
      CHECK((after.max - (extent.max - zero)).norm() < 1e-9);
      CHECK(after.area == Approx(extent.area).epsilon(1e-12));
    }
  }
}

TEST_CASE("the set-up surface's normals still point away from the material, up at the top") {
  const auto up =
      GENERATE(g::UpAxis::x, g::UpAxis::y, g::UpAxis::neg_x, g::UpAxis::neg_y, g::UpAxis::neg_z);
  auto original = g::read_obj(examples + "dome.obj");
  REQUIRE(original);
  auto cage = as_modelled(*original, up, 10.0);
  REQUIRE(g::set_up_part(cage, {up, 10.0, g::OriginKind::top_centre, Eigen::Vector3d::Zero()}));
  const auto surface = g::LimitSurface::build(cage);
  REQUIRE(surface);
  int upward = 0;
  for (int f = 0; f < surface->face_count(); ++f) {
    const auto s = surface->evaluate(f, 0.5, 0.5);
    REQUIRE(s);
    // The dome is convex and its zero is the top: every outward normal points up and away
    // from the axis through the top.
    CHECK(s->normal.z() > 0.2);
    CHECK(s->point.z() <= 1e-12);
    upward += s->normal.head<2>().dot(s->point.head<2>()) > 0 ? 1 : 0;
  }
  CHECK(upward == surface->face_count());
}

TEST_CASE("a setup's text reads back to the same setup, and bad words are named") {
  for (const auto up : {g::UpAxis::x, g::UpAxis::y, g::UpAxis::z, g::UpAxis::neg_x,
                        g::UpAxis::neg_y, g::UpAxis::neg_z}) {
    for (const double scale : {1.0, 10.0, 25.4, 1000.0, 0.1 + 0.2}) {
      for (const auto* origin :
           {"model", "top-centre", "bottom-centre", "min-corner", "0.1,-2.5e-3,1e10"}) {
        g::PartSetup s{up, scale, {}, Eigen::Vector3d::Zero()};
        REQUIRE(g::parse_origin(origin, s));
        const auto back = g::parse_setup_text(g::setup_text(s));
        REQUIRE(back);
        CHECK(*back == s);
      }
    }
  }
  CHECK(g::setup_text({}) == "up=z scale=1 origin=model");
  CHECK(g::PartSetup{}.is_identity());
  CHECK(g::parse_up_axis("Y").error().message == "up axis 'Y' is not x, y, z, -x, -y or -z");
  CHECK(g::parse_units("ft").error().message == "units 'ft' are not mm, cm, m or in");
  g::PartSetup s;
  for (const auto* bad : {"1,2", "1,2,3,4", "top", "1,,3", "a,b,c"}) {
    CAPTURE(bad);
    CHECK(g::parse_origin(bad, s).error().message ==
          std::string("origin '") + bad +
              "' is not top-centre, bottom-centre, min-corner, model or X,Y,Z in mm");
  }
  CHECK(g::parse_setup_text("up=y scale=0 origin=model").error().message ==
        "setup scale '0' is not a number above 0");
  CHECK(g::parse_setup_text("up=y origin=model").error().message ==
        "setup needs up=, scale= and origin=");
  CHECK(g::parse_setup_text("up=y up=z scale=1 origin=model").error().message ==
        "setup field 'up=z' is not up=, scale= or origin= (each once)");
}

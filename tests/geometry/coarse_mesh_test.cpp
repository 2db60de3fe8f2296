// The coarse mesh and its map (coarse_mesh.hpp): a field on the coarse vertices reaches the
// fine ones as the surface has it, to the coarse cells' chord, and each coarse vertex's
// nearest fine vertex is a neighbour, on every sample part (hexagons on the ridge), on a
// cage with a sharp crease and on one with triangles, for several coarsening factors.

#include "geometry/coarse_mesh.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/surface_mesh.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>

using namespace subfeed;

namespace {

const std::string source_dir = SUBFEED_SOURCE_DIR;

// A 3 x 1 strip folded along a sharp crease: the mesh keeps two vertices per crease point.
geometry::Cage folded() {
  std::istringstream in("v 0 0 0\nv 10 0 0\nv 20 0 8\nv 30 0 8\nv 0 10 0\nv 10 10 0\n"
                        "v 20 10 8\nv 30 10 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
                        "t crease 2/1/0 1 5 10\nt crease 2/1/0 2 6 10\n");
  auto cage = geometry::parse_obj(in, "folded.obj");
  REQUIRE(cage);
  return std::move(*cage);
}

// A raised hexagonal fan of six triangles round a centre and a ring of quads round it: Bfr's
// triangle domain beside quads.
geometry::Cage fan() {
  std::string text = "v 0 0 6\n";
  for (int ring = 1; ring <= 2; ++ring) {
    for (int k = 0; k < 6; ++k) {
      const double a = k * 3.14159265358979 / 3.0;
      text += "v " + std::to_string(10.0 * ring * std::cos(a)) + " " +
              std::to_string(10.0 * ring * std::sin(a)) + " " + std::to_string(6.0 - 3.0 * ring) +
              "\n";
    }
  }
  for (int k = 0; k < 6; ++k) {
    const int a = 2 + k, b = 2 + (k + 1) % 6;
    text += "f 1 " + std::to_string(a) + " " + std::to_string(b) + "\n";
    text += "f " + std::to_string(a) + " " + std::to_string(a + 6) + " " + std::to_string(b + 6) +
            " " + std::to_string(b) + "\n";
  }
  std::istringstream in(text);
  auto cage = geometry::parse_obj(in, "fan.obj");
  REQUIRE(cage);
  return std::move(*cage);
}

double longest_edge(const geometry::SurfaceMesh& mesh) {
  double longest = 0.0;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, (mesh.points[static_cast<std::size_t>(t[k])] -
                                   mesh.points[static_cast<std::size_t>(t[(k + 1) % 3])])
                                      .norm());
    }
  }
  return longest;
}

void check_map(const geometry::Cage& cage, int rate, int factor) {
  const auto surface = geometry::LimitSurface::build(cage);
  REQUIRE(surface);
  const auto fine = geometry::mesh_surface(cage, *surface, rate);
  REQUIRE(fine);
  const auto coarse = geometry::coarse_mesh(cage, *surface, *fine, factor);
  REQUIRE(coarse);
  const auto& cm = coarse->mesh;
  CHECK(cm.vertex_count() * factor * factor < fine->vertex_count() * 2);
  const double cell = longest_edge(cm);
  // Each coordinate as a field: carried to the fine mesh it is the fine points, to within
  // the coarse cells' sag.
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> field;
    for (const auto& p : cm.points) {
      field.push_back(p[axis]);
    }
    const auto carried = coarse->to_fine(field);
    double worst = 0.0;
    for (std::size_t v = 0; v < carried.size(); ++v) {
      worst = std::max(worst, std::abs(carried[v] - fine->points[v][axis]));
    }
    INFO("axis " << axis << ", coarse cells up to " << cell << " mm");
    CHECK(worst < 0.1 * cell);
  }
  // Exact where the fine vertex is a coarse one, and the weights a partition of one.
  for (std::size_t v = 0; v < coarse->fine_weights.size(); ++v) {
    CHECK(coarse->fine_weights[v].sum() == Approx(1.0));
    CHECK(coarse->fine_weights[v].minCoeff() >= 0.0);
  }
  const double fine_edge = longest_edge(*fine);
  for (std::size_t c = 0; c < coarse->nearest_fine.size(); ++c) {
    const auto& p = cm.points[c];
    const auto& q = fine->points[static_cast<std::size_t>(coarse->nearest_fine[c])];
    REQUIRE((p - q).norm() <= fine_edge);
    // The same side of a crease: the normals agree.
    REQUIRE(cm.normals[c].dot(fine->normals[static_cast<std::size_t>(coarse->nearest_fine[c])]) >
            0.9);
  }
}

} // namespace

TEST_CASE("a field on the coarse mesh reaches the fine mesh as the surface has it", "[unit]") {
  for (const char* part : {"dome", "bowl", "saddle", "seat", "ridge"}) {
    for (const int factor : {2, 4, 8}) {
      INFO(part << ", factor " << factor);
      auto cage = geometry::read_obj(source_dir + "/examples/" + std::string(part) + ".obj");
      REQUIRE(cage);
      check_map(*cage, 16, factor);
    }
  }
  for (const int factor : {2, 3, 4}) {
    INFO("folded strip, factor " << factor);
    check_map(folded(), 12, factor);
    INFO("triangle fan, factor " << factor);
    check_map(fan(), 12, factor);
  }
}

TEST_CASE("the coarse mesh keeps each face's own rate, coarsened", "[unit]") {
  const auto cage = folded();
  const auto surface = geometry::LimitSurface::build(cage);
  REQUIRE(surface);
  const auto fine = geometry::mesh_surface(cage, *surface, std::vector<int>{4, 16, 9});
  REQUIRE(fine);
  const auto coarse = geometry::coarse_mesh(cage, *surface, *fine, 4);
  REQUIRE(coarse);
  CHECK(coarse->mesh.face_rates == std::vector<int>{1, 4, 2});
}

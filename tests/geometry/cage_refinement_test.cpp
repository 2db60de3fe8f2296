// A refined cage (cage_refinement.hpp) has the same limit surface as the cage it came from,
// whatever the cage holds: creases sharp and semi-sharp under both creasing methods,
// corners, holes, extraordinary vertices, triangles under both rules, both boundary rules.
// Measured: every sample of the cage's surface lies on the refined one (projected onto it
// by Newton's method on its parameters), and the areas agree.

#include "geometry/cage_refinement.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/point_grid.hpp"
#include "geometry/surface_summary.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <limits>
#include <sstream>
#include <string>

using namespace subfeed;

namespace {

const std::string source_dir = SUBFEED_SOURCE_DIR;

// Bfr at its most exact level: near extraordinary vertices the default level's
// approximation differs between a cage and its refinement by up to 1e-3 of the size.
constexpr int exact_level = 10;

geometry::Cage parsed(const std::string& text) {
  std::istringstream in(text);
  auto cage = geometry::parse_obj(in, "cage.obj");
  REQUIRE(cage);
  return std::move(*cage);
}

// Points of a surface with where they are on it: starts for projecting onto it.
struct OnSurface {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> faces;
  std::vector<Eigen::Vector2d> uvs;
};

OnSurface points_of(const geometry::LimitSurface& s, int rate) {
  OnSurface out;
  for (int f = 0; f < s.face_count(); ++f) {
    if (!s.has_patch(f)) {
      continue;
    }
    for (const auto& uv : s.tessellate(f, rate).uv) {
      out.points.push_back(s.evaluate_regular(f, uv.x(), uv.y())->point);
      out.faces.push_back(f);
      out.uvs.push_back(uv);
    }
  }
  return out;
}

// The distance from x to `surface`: Gauss-Newton on the parameters of the quads of the few
// starts nearest x, kept inside [0, 1]^2; the least found. (Bfr parameterises other faces
// by sub-faces; a refined cage is all quads.)
double distance_to(const geometry::LimitSurface& surface, const OnSurface& starts,
                   const geometry::PointGrid& grid, double spacing, const Eigen::Vector3d& x) {
  std::vector<std::pair<double, std::size_t>> near;
  for (double reach = spacing; near.size() < 4 && reach < 1e3 * spacing; reach *= 2.0) {
    near.clear();
    grid.within(x, reach, [&](int i) {
      const auto k = static_cast<std::size_t>(i);
      near.emplace_back((starts.points[k] - x).norm(), k);
    });
  }
  std::ranges::sort(near);
  const auto quad = [&](const auto& n) { return surface.face_size(starts.faces[n.second]) == 4; };
  REQUIRE(!near.empty());
  std::erase_if(near, [&](const auto& n) { return !quad(n); });
  REQUIRE(!near.empty());
  near.resize(std::min<std::size_t>(near.size(), 4));
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [d, k] : near) {
    const int f = starts.faces[k];
    Eigen::Vector2d uv = starts.uvs[k];
    for (int step = 0; step < 12; ++step) {
      const auto s = surface.evaluate_regular(f, uv.x(), uv.y());
      Eigen::Matrix<double, 3, 2> j;
      j << s->du, s->dv;
      const Eigen::Matrix2d normal = j.transpose() * j + 1e-12 * Eigen::Matrix2d::Identity();
      uv += normal.ldlt().solve(j.transpose() * (x - s->point));
      uv = uv.cwiseMax(0.0).cwiseMin(1.0);
    }
    best = std::min(best, (surface.evaluate_regular(f, uv.x(), uv.y())->point - x).norm());
  }
  return best;
}

// The largest distance from samples of `from` (a 6 x 6 grid on every face) to `to`.
double farthest(const geometry::LimitSurface& to, const geometry::LimitSurface& from,
                double spacing) {
  const auto starts = points_of(to, 8);
  const geometry::PointGrid grid(starts.points, spacing);
  double most = 0.0;
  for (const auto& x : points_of(from, 5).points) {
    most = std::max(most, distance_to(to, starts, grid, spacing, x));
  }
  return most;
}

// A 4 x 4 grid with a bump, one triangle row, a semi-sharp and a sharp crease, a corner
// and a hole, under the given rules.
std::string tagged_grid(const std::string& rules) {
  std::string text;
  for (int j = 0; j <= 4; ++j) {
    for (int i = 0; i <= 4; ++i) {
      const double z = (i > 0 && i < 4 && j > 0 && j < 4) ? 0.7 * ((i * 2 + j) % 3) : 0.0;
      text += "v " + std::to_string(i * 5) + " " + std::to_string(j * 5) + " " + std::to_string(z) +
              "\n";
    }
  }
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      const int a = j * 5 + i + 1;
      const auto s = [](int v) { return std::to_string(v); };
      if (j == 1) {
        text += "f " + s(a) + " " + s(a + 1) + " " + s(a + 6) + "\n";
        text += "f " + s(a) + " " + s(a + 6) + " " + s(a + 5) + "\n";
      } else {
        text += "f " + s(a) + " " + s(a + 1) + " " + s(a + 6) + " " + s(a + 5) + "\n";
      }
    }
  }
  // 0-based: a semi-sharp crease along y = 10 (vertices 10..12), a sharp one at x = 15,
  // a corner at vertex 6, and the last face a hole.
  text += "t crease 2/1/0 10 11 1.5\nt crease 2/1/0 11 12 2.5\nt crease 2/1/0 8 13 10\n"
          "t corner 1/1/0 6 3\nt hole 1/0/0 19\n" +
          rules;
  return text;
}

} // namespace

namespace {

// Every sample of the cage's surface lies on the refined one (all quads, so the projection
// reaches every face), to the projection's rounding; and the areas agree, so the refined
// surface has nothing more.
void check_same_surface(const std::string& name, const geometry::Cage& cage, int levels) {
  INFO(name << ", " << levels << " level(s)");
  const auto surface = geometry::LimitSurface::build(cage, exact_level);
  REQUIRE(surface);
  const auto summary = geometry::summarize(cage, *surface, 64);
  REQUIRE(summary);
  const double size = (summary->max - summary->min).norm();
  const auto refined = geometry::refine_cage(cage, levels);
  REQUIRE(refined);
  CHECK(refined->face_count() >= cage.face_count() * (1 << (2 * levels)) / 2);
  const auto again = geometry::LimitSurface::build(*refined, exact_level);
  REQUIRE(again);
  CHECK(farthest(*again, *surface, 0.01 * size) <= 1e-6 * size);
  // Areas integrated over different parameterisations: equal to the integration's error.
  const auto refined_summary = geometry::summarize(*refined, *again, 64);
  REQUIRE(refined_summary);
  CHECK(refined_summary->area == Approx(summary->area).epsilon(1e-4));
}

} // namespace

TEST_CASE("a refined cage keeps its limit surface, tags and rules included", "[parts][slow]") {
  for (const char* name : {"ridge.obj", "seat.obj", "dome.obj"}) {
    auto cage = geometry::read_obj(source_dir + "/examples/" + name);
    REQUIRE(cage);
    for (const int levels : {1, 2}) {
      check_same_surface(name, *cage, levels);
    }
  }
  for (const char* rules : {"", "t creasemethod 0/0/1 chaikin\n",
                            "t smoothtriangles 0/0/1 smooth\n", "t interpolateboundary 1/0/0 2\n",
                            "t creasemethod 0/0/1 chaikin\nt interpolateboundary 1/0/0 0\n"}) {
    for (const int levels : {1, 2}) {
      check_same_surface(std::string("tagged grid ") + rules, parsed(tagged_grid(rules)), levels);
    }
  }
}

TEST_CASE("a refined cage keeps a tagged grid's limit surface", "[unit]") {
  // The family's check on one cage: creases sharp and semi-sharp, a corner, a hole and
  // triangles, under Chaikin's rule.
  check_same_surface("tagged grid, chaikin", parsed(tagged_grid("t creasemethod 0/0/1 chaikin\n")),
                     1);
}

TEST_CASE("refining nothing is the cage itself", "[unit]") {
  auto cage = geometry::read_obj(source_dir + "/examples/ridge.obj");
  REQUIRE(cage);
  const auto same = geometry::refine_cage(*cage, 0);
  REQUIRE(same);
  CHECK(same->positions == cage->positions);
  CHECK(same->face_indices == cage->face_indices);
}

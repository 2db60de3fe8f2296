// OpenSubdiv's shape tags beyond creases and corners reach the limit surface: a hole leaves
// its face without one, the creasing method and the triangle rule change the shape exactly
// where OpenSubdiv says they do and nowhere else, and face-varying tags change nothing.

#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"

#include <catch2/catch.hpp>
#include <sstream>
#include <string>

using subfeed::geometry::LimitSurface;

namespace {

LimitSurface surface_of(const std::string& text) {
  std::istringstream in(text);
  auto cage = subfeed::geometry::parse_obj(in, "tags.obj");
  REQUIRE(cage);
  auto surface = LimitSurface::build(*cage);
  REQUIRE(surface);
  return std::move(*surface);
}

// An n x n grid of quads over [0, n]^2 with a bump, so that rules have something to change;
// with `triangles`, its middle row of quads split into triangles.
std::string grid(int n, bool triangles = false) {
  const auto s = [](int v) { return std::to_string(v); };
  std::string text;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double z = (i > 0 && i < n && j > 0 && j < n) ? 0.3 * ((i + j) % 3) : 0.0;
      text += "v " + s(i) + " " + s(j) + " " + std::to_string(z) + "\n";
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1;
      if (triangles && j == n / 2) {
        text += "f " + s(a) + " " + s(a + 1) + " " + s(a + n + 2) + "\n";
        text += "f " + s(a) + " " + s(a + n + 2) + " " + s(a + n + 1) + "\n";
      } else {
        text += "f " + s(a) + " " + s(a + 1) + " " + s(a + n + 2) + " " + s(a + n + 1) + "\n";
      }
    }
  }
  return text;
}

// Largest distance between the two surfaces' points over every face, on a 5 x 5 grid.
double largest_difference(const LimitSurface& a, const LimitSurface& b) {
  REQUIRE(a.face_count() == b.face_count());
  double most = 0.0;
  for (int f = 0; f < a.face_count(); ++f) {
    REQUIRE(a.has_patch(f) == b.has_patch(f));
    if (!a.has_patch(f)) {
      continue;
    }
    const double top = a.face_size(f) == 4 ? 1.0 : 0.5; // triangles: u + v <= 1
    for (int i = 0; i <= 4; ++i) {
      for (int j = 0; j <= 4; ++j) {
        const double u = top * i / 4, v = top * j / 4;
        const auto pa = a.evaluate_regular(f, u, v);
        const auto pb = b.evaluate_regular(f, u, v);
        REQUIRE(pa);
        REQUIRE(pb);
        most = std::max(most, (pa->point - pb->point).norm());
      }
    }
  }
  return most;
}

} // namespace

TEST_CASE("a hole tag leaves its faces without a limit surface, the rest as they were") {
  for (const int n : {4, 5, 7}) {
    const int middle = (n / 2) * n + n / 2;
    const auto plain = surface_of(grid(n));
    const auto holed = surface_of(grid(n) + "t hole 2/0/0 " + std::to_string(middle) + " 0\n");
    for (int f = 0; f < n * n; ++f) {
      CHECK(holed.has_patch(f) == (f != middle && f != 0));
      CHECK(plain.has_patch(f));
    }
  }
}

TEST_CASE("chaikin creasing changes a semi-sharp crease and nothing on a cage without one") {
  // A crease along the grid's row j = 2, its two edges at different sharpness.
  const int n = 5;
  const auto row = [&](int i) { return std::to_string(2 * (n + 1) + i); };
  const std::string varying =
      "t crease 4/2/0 " + row(1) + " " + row(2) + " " + row(2) + " " + row(3) + " 1 3\n";
  const std::string none;
  for (const bool creased : {true, false}) {
    const std::string& crease = creased ? varying : none;
    const auto normal = surface_of(grid(n) + crease);
    const auto said_normal = surface_of(grid(n) + crease + "t creasemethod 0/0/1 normal\n");
    const auto chaikin = surface_of(grid(n) + crease + "t creasemethod 0/0/1 chaikin\n");
    CHECK(largest_difference(normal, said_normal) == 0.0);
    if (creased) {
      CHECK(largest_difference(normal, chaikin) > 1e-3);
    } else {
      CHECK(largest_difference(normal, chaikin) < 1e-12);
    }
  }
}

TEST_CASE("smooth triangles change a cage's triangles and leave all-quad cages alone") {
  for (const int n : {4, 6}) {
    const auto catmark = surface_of(grid(n, true));
    const auto said = surface_of(grid(n, true) + "t smoothtriangles 0/0/1 catmark\n");
    const auto smooth = surface_of(grid(n, true) + "t smoothtriangles 0/0/1 smooth\n");
    CHECK(largest_difference(catmark, said) == 0.0);
    CHECK(largest_difference(catmark, smooth) > 1e-3);
    const auto quads = surface_of(grid(n));
    const auto quads_smooth = surface_of(grid(n) + "t smoothtriangles 0/0/1 smooth\n");
    CHECK(largest_difference(quads, quads_smooth) == 0.0);
  }
}

TEST_CASE("face-varying tags are read and change nothing of the shape") {
  const auto plain = surface_of(grid(4));
  const auto tagged = surface_of(grid(4) + "t facevaryinginterpolateboundary 1/0/0 1\n" +
                                 "t facevaryingpropagatecorners 1/0/0 1\n");
  CHECK(largest_difference(plain, tagged) == 0.0);
}

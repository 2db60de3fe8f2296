#pragma once
// The benchmarks' real-model stand-in: a car-like body shell about 190 x 80 x 40 mm, open at
// its base, as a modeller would hand it over: Y up and in centimetres, semi-sharp creases
// along the roof line and a waist line, extraordinary vertices at the roof corners and
// wherever a quad of the roof is split into two triangles. Made here, from numbers, so no
// one's model is shipped.

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace subfeed::bench {

struct BodyCage {
  std::string obj; // Y up, cm
  int faces = 0;
  int creases = 0;
};

// `nx` x `ny` faces over the roof, `nz` down each side: 2 (nx + ny) nz + nx ny faces and
// more (split quads).
inline BodyCage body_cage_obj(int nx, int ny, int nz) {
  const double length = 190.0, width = 80.0, height = 40.0; // mm
  std::map<std::tuple<int, int, int>, int> index;
  std::ostringstream v, f;
  v.precision(10);
  int count = 0;
  // The shape in mm, Z up: a roof rising toward the cabin, sides drawn in toward the top.
  const auto vertex = [&](int i, int j, int k) {
    const auto key = std::make_tuple(i, j, k);
    if (const auto it = index.find(key); it != index.end()) {
      return it->second;
    }
    const double s = static_cast<double>(i) / nx - 0.5, t = static_cast<double>(j) / ny - 0.5;
    const double up = static_cast<double>(k) / nz;
    const double cabin = std::exp(-std::pow((s - 0.08) / 0.28, 4.0));
    const double roof = height * (0.55 + 0.45 * cabin) * (1.0 - 0.25 * std::pow(2.0 * t, 4.0));
    const double draw_in = 1.0 - 0.18 * up * up * (0.4 + cabin);
    const double x = length * s * (1.0 - 0.05 * up * up), y = width * t * draw_in;
    const double z = roof * up;
    // Y up, centimetres: model (x, z, -y) / 10 sets up to (x, y, z) with --up y --units cm.
    v << "v " << x / 10 << ' ' << z / 10 << ' ' << -y / 10 << '\n';
    index[key] = ++count;
    return count;
  };
  BodyCage cage;
  const auto quad = [&](int a, int b, int c, int d, bool split) {
    if (split) {
      f << "f " << a << ' ' << b << ' ' << c << "\nf " << a << ' ' << c << ' ' << d << '\n';
      cage.faces += 2;
    } else {
      f << "f " << a << ' ' << b << ' ' << c << ' ' << d << '\n';
      ++cage.faces;
    }
  };
  // The roof (k = nz), counter-clockwise seen from above; some quads split in two.
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const bool split = (i % 5 == 2) && (j % 3 == 1);
      quad(vertex(i, j, nz), vertex(i + 1, j, nz), vertex(i + 1, j + 1, nz), vertex(i, j + 1, nz),
           split);
    }
  }
  // The four sides, each counter-clockwise seen from outside.
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      quad(vertex(i, 0, k), vertex(i + 1, 0, k), vertex(i + 1, 0, k + 1), vertex(i, 0, k + 1),
           false);
      quad(vertex(i + 1, ny, k), vertex(i, ny, k), vertex(i, ny, k + 1), vertex(i + 1, ny, k + 1),
           false);
    }
    for (int j = 0; j < ny; ++j) {
      quad(vertex(nx, j, k), vertex(nx, j + 1, k), vertex(nx, j + 1, k + 1), vertex(nx, j, k + 1),
           false);
      quad(vertex(0, j + 1, k), vertex(0, j, k), vertex(0, j, k + 1), vertex(0, j + 1, k + 1),
           false);
    }
  }
  // Creases (0-based) round the roof (sharpness 2) and along a waist line (sharpness 1).
  std::ostringstream t;
  const auto crease = [&](int a, int b, double sharpness) {
    t << "t crease 2/1/0 " << a - 1 << ' ' << b - 1 << ' ' << sharpness << '\n';
    ++cage.creases;
  };
  const int waist = nz * 2 / 3;
  for (const auto& [k, sharpness] : {std::pair{nz, 2.0}, std::pair{waist, 1.0}}) {
    for (int i = 0; i < nx; ++i) {
      crease(vertex(i, 0, k), vertex(i + 1, 0, k), sharpness);
      crease(vertex(i, ny, k), vertex(i + 1, ny, k), sharpness);
    }
    for (int j = 0; j < ny; ++j) {
      crease(vertex(0, j, k), vertex(0, j + 1, k), sharpness);
      crease(vertex(nx, j, k), vertex(nx, j + 1, k), sharpness);
    }
  }
  cage.obj = "# a generated body shell: Y up, centimetres\n" + v.str() + f.str() + t.str();
  return cage;
}

} // namespace subfeed::bench

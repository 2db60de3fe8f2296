#pragma once
// The benchmarks' synthetic part: an n x n grid cage `spacing` mm apart whose heights follow
// gentle waves of `amplitude` mm, as OBJ text; its corner at the origin, or its middle when
// `centred` (for a machine whose travel is centred on zero).

#include <cmath>
#include <sstream>
#include <string>

namespace subfeed::bench {

inline std::string wavy_grid_obj(int n, double spacing, double amplitude, bool centred = false) {
  std::ostringstream obj;
  obj.precision(10);
  const double shift = centred ? -0.5 * spacing * (n - 1) : 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      obj << "v " << shift + spacing * i << ' ' << shift + spacing * j << ' '
          << amplitude * std::sin(0.3 * i) * std::cos(0.2 * j) << '\n';
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int v = j * n + i + 1;
      obj << "f " << v << ' ' << v + 1 << ' ' << v + 1 + n << ' ' << v + n << '\n';
    }
  }
  return obj.str();
}

} // namespace subfeed::bench

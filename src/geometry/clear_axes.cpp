#include "geometry/clear_axes.hpp"

#include "geometry/mesh_edges.hpp"
#include "geometry/point_grid.hpp"
#include "geometry/split_work.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <unordered_map>

namespace subfeed::geometry {

namespace {

constexpr double rad_per_deg = std::numbers::pi / 180.0;
// The contact stays this far below the ball's equator: a·n at least cos 80 degrees.
const double least_contact_cos_80 = std::cos(80.0 * rad_per_deg);

// `a` turned by `angle` about `about` (unit), which need not be square to it: only its part
// square to `a` turns it.
Eigen::Vector3d turned_about(const Eigen::Vector3d& a, const Eigen::Vector3d& about, double angle) {
  const Eigen::Vector3d k = about - about.dot(a) * a;
  if (k.norm() < 1e-12 || angle == 0.0) {
    return a;
  }
  return Eigen::AngleAxisd(angle, k.normalized()) * a;
}

// A unit vector square to `a`.
Eigen::Vector3d square_to_axis(const Eigen::Vector3d& a) {
  const Eigen::Vector3d other =
      std::abs(a.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  return a.cross(other).normalized();
}

constexpr int coarse_turn_stride = 3; // steps of the coarse search's turns

struct AxisTurn {
  double angle = 0.0; // radians
  Eigen::Vector3d about = Eigen::Vector3d::Zero();
};

// Each vertex's neighbours along the mesh's edges, packed.
struct EdgeNeighbours {
  std::vector<int> start, vertices;
};

EdgeNeighbours edge_neighbours(const SurfaceMesh& mesh) {
  const auto edges = mesh_edges(mesh.triangles);
  EdgeNeighbours n;
  n.start.assign(mesh.points.size() + 1, 0);
  for (const auto& e : edges) {
    ++n.start[static_cast<std::size_t>(e.a) + 1];
    ++n.start[static_cast<std::size_t>(e.b) + 1];
  }
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    n.start[v + 1] += n.start[v];
  }
  n.vertices.resize(static_cast<std::size_t>(n.start.back()));
  auto fill = n.start;
  for (const auto& e : edges) {
    n.vertices[static_cast<std::size_t>(fill[static_cast<std::size_t>(e.a)]++)] = e.b;
    n.vertices[static_cast<std::size_t>(fill[static_cast<std::size_t>(e.b)]++)] = e.a;
  }
  return n;
}

class AxisSearch {
public:
  AxisSearch(const AssemblyClearance& clearance, const ClearAxesOptions& options)
      : clearance_(clearance), options_(options), r_(clearance.tool().ball_radius),
        least_z_(std::cos(options.max_tilt_deg * rad_per_deg)) {}

  [[nodiscard]] bool allowed(const Eigen::Vector3d& axis, const Eigen::Vector3d& normal) const {
    return axis.z() >= least_z_ - 1e-12 && axis.dot(normal) >= least_contact_cos_80;
  }
  [[nodiscard]] bool clear(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis) const {
    return clearance_.clear(centre - r_ * axis, axis, options_.extra_mm);
  }
  // The nearest clear turn of `axis`, if any within the limits: first on a coarse grid of
  // turns (every third step, half the directions; a vertex with no clear axis, the costly
  // case, costs a sixth of the full grid), then on the full grid below and round the first
  // coarse turn found.
  [[nodiscard]] std::optional<AxisTurn> nearest(const Eigen::Vector3d& centre,
                                                const Eigen::Vector3d& normal,
                                                const Eigen::Vector3d& axis) const {
    const int most = static_cast<int>(std::floor(options_.most_turn_deg / options_.step_deg));
    std::optional<AxisTurn> coarse;
    int found_step = 0;
    for (int step = coarse_turn_stride; step <= most + coarse_turn_stride - 1 && !coarse;
         step += coarse_turn_stride) {
      found_step = std::min(step, most);
      coarse = best_at(centre, normal, axis, found_step, 2);
    }
    if (!coarse) {
      return std::nullopt;
    }
    for (int step = std::max(1, found_step - coarse_turn_stride + 1); step < found_step; ++step) {
      if (auto finer = best_at(centre, normal, axis, step, 1)) {
        return finer;
      }
    }
    return best_at(centre, normal, axis, found_step, 1);
  }

  // Of the turns by `step` steps in every `stride`-th direction round `axis`, the clear one
  // with the most slack.
  [[nodiscard]] std::optional<AxisTurn> best_at(const Eigen::Vector3d& centre,
                                                const Eigen::Vector3d& normal,
                                                const Eigen::Vector3d& axis, int step,
                                                int stride) const {
    const Eigen::Vector3d u = square_to_axis(axis), w = axis.cross(u);
    const double angle = step * options_.step_deg * rad_per_deg;
    std::optional<AxisTurn> best;
    double most = -1.0;
    for (int k = 0; k < options_.azimuths; k += stride) {
      const double phi = 2.0 * std::numbers::pi * k / options_.azimuths;
      const Eigen::Vector3d about = std::cos(phi) * u + std::sin(phi) * w;
      const Eigen::Vector3d a = turned_about(axis, about, angle);
      if (!allowed(a, normal) || !clear(centre, a)) {
        continue;
      }
      const double slack = clearance_.slack(centre - r_ * a, a, 2.0);
      if (slack > most) {
        most = slack;
        best = AxisTurn{angle, about};
      }
    }
    return best;
  }

private:
  const AssemblyClearance& clearance_;
  const ClearAxesOptions& options_;
  double r_, least_z_;
};

// The largest turn reaching each vertex from those the search turned, less the ramp's
// fall over the mesh's edges (Dijkstra, largest first).
std::vector<AxisTurn> spread_turns(const SurfaceMesh& mesh, const EdgeNeighbours& n,
                                   std::vector<AxisTurn> turns,
                                   const std::vector<ReachLimit>& reach, double fall_per_mm) {
  using Item = std::pair<double, int>;
  std::priority_queue<Item> queue;
  for (std::size_t v = 0; v < turns.size(); ++v) {
    if (turns[v].angle > 0.0) {
      queue.emplace(turns[v].angle, static_cast<int>(v));
    }
  }
  while (!queue.empty()) {
    const auto [angle, v] = queue.top();
    queue.pop();
    const auto vu = static_cast<std::size_t>(v);
    if (angle < turns[vu].angle) {
      continue;
    }
    for (int i = n.start[vu]; i < n.start[vu + 1]; ++i) {
      const auto u = static_cast<std::size_t>(n.vertices[static_cast<std::size_t>(i)]);
      const double next = angle - fall_per_mm * (mesh.points[u] - mesh.points[vu]).norm();
      if (reach[u] == ReachLimit::reached && next > turns[u].angle) {
        turns[u] = {next, turns[vu].about};
        queue.emplace(next, static_cast<int>(u));
      }
    }
  }
  return turns;
}

// Each turned axis averaged with its neighbours' `rounds` times: the searches turn by whole
// steps in a few directions, so neighbouring cells can differ by a step where the need does
// not. An axis the average would bring too near goes as far toward it as stays clear.
void smooth_turned_axes(const SurfaceMesh& mesh, const EdgeNeighbours& n,
                        const std::vector<AxisTurn>& ramped, const std::vector<ReachLimit>& reach,
                        const std::vector<char>& failed, const AxisSearch& search,
                        const std::vector<Eigen::Vector3d>& centres,
                        std::vector<Eigen::Vector3d>& axes, int rounds) {
  const auto moves = [&](std::size_t v) { return ramped[v].angle > 0.0 && failed[v] == 0; };
  const auto kept = axes;
  std::vector<Eigen::Vector3d> next = axes;
  for (int round = 0; round < rounds; ++round) {
    split_work(axes.size(), [&](std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        if (!moves(v)) {
          continue;
        }
        Eigen::Vector3d sum = axes[v];
        for (int i = n.start[v]; i < n.start[v + 1]; ++i) {
          const auto u = static_cast<std::size_t>(n.vertices[static_cast<std::size_t>(i)]);
          sum += reach[u] == ReachLimit::reached ? axes[u] : Eigen::Vector3d::Zero();
        }
        next[v] = sum.normalized();
      }
    });
    std::swap(axes, next);
  }
  split_work(axes.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      if (!moves(v)) {
        continue;
      }
      // The average, else the way to it as far as it stays clear (half, a quarter), else
      // the turn as it was.
      const Eigen::Vector3d smoothed = axes[v];
      axes[v] = kept[v];
      for (const double share : {1.0, 0.5, 0.25}) {
        const Eigen::Vector3d a = ((1.0 - share) * kept[v] + share * smoothed).normalized();
        if (search.allowed(a, mesh.normals[v]) && search.clear(centres[v], a)) {
          axes[v] = a;
          break;
        }
      }
    }
  });
}

} // namespace

ClearAxesReport clear_axes(const SurfaceMesh& mesh, const std::vector<Eigen::Vector3d>& centres,
                           std::vector<Eigen::Vector3d>& axes, std::vector<ReachLimit>& reach,
                           const AssemblyClearance& clearance, const ClearAxesOptions& options,
                           StageShare* share) {
  ClearAxesReport report;
  const AxisSearch search(clearance, options);
  const double r = clearance.tool().ball_radius;
  const auto& fixture = clearance.fixture();
  std::vector<AxisTurn> turns(axes.size());
  // 0: clear as it is; 1: no clear axis; 2: the ball under the stock; 3: to be searched.
  std::vector<char> blocked(axes.size(), 0);
  split_work(axes.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      if (share != nullptr) {
        share->tell(begin, v, end);
      }
      if (reach[v] != ReachLimit::reached) {
        continue;
      }
      // The ball's own depth does not depend on the axis.
      if (fixture.floor_z && centres[v].z() - r < *fixture.floor_z - fixture.stock_margin -
                                                      AssemblyClearance::floor_tolerance_mm) {
        blocked[v] = 2;
      } else if (!search.clear(centres[v], axes[v])) {
        blocked[v] = options.fixed_axis ? 1 : 3;
      }
    }
  });
  // A search per cell of `search_cell_mm`, at its first vertex; its turn is tried on the
  // cell's other vertices, which search for themselves only where it fails them. A cell
  // whose first vertex has no clear axis is left uncut whole: the edge of what is left moves
  // by at most a cell, never toward cutting what collides (every axis kept is checked).
  std::unordered_map<std::uint64_t, std::size_t> cell_of;
  std::vector<std::size_t> firsts, searched;
  for (std::size_t v = 0; v < axes.size(); ++v) {
    if (blocked[v] == 3) {
      const auto c = grid_cell(centres[v], options.search_cell_mm);
      const auto [it, added] = cell_of.try_emplace(grid_cell_key(c[0], c[1], c[2]), firsts.size());
      if (added) {
        firsts.push_back(v);
      }
      searched.push_back(v);
    }
  }
  std::vector<std::optional<AxisTurn>> cell_turns(firsts.size());
  split_work(
      firsts.size(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          const auto v = firsts[i];
          cell_turns[i] = search.nearest(centres[v], mesh.normals[v], axes[v]);
        }
      },
      1);
  split_work(searched.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const auto v = searched[i];
      const auto c = grid_cell(centres[v], options.search_cell_mm);
      const auto& cell = cell_turns[cell_of.at(grid_cell_key(c[0], c[1], c[2]))];
      if (!cell) {
        blocked[v] = 1;
        continue;
      }
      const Eigen::Vector3d a = turned_about(axes[v], cell->about, cell->angle);
      std::optional<AxisTurn> own =
          search.allowed(a, mesh.normals[v]) && search.clear(centres[v], a)
              ? cell
              : search.nearest(centres[v], mesh.normals[v], axes[v]);
      blocked[v] = own ? 0 : 1;
      turns[v] = own.value_or(AxisTurn{});
    }
  });
  for (std::size_t v = 0; v < axes.size(); ++v) {
    if (blocked[v] != 0) {
      reach[v] = blocked[v] == 2 ? ReachLimit::floor : ReachLimit::collision;
      ++(blocked[v] == 2 ? report.under_floor : report.collided);
    } else if (turns[v].angle > 0.0) {
      ++report.turned;
      report.largest_turn_deg = std::max(report.largest_turn_deg, turns[v].angle / rad_per_deg);
    }
  }
  if (report.turned == 0) {
    return report;
  }
  const auto n = edge_neighbours(mesh);
  const auto ramped = spread_turns(mesh, n, turns, reach, options.ramp_deg_per_mm * rad_per_deg);
  std::vector<char> failed(axes.size(), 0);
  split_work(axes.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      if (ramped[v].angle <= 0.0) {
        continue;
      }
      // The ramp's turn, else the vertex's own, else none: the first that keeps every rule.
      // (A turn spread from elsewhere may leave the limits, or not clear this vertex.)
      const Eigen::Vector3d own = axes[v];
      failed[v] = 1;
      for (const auto& t : {ramped[v], turns[v], AxisTurn{}}) {
        const Eigen::Vector3d a = turned_about(own, t.about, t.angle);
        if (search.allowed(a, mesh.normals[v]) && search.clear(centres[v], a)) {
          axes[v] = a;
          failed[v] = 0;
          break;
        }
      }
    }
  });
  smooth_turned_axes(mesh, n, ramped, reach, failed, search, centres, axes,
                     options.smoothing_rounds);
  for (std::size_t v = 0; v < axes.size(); ++v) {
    report.spread += ramped[v].angle > 0.0 ? 1 : 0;
    if (failed[v] != 0) {
      reach[v] = ReachLimit::collision;
      ++report.collided;
    }
  }
  report.spread -= report.turned;
  return report;
}

} // namespace subfeed::geometry

#include "geometry/assembly_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace subfeed::geometry {

namespace {

// Lowers `bound` toward the least of f over the triangle abc, to within `slop(bound)`: f is
// 1-Lipschitz, so no point of a triangle lies nearer than f at its centroid less its
// radius; a triangle is split in four until that rules it out, or it is smaller than the
// slop. Where f is nearly even (a face parallel to the part) only the slop ends the split:
// to a fixed 10 um that cost a hundred times more, so far from the rule it grows.
template <class F, class Slop>
void least_over_triangle(const F& f, const Slop& slop, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, const Eigen::Vector3d& c, double& bound,
                         Eigen::Vector3d& where) {
  const Eigen::Vector3d g = (a + b + c) / 3.0;
  const double radius =
      std::sqrt(std::max({(a - g).squaredNorm(), (b - g).squaredNorm(), (c - g).squaredNorm()}));
  const double at = f(g);
  if (at < bound) {
    bound = at;
    where = g;
  }
  const double loose = slop(bound);
  if (at - radius >= bound - loose || radius <= loose) {
    return;
  }
  const Eigen::Vector3d ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
  least_over_triangle(f, slop, a, ab, ca, bound, where);
  least_over_triangle(f, slop, ab, b, bc, bound, where);
  least_over_triangle(f, slop, ca, bc, c, bound, where);
  least_over_triangle(f, slop, ab, bc, ca, bound, where);
}

} // namespace

AssemblyClearance::AssemblyClearance(const ToolAssembly& tool, const Fixture& fixture,
                                     const TriangleTree& part)
    : tool_(tool), bodies_(tool.bodies()), fixture_(fixture), part_(&part) {
  reach_ = 2.0 * tool.ball_radius;
  for (const auto& b : bodies_) {
    reach_ = std::max(reach_, std::hypot(b.to_mm, std::max(b.radius_from_mm, b.radius_to_mm)));
  }
}

double AssemblyClearance::slop_at(double distance) const {
  return std::max(resolution_mm, slop_share * (distance - fixture_.clearance_min));
}

double AssemblyClearance::to_part(const ToolBody& body, const Eigen::Vector3d& tip,
                                  const Eigen::Vector3d& axis, double bound, double enough,
                                  Eigen::Vector3d* where) const {
  const auto f = [&](const Eigen::Vector3d& p) { return body_distance(body, tip, axis, p); };
  // Once a distance under `enough` is found the search is over: every node and triangle
  // left is then within the slop. (Inside the part, where every point reads 0, nothing else
  // would end it short of splitting the whole overlap to the resolution.)
  const double stop = std::max(enough, 1e-9);
  const auto slop = [&](double d) {
    return d < stop ? std::numeric_limits<double>::infinity() : slop_at(d);
  };
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  part_->search(
      bound,
      [&](const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
        return f(0.5 * (low + high)) - 0.5 * (high - low).norm();
      },
      slop,
      [&](int, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
        least_over_triangle(f, slop, a, b, c, bound, at);
      });
  if (where != nullptr) {
    *where = at;
  }
  return bound;
}

double AssemblyClearance::ball_lowest_z(const Eigen::Vector3d& tip,
                                        const Eigen::Vector3d& axis) const {
  return tip.z() + tool_.ball_radius * (axis.z() - 1.0);
}

std::optional<ClearanceViolation> AssemblyClearance::violation(const Eigen::Vector3d& tip,
                                                               const Eigen::Vector3d& axis,
                                                               double extra) const {
  if (fixture_.floor_z) {
    const double stock = *fixture_.floor_z - fixture_.stock_margin - floor_tolerance_mm;
    const double table = *fixture_.floor_z - floor_tolerance_mm;
    if (const double z = ball_lowest_z(tip, axis); z < stock) {
      return ClearanceViolation{"ball", true, stock + floor_tolerance_mm - z,
                                tip + tool_.ball_radius * (axis - Eigen::Vector3d::UnitZ())};
    }
    for (const auto& b : bodies_) {
      const double limit = b.cuts ? stock : table;
      if (const double z = body_lowest_z(b, tip, axis); z < limit) {
        return ClearanceViolation{b.name, true, limit + floor_tolerance_mm - z,
                                  body_lowest_point(b, tip, axis)};
      }
    }
  }
  const double wanted = fixture_.clearance_min + extra;
  for (const auto& b : bodies_) {
    Eigen::Vector3d where;
    if (const double d = to_part(b, tip, axis, wanted, wanted, &where); d < wanted) {
      return ClearanceViolation{b.name, false, d, where};
    }
  }
  return std::nullopt;
}

double AssemblyClearance::slack(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis, double cap,
                                std::vector<BodyClearance>* into) const {
  return std::min(floor_slack(tip, axis, into), part_slack(tip, axis, cap, into));
}

double AssemblyClearance::floor_slack(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis,
                                      std::vector<BodyClearance>* into) const {
  if (into != nullptr && into->size() != bodies_.size() + 1) {
    *into = blank();
  }
  if (!fixture_.floor_z) {
    return std::numeric_limits<double>::infinity();
  }
  double least = std::numeric_limits<double>::infinity();
  const auto floor_at = [&](std::size_t entry, double lowest, bool cuts) {
    const double limit = *fixture_.floor_z - (cuts ? fixture_.stock_margin : 0.0);
    least = std::min(least, lowest - limit + floor_tolerance_mm);
    if (into != nullptr && lowest - *fixture_.floor_z < (*into)[entry].to_floor) {
      (*into)[entry].to_floor = lowest - *fixture_.floor_z;
      (*into)[entry].floor_tip = tip;
    }
  };
  floor_at(0, ball_lowest_z(tip, axis), true);
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    floor_at(i + 1, body_lowest_z(bodies_[i], tip, axis), bodies_[i].cuts);
  }
  return least;
}

double AssemblyClearance::part_slack(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis,
                                     double cap, std::vector<BodyClearance>* into) const {
  if (into != nullptr && into->size() != bodies_.size() + 1) {
    *into = blank();
  }
  double least = cap;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    Eigen::Vector3d where;
    const double within = fixture_.clearance_min + cap;
    // Under clearance_min the slack is broken whatever the least: the search may end there.
    if (const double d = to_part(bodies_[i], tip, axis, within, fixture_.clearance_min, &where);
        d < within) {
      least = std::min(least, d - slop_at(d) - fixture_.clearance_min);
      if (into != nullptr && d < (*into)[i + 1].to_part) {
        (*into)[i + 1].to_part = d;
        (*into)[i + 1].part_point = where;
      }
    }
  }
  return least;
}

std::vector<BodyClearance> AssemblyClearance::blank() const {
  std::vector<BodyClearance> out{{.body = "ball"}};
  for (const auto& b : bodies_) {
    out.push_back({.body = b.name});
  }
  return out;
}

} // namespace subfeed::geometry

#include "geometry/triangle_tree.hpp"

#include "geometry/closest_point.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace subfeed::geometry {

namespace {

constexpr int leaf_size = 4;

// How far a coordinate running linearly from a to b stays outside [low, high], at least.
double gap(double a, double b, double low, double high) {
  return std::max({0.0, low - std::max(a, b), std::min(a, b) - high});
}

// Lower bounds of the distance from segment pq to a box and to a cylinder: each part of
// the distance (per box axis; along and across the cylinder's axis) at its own least over
// the segment, so the sum of their squares can only fall short of the true distance's.
double box_lower_bound(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                       const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double g = gap(p[i], q[i], low[i], high[i]);
    sum += g * g;
  }
  return std::sqrt(sum);
}

double cylinder_lower_bound(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                            const Eigen::Vector3d& centre, const Eigen::Vector3d& normal,
                            double radius, double half_height) {
  const Eigen::Vector3d dp = p - centre, dq = q - centre;
  const double hp = normal.dot(dp), hq = normal.dot(dq);
  const double up = gap(hp, hq, -half_height, half_height);
  // Across the axis: the segment projected on the cylinder's plane, from the centre.
  const Eigen::Vector3d pp = dp - hp * normal, pq = dq - hq * normal;
  const Eigen::Vector3d d = pq - pp;
  const double length2 = d.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp(-pp.dot(d) / length2, 0.0, 1.0) : 0.0;
  const double out = std::max(0.0, (pp + t * d).norm() - radius);
  return std::sqrt(up * up + out * out);
}

// The same two bounds for a point, squared: the segment's least-distance search drops out.
double box_point_bound2(const Eigen::Vector3d& p, const Eigen::Vector3d& low,
                        const Eigen::Vector3d& high) {
  return (low - p).cwiseMax(p - high).cwiseMax(0.0).squaredNorm();
}

double cylinder_point_bound2(const Eigen::Vector3d& p, const Eigen::Vector3d& centre,
                             const Eigen::Vector3d& normal, double radius, double half_height) {
  const Eigen::Vector3d d = p - centre;
  const double h = normal.dot(d);
  const double up = std::max(0.0, std::abs(h) - half_height);
  const double out = std::max(0.0, (d - h * normal).norm() - radius);
  return up * up + out * out;
}

} // namespace

void TriangleTree::fit_cylinder(Node& leaf) const {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
  for (int i = leaf.first; i < leaf.first + leaf.count; ++i) {
    const auto& t = (*triangles_)[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])];
    const auto& a = (*points_)[static_cast<std::size_t>(t[0])];
    const auto& b = (*points_)[static_cast<std::size_t>(t[1])];
    const auto& c = (*points_)[static_cast<std::size_t>(t[2])];
    centre += a + b + c;
    normal += (b - a).cross(c - a);
  }
  leaf.centre = centre / (3.0 * leaf.count);
  leaf.normal =
      normal.norm() > 0.0 ? Eigen::Vector3d(normal.normalized()) : Eigen::Vector3d::UnitZ();
  for (int i = leaf.first; i < leaf.first + leaf.count; ++i) {
    const auto& t = (*triangles_)[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])];
    for (const int v : t) {
      const Eigen::Vector3d d = (*points_)[static_cast<std::size_t>(v)] - leaf.centre;
      const double h = leaf.normal.dot(d);
      leaf.half_height = std::max(leaf.half_height, std::abs(h));
      leaf.radius = std::max(leaf.radius, (d - h * leaf.normal).norm());
    }
  }
}

TriangleTree::TriangleTree(const std::vector<Eigen::Vector3d>& points,
                           const std::vector<std::array<int, 3>>& triangles)
    : TriangleTree(points, triangles, {}) {}

TriangleTree::TriangleTree(const std::vector<Eigen::Vector3d>& points,
                           const std::vector<std::array<int, 3>>& triangles,
                           std::vector<double> grown)
    : points_(&points), triangles_(&triangles), order_(triangles.size()), grown_(std::move(grown)) {
  std::iota(order_.begin(), order_.end(), 0);
  centroids_.reserve(triangles.size());
  for (const auto& t : triangles) {
    centroids_.push_back((points[static_cast<std::size_t>(t[0])] +
                          points[static_cast<std::size_t>(t[1])] +
                          points[static_cast<std::size_t>(t[2])]) /
                         3.0);
  }
  nodes_.reserve(2 * triangles.size() / leaf_size + 2);
  if (!triangles.empty()) {
    build(0, static_cast<int>(triangles.size()));
  }
}

int TriangleTree::build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  Eigen::Vector3d clow = low, chigh = high;
  double grown = 0.0;
  for (int i = first; i < first + count; ++i) {
    const auto t = static_cast<std::size_t>(order_[static_cast<std::size_t>(i)]);
    grown = grown_.empty() ? 0.0 : std::max(grown, grown_[t]);
    for (const int v : (*triangles_)[t]) {
      low = low.cwiseMin((*points_)[static_cast<std::size_t>(v)]);
      high = high.cwiseMax((*points_)[static_cast<std::size_t>(v)]);
    }
    clow = clow.cwiseMin(centroids_[t]);
    chigh = chigh.cwiseMax(centroids_[t]);
  }
  nodes_[static_cast<std::size_t>(index)].low = low - Eigen::Vector3d::Constant(grown);
  nodes_[static_cast<std::size_t>(index)].high = high + Eigen::Vector3d::Constant(grown);
  nodes_[static_cast<std::size_t>(index)].first = first;
  nodes_[static_cast<std::size_t>(index)].count = count;
  fit_cylinder(nodes_[static_cast<std::size_t>(index)]);
  nodes_[static_cast<std::size_t>(index)].radius += grown;
  nodes_[static_cast<std::size_t>(index)].half_height += grown;
  if (count <= leaf_size) {
    nodes_[static_cast<std::size_t>(index)].first = first;
    nodes_[static_cast<std::size_t>(index)].count = count;
    return index;
  }
  int axis = 0;
  (chigh - clow).maxCoeff(&axis);
  const auto begin = order_.begin() + first, middle = begin + count / 2, end = begin + count;
  std::nth_element(begin, middle, end, [&](int a, int b) {
    return centroids_[static_cast<std::size_t>(a)][axis] <
           centroids_[static_cast<std::size_t>(b)][axis];
  });
  const int left = build(first, count / 2);
  const int right = build(first + count / 2, count - count / 2);
  nodes_[static_cast<std::size_t>(index)].left = left;
  nodes_[static_cast<std::size_t>(index)].right = right;
  return index;
}

std::optional<MeshNearest> TriangleTree::nearest(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                                 double limit) const {
  if (nodes_.empty()) {
    return std::nullopt;
  }
  std::optional<MeshNearest> best;
  double bound = limit;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const auto& node = nodes_[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    if (box_lower_bound(p, q, node.low, node.high) >= bound ||
        cylinder_lower_bound(p, q, node.centre, node.normal, node.radius, node.half_height) >=
            bound) {
      continue;
    }
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int t = order_[static_cast<std::size_t>(i)];
        const auto& tri = (*triangles_)[static_cast<std::size_t>(t)];
        const auto found =
            closest_segment_triangle(p, q, (*points_)[static_cast<std::size_t>(tri[0])],
                                     (*points_)[static_cast<std::size_t>(tri[1])],
                                     (*points_)[static_cast<std::size_t>(tri[2])]);
        const double d = found.distance();
        if (d < bound) {
          bound = d;
          best = MeshNearest{d, found.on_segment, found.on_triangle, t};
        }
      }
      continue;
    }
    // The nearer child last, so it is searched first and tightens the bound.
    const auto& l = nodes_[static_cast<std::size_t>(node.left)];
    const auto& r = nodes_[static_cast<std::size_t>(node.right)];
    const bool left_nearer =
        box_lower_bound(p, q, l.low, l.high) < box_lower_bound(p, q, r.low, r.high);
    stack.push_back(left_nearer ? node.right : node.left);
    stack.push_back(left_nearer ? node.left : node.right);
  }
  return best;
}

void TriangleTree::segment_search(
    const Eigen::Vector3d& p, const Eigen::Vector3d& q, double& bound,
    const std::function<void(int, const SegmentTriangleNearest&)>& leaf) const {
  if (nodes_.empty()) {
    return;
  }
  const bool point = p == q;
  // A point's bounds are cheaper than a segment's; both are compared squared.
  const auto beyond = [&](const Node& node) {
    const double b2 = bound * bound;
    if (point) {
      return box_point_bound2(p, node.low, node.high) >= b2 ||
             cylinder_point_bound2(p, node.centre, node.normal, node.radius, node.half_height) >=
                 b2;
    }
    return box_lower_bound(p, q, node.low, node.high) >= bound ||
           cylinder_lower_bound(p, q, node.centre, node.normal, node.radius, node.half_height) >=
               bound;
  };
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const auto& node = nodes_[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    if (bound <= 0.0 || beyond(node)) {
      continue;
    }
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int t = order_[static_cast<std::size_t>(i)];
        const auto& tri = (*triangles_)[static_cast<std::size_t>(t)];
        const auto& a = (*points_)[static_cast<std::size_t>(tri[0])];
        const auto& b = (*points_)[static_cast<std::size_t>(tri[1])];
        const auto& c = (*points_)[static_cast<std::size_t>(tri[2])];
        const auto found = point ? SegmentTriangleNearest{p, closest_on_triangle(p, a, b, c)}
                                 : closest_segment_triangle(p, q, a, b, c);
        const double grown = grown_.empty() ? 0.0 : grown_[static_cast<std::size_t>(t)];
        if (found.distance() - grown < bound) {
          leaf(t, found);
        }
      }
      continue;
    }
    const auto& l = nodes_[static_cast<std::size_t>(node.left)];
    const auto& r = nodes_[static_cast<std::size_t>(node.right)];
    const bool left_nearer =
        box_lower_bound(p, q, l.low, l.high) < box_lower_bound(p, q, r.low, r.high);
    stack.push_back(left_nearer ? node.right : node.left);
    stack.push_back(left_nearer ? node.left : node.right);
  }
}

std::vector<int> TriangleTree::near(const Eigen::Vector3d& p, double radius) const {
  std::vector<int> found;
  if (nodes_.empty()) {
    return found;
  }
  const double radius2 = radius * radius;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const auto& node = nodes_[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    if (box_point_bound2(p, node.low, node.high) > radius2 ||
        cylinder_point_bound2(p, node.centre, node.normal, node.radius, node.half_height) >
            radius2) {
      continue;
    }
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        found.push_back(order_[static_cast<std::size_t>(i)]);
      }
      continue;
    }
    stack.push_back(node.left);
    stack.push_back(node.right);
  }
  return found;
}

} // namespace subfeed::geometry

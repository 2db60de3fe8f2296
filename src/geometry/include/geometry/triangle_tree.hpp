#pragma once
// A bounding-box tree over a triangle mesh for "the nearest point of the mesh to this
// segment" and "the triangles near this point" queries. Exact: a subtree is skipped only when its
// box is provably farther than the best found (or than the caller's limit), and every triangle left
// is measured by closest_segment_triangle. The caller keeps the points and triangles alive.

#include "geometry/closest_point.hpp"

#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace subfeed::geometry {

struct MeshNearest {
  double distance = 0.0;      // mm
  Eigen::Vector3d on_segment; // the segment's point nearest the mesh
  Eigen::Vector3d on_mesh;    // the mesh's point nearest the segment
  int triangle = -1;
};

class TriangleTree {
public:
  TriangleTree(const std::vector<Eigen::Vector3d>& points,
               const std::vector<std::array<int, 3>>& triangles);
  // With each triangle grown by `grown[t]` mm (a surface piece within that of it): the
  // bounds that skip subtrees hold for the grown triangles, so a subtree is skipped only when
  // every piece in it is provably farther.
  TriangleTree(const std::vector<Eigen::Vector3d>& points,
               const std::vector<std::array<int, 3>>& triangles, std::vector<double> grown);

  // The nearest mesh point to segment pq if it lies closer than `limit`, else nothing.
  [[nodiscard]] std::optional<MeshNearest> nearest(const Eigen::Vector3d& p,
                                                   const Eigen::Vector3d& q, double limit) const;

  // Every triangle that may lie nearer segment pq than `bound`, nearer subtrees first:
  // `leaf(t, nearest)` is given the pair of points nearest each other and may lower `bound`.
  void segment_search(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double& bound,
                      const std::function<void(int, const SegmentTriangleNearest&)>& leaf) const;

  // Each triangle that may lie within `radius` of p, once: every one that does, and a few
  // near ones that do not (pruned by boxes and cylinders, not measured).
  [[nodiscard]] std::vector<int> near(const Eigen::Vector3d& p, double radius) const;

  // Branch and bound for any distance that is 1-Lipschitz in space: `lower(low, high)` must
  // not exceed the least distance within the box [low, high]; nodes whose bound is not under
  // `bound - slop(bound)` are skipped (slop: how far over the least the caller accepts), and
  // `leaf(t, a, b, c)` is called for each triangle t left (corners a, b, c), and may lower
  // `bound`.
  template <class Lower, class Slop, class Leaf>
  void search(double& bound, Lower&& lower, Slop&& slop, Leaf&& leaf) const {
    if (nodes_.empty()) {
      return;
    }
    // Each node with its bound; the nearer child is searched first, to tighten `bound`.
    std::vector<std::pair<int, double>> stack{{0, lower(nodes_[0].low, nodes_[0].high)}};
    while (!stack.empty()) {
      const auto [index, below] = stack.back();
      stack.pop_back();
      if (below >= bound - slop(bound)) {
        continue;
      }
      const auto& node = nodes_[static_cast<std::size_t>(index)];
      if (node.left < 0) {
        for (int i = node.first; i < node.first + node.count; ++i) {
          const int t = order_[static_cast<std::size_t>(i)];
          const auto& tri = (*triangles_)[static_cast<std::size_t>(t)];
          leaf(t, (*points_)[static_cast<std::size_t>(tri[0])],
               (*points_)[static_cast<std::size_t>(tri[1])],
               (*points_)[static_cast<std::size_t>(tri[2])]);
        }
        continue;
      }
      const auto& l = nodes_[static_cast<std::size_t>(node.left)];
      const auto& r = nodes_[static_cast<std::size_t>(node.right)];
      const double lb = lower(l.low, l.high), rb = lower(r.low, r.high);
      if (lb < rb) {
        stack.emplace_back(node.right, rb);
        stack.emplace_back(node.left, lb);
      } else {
        stack.emplace_back(node.left, lb);
        stack.emplace_back(node.right, rb);
      }
    }
  }

private:
  struct Node {
    Eigen::Vector3d low, high;
    int first = 0, count = 0;  // its triangles: order_[first, first + count)
    int left = -1, right = -1; // children; -1 for a leaf
    // The node's triangles also lie in a cylinder along their mean normal, flat where the
    // mesh is nearly flat, whose distance bounds them far more tightly than the box there.
    Eigen::Vector3d centre, normal;
    double radius = 0.0, half_height = 0.0;
  };
  void fit_cylinder(Node& leaf) const;
  int build(int first, int count);

  const std::vector<Eigen::Vector3d>* points_;
  const std::vector<std::array<int, 3>>* triangles_;
  std::vector<int> order_;
  std::vector<Eigen::Vector3d> centroids_;
  std::vector<double> grown_; // per triangle, or empty
  std::vector<Node> nodes_;
};

} // namespace subfeed::geometry

#pragma once
// A bounding-box tree over a triangle mesh for "the nearest point of the mesh to this
// segment" and "the triangles near this point" queries. Exact: a subtree is skipped only when its
// box is provably farther than the best found (or than the caller's limit), and every triangle left
// is measured by closest_segment_triangle. The caller keeps the points and triangles alive.

#include <Eigen/Core>
#include <array>
#include <optional>
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

  // The nearest mesh point to segment pq if it lies closer than `limit`, else nothing.
  [[nodiscard]] std::optional<MeshNearest> nearest(const Eigen::Vector3d& p,
                                                   const Eigen::Vector3d& q, double limit) const;

  // Each triangle that may lie within `radius` of p, once: every one that does, and a few
  // near ones that do not (pruned by boxes and cylinders, not measured).
  [[nodiscard]] std::vector<int> near(const Eigen::Vector3d& p, double radius) const;

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
  std::vector<Node> nodes_;
};

} // namespace subfeed::geometry

#include "geometry/vector_sum_tree.hpp"

#include <algorithm>
#include <numeric>

namespace subfeed::geometry {

namespace {

constexpr int sum_leaf_size = 8;

} // namespace

VectorSumTree::VectorSumTree(const std::vector<Eigen::Vector3d>& points,
                             const std::vector<Eigen::Vector3d>& vectors) {
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  points_.reserve(points.size());
  vectors_.reserve(points.size());
  // Sorted into tree order once, so each node is a contiguous run.
  const auto split = [&](auto& self, int first, int count) -> void {
    if (count <= sum_leaf_size) {
      return;
    }
    Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
    for (int i = first; i < first + count; ++i) {
      low = low.cwiseMin(points[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])]);
      high = high.cwiseMax(points[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])]);
    }
    int axis = 0;
    (high - low).maxCoeff(&axis);
    const auto begin = order.begin() + first;
    std::nth_element(begin, begin + count / 2, begin + count, [&](int a, int b) {
      return points[static_cast<std::size_t>(a)][axis] < points[static_cast<std::size_t>(b)][axis];
    });
    self(self, first, count / 2);
    self(self, first + count / 2, count - count / 2);
  };
  split(split, 0, static_cast<int>(points.size()));
  for (const int i : order) {
    points_.push_back(points[static_cast<std::size_t>(i)]);
    vectors_.push_back(vectors[static_cast<std::size_t>(i)]);
  }
  nodes_.reserve(2 * points.size() / sum_leaf_size + 2);
  if (!points_.empty()) {
    build(0, static_cast<int>(points_.size()));
  }
}

int VectorSumTree::build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Node node;
  node.low = Eigen::Vector3d::Constant(1e300);
  node.high = -node.low;
  node.sum.setZero();
  node.first = first;
  node.count = count;
  for (int i = first; i < first + count; ++i) {
    node.low = node.low.cwiseMin(points_[static_cast<std::size_t>(i)]);
    node.high = node.high.cwiseMax(points_[static_cast<std::size_t>(i)]);
    node.sum += vectors_[static_cast<std::size_t>(i)];
  }
  if (count > sum_leaf_size) { // the same halves the sort made
    node.left = build(first, count / 2);
    node.right = build(first + count / 2, count - count / 2);
  }
  nodes_[static_cast<std::size_t>(index)] = node;
  return index;
}

Eigen::Vector3d VectorSumTree::sum_within(const Eigen::Vector3d& p, double radius) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  if (nodes_.empty()) {
    return sum;
  }
  const double r2 = radius * radius;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const auto& node = nodes_[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    const Eigen::Vector3d near = (node.low - p).cwiseMax(p - node.high).cwiseMax(0.0);
    if (near.squaredNorm() > r2) {
      continue;
    }
    const Eigen::Vector3d far = (p - node.low).cwiseAbs().cwiseMax((node.high - p).cwiseAbs());
    if (far.squaredNorm() <= r2) {
      sum += node.sum;
      continue;
    }
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if ((points_[static_cast<std::size_t>(i)] - p).squaredNorm() <= r2) {
          sum += vectors_[static_cast<std::size_t>(i)];
        }
      }
      continue;
    }
    stack.push_back(node.left);
    stack.push_back(node.right);
  }
  return sum;
}

} // namespace subfeed::geometry

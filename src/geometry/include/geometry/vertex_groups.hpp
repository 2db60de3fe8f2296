#pragma once
// Union-find over vertex indices (path halving): which vertices a set of joins connects.

#include <cstddef>
#include <numeric>
#include <vector>

namespace subfeed::geometry {

class VertexGroups {
public:
  explicit VertexGroups(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  // The same index for every vertex of one group.
  [[nodiscard]] std::size_t root(std::size_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void join(std::size_t a, std::size_t b) { parent_[root(a)] = root(b); }

private:
  std::vector<std::size_t> parent_;
};

} // namespace subfeed::geometry

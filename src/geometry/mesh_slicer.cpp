#include "geometry/mesh_slicer.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace subfeed::geometry {

namespace {

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return lo << 32 | hi;
}

struct Piece {
  EdgePoint from, to;
  bool used = false;
};

} // namespace

MeshSlicer::MeshSlicer(const std::vector<std::array<int, 3>>& triangles,
                       const std::vector<double>& values)
    : triangles_(&triangles), values_(&values) {
  tri_min_.resize(triangles.size());
  tri_max_.resize(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    const double a = values[static_cast<std::size_t>(t[0])],
                 b = values[static_cast<std::size_t>(t[1])],
                 c = values[static_cast<std::size_t>(t[2])];
    tri_min_[i] = std::min({a, b, c});
    tri_max_[i] = std::max({a, b, c});
  }
  by_min_.resize(triangles.size());
  std::iota(by_min_.begin(), by_min_.end(), 0);
  std::ranges::sort(by_min_, [&](int x, int y) {
    return tri_min_[static_cast<std::size_t>(x)] < tri_min_[static_cast<std::size_t>(y)];
  });
  min_ = triangles.empty() ? 0.0 : *std::ranges::min_element(tri_min_);
  max_ = triangles.empty() ? 0.0 : *std::ranges::max_element(tri_max_);
}

std::vector<SlicePolyline> MeshSlicer::slice(double level, const std::vector<unsigned char>* depth,
                                             int min_depth) {
  const auto& values = *values_;
  while (next_ < by_min_.size() && tri_min_[static_cast<std::size_t>(by_min_[next_])] <= level) {
    active_.push_back(by_min_[next_++]);
  }
  std::erase_if(active_, [&](int t) { return tri_max_[static_cast<std::size_t>(t)] < level; });
  // A vertex exactly on the level counts as above, so every crossed triangle has exactly
  // two crossed edges and neighbours agree on them.
  const auto above = [&](int v) { return values[static_cast<std::size_t>(v)] >= level; };
  const auto cross = [&](int a, int b) {
    const double va = values[static_cast<std::size_t>(a)], vb = values[static_cast<std::size_t>(b)];
    return EdgePoint{a, b, (level - va) / (vb - va)};
  };
  std::vector<Piece> pieces;
  std::unordered_map<std::uint64_t, std::array<int, 2>> at_edge;
  const auto attach = [&](const EdgePoint& p, int piece) {
    auto [it, fresh] = at_edge.try_emplace(edge_key(p.a, p.b), std::array<int, 2>{piece, -1});
    if (!fresh) {
      it->second[1] = piece;
    }
  };
  for (const int ti : active_) {
    if (depth != nullptr && (*depth)[static_cast<std::size_t>(ti)] < min_depth) {
      continue;
    }
    const auto& t = (*triangles_)[static_cast<std::size_t>(ti)];
    std::array<EdgePoint, 2> ends{};
    int found = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      if (above(a) != above(b) && found < 2) {
        ends[static_cast<std::size_t>(found++)] = above(a) ? cross(b, a) : cross(a, b);
      }
    }
    if (found == 2) {
      pieces.push_back({ends[0], ends[1]});
      attach(ends[0], static_cast<int>(pieces.size()) - 1);
      attach(ends[1], static_cast<int>(pieces.size()) - 1);
    }
  }
  const auto other_piece = [&](const EdgePoint& p, int piece) {
    const auto& both = at_edge.at(edge_key(p.a, p.b));
    return both[0] == piece ? both[1] : both[0];
  };
  const auto walk = [&](int start, const EdgePoint& first) {
    SlicePolyline line{first};
    int piece = start;
    EdgePoint at = first;
    while (piece >= 0 && !pieces[static_cast<std::size_t>(piece)].used) {
      auto& p = pieces[static_cast<std::size_t>(piece)];
      p.used = true;
      const bool forward = edge_key(p.from.a, p.from.b) == edge_key(at.a, at.b);
      at = forward ? p.to : p.from;
      line.push_back(at);
      piece = other_piece(at, piece);
    }
    return line;
  };
  std::vector<SlicePolyline> lines;
  // Open polylines first, from an end (an edge with one piece), then the closed loops.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (pieces[i].used) {
        continue;
      }
      const auto& p = pieces[i];
      const bool from_end = at_edge.at(edge_key(p.from.a, p.from.b))[1] < 0;
      const bool to_end = at_edge.at(edge_key(p.to.a, p.to.b))[1] < 0;
      if (pass == 0 && !from_end && !to_end) {
        continue;
      }
      lines.push_back(walk(static_cast<int>(i), from_end || pass == 1 ? p.from : p.to));
    }
  }
  return lines;
}

} // namespace subfeed::geometry

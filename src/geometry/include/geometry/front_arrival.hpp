#pragma once
// Arrival times of a front that leaves a set of vertices of a triangle mesh at time 0 and
// crosses the surface with a given slowness (time per mm) at each vertex: the solution T
// of the eikonal equation |grad T| = slowness, by fast marching on triangles (Kimmel &
// Sethian 1998). A vertex takes the least time over planar fronts that reach it across one
// of its triangles from the two corners already known, where the front's direction falls
// inside that triangle, else along an edge from one known corner. Each vertex is settled
// once, in increasing time (a binary heap): O(n log n).
//
// Level lines of T spaced by one unit of time lie 1/slowness apart, whatever way they bend:
// with slowness = 1 / the spacing each vertex needs, they are passes at exactly that
// spacing, except where two parts of the front meet (a kink), which spacing_ratios measures.
// Vertices no front reaches (a piece of mesh without a source) are +infinity.

#include <Eigen/Core>
#include <array>
#include <vector>

namespace subfeed::geometry {

[[nodiscard]] std::vector<double> front_arrival(const std::vector<Eigen::Vector3d>& points,
                                                const std::vector<std::array<int, 3>>& triangles,
                                                const std::vector<double>& slowness,
                                                const std::vector<int>& sources);

} // namespace subfeed::geometry

#pragma once
// The checks that make a parsed cage safe to subdivide and machine. A cage passes when every
// face has at least three distinct, in-range vertices and non-zero area, no face repeats
// another, every edge has one or two faces and two faces agree on its direction, every
// vertex has one fan of faces, coordinates are finite, and every crease names a cage edge.

#include "base/error.hpp"
#include "geometry/cage.hpp"

namespace subfeed::geometry {

[[nodiscard]] Expected<void> validate_cage(const Cage& cage);

} // namespace subfeed::geometry

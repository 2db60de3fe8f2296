#pragma once
// The cage as OpenSubdiv's topology refiner sees it: faces, creases, corners, holes and the
// rules (boundary interpolation, creasing method, triangle rule). Private to the geometry
// library: the limit surface and the cage's refinement both start here.

#include "geometry/cage.hpp"

#include <memory>
#include <opensubdiv/far/topologyRefiner.h>

namespace subfeed::geometry {

// Null when OpenSubdiv rejects the topology.
[[nodiscard]] std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> make_refiner(const Cage& cage);

} // namespace subfeed::geometry

#pragma once
// A cage subdivided by uniform Catmull-Clark steps, kept as a cage: four times the faces a
// step (every face a quad after the first), its creases and corners carried with the
// sharpness the rules leave them, its holes and rules kept. Subdivision is exact, so the
// limit surface is the same; what changes is how finely each face can be meshed on its own.
// A large coarse face whose curvature peaks in one corner must be meshed at that corner's
// rate all over; its sixteen children each take their own.

#include "base/error.hpp"
#include "geometry/cage.hpp"

namespace subfeed::geometry {

// `levels` >= 0; faces of the result have no source line (0).
[[nodiscard]] Expected<Cage> refine_cage(const Cage& cage, int levels);

} // namespace subfeed::geometry

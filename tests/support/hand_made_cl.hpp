#pragma once
// CL data made by hand to be wrong on purpose, for the commands' tests of the motion gate.

namespace subfeed::testing {

// Over examples/plane.obj (z = 0), ball 6 mm: a plunge, one pass on the plane, a retract, and
// on line 16 a rapid whose ball ends 1 mm below the plane (its centre 2 mm above it).
inline constexpr const char* rapid_through_plane_cl = "PARTNO THROUGH\nUNITS/MM\nCUTTER/6,3\n"
                                                      "RAPID\nGOTO/-10,0,10\nRAPID\nGOTO/-10,0,1\n"
                                                      "FEDRAT/300\nPLUNGE\nGOTO/-10,0,0\n"
                                                      "FEDRAT/1000\nGOTO/10,0,0\n"
                                                      "RETRACT\nGOTO/10,0,2\n"
                                                      "RAPID\nGOTO/-10,5,-1\nFINI\n";

// The same path up to the bad rapid: what may be posted and streamed.
inline constexpr const char* rapid_through_plane_sound_part_cl =
    "PARTNO THROUGH\nUNITS/MM\nCUTTER/6,3\n"
    "RAPID\nGOTO/-10,0,10\nRAPID\nGOTO/-10,0,1\n"
    "FEDRAT/300\nPLUNGE\nGOTO/-10,0,0\n"
    "FEDRAT/1000\nGOTO/10,0,0\n"
    "RETRACT\nGOTO/10,0,2\nFINI\n";

} // namespace subfeed::testing

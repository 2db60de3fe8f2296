#pragma once
// The pose at the seam between planning and post-processing (docs/ARCHITECTURE.md): where the
// tool tip goes, which way the tool points, and how it gets there. The one type the
// geometry core and the postprocessors share; it knows nothing of meshes or machines.

#include <array>
#include <string>

namespace subfeed::cl {

enum class MoveKind {
  rapid,   // positioning at the machine's rapid rate, off the part
  feed,    // cutting at `feed`
  plunge,  // feeding toward the part (an approach)
  retract, // feeding away from the part
};

struct ClPose {
  std::array<double, 3> tip{};  // mm, workpiece frame
  std::array<double, 3> axis{}; // unit vector from the tip toward the spindle
  MoveKind kind = MoveKind::feed;
  double feed = 0.0; // mm/min at the tool tip; 0 for rapids
  long line = 0;     // source line in the CL file (0 when not read from a file)
};

struct Cutter {
  double diameter = 0.0;      // mm
  double corner_radius = 0.0; // mm; diameter / 2 for a ball end
};

// The tool above the ball and the fixture a path was planned against ("flute=18 shank=6
// ...", "floor=0 margin=0 clearance=0.5": job/tool_spec.hpp), kept in `PPRINT TOOL` and
// `PPRINT FIXTURE` records; empty when not recorded.
struct WholeToolRecords {
  std::string tool;
  std::string fixture;
  long tool_line = 0, fixture_line = 0; // where they were read, for errors; 0: not read
};

// What the records before the first motion say.
struct ClHeader {
  std::string part_name;
  Cutter cutter;
  bool multiaxis = false; // MULTAX/ON: every GOTO carries the tool axis
  // How the part was set up on the machine when planned ("up=y scale=10 origin=top-centre",
  // geometry/part_setup.hpp), kept in a `PPRINT SETUP ...` record; empty when not recorded.
  std::string setup;
  WholeToolRecords whole_tool;
};

} // namespace subfeed::cl

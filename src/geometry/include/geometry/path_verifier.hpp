#pragma once
// `subfeed verify`: measures what a CL path leaves on the limit surface, independently of
// the planner and of the motion gate (it reads only the cage's surface and the CL data).
// Dense samples of the design surface are measured against the capsules the ball sweeps
// between consecutive feed poses (scallop_meter.hpp); each sample is then pushed sideways,
// across the nearest pass, to the local maximum so cusps between sample points are not
// missed. The same samples are measured apart against the sweeps of plunges and retracts
// (links) and of rapids, so that a link or rapid into the part is told from a cutting gouge.
//
// The ideal bound L* = integral of dA / w(h, rho) (docs/METHOD.md §5) uses the measured worst
// scallop as h (or the target when given), rho across the nearest pass, and w from the
// circle geometry of two neighbouring balls, written here on its own.

#include "base/error.hpp"
#include "cl/cl_reader.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/uncut_regions.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <string>

namespace subfeed::geometry {

struct VerifyOptions {
  double ball_radius = 3.0;                 // mm
  std::optional<double> scallop_target;     // mm, for L*; default the measured maximum
  double sample_spacing = 0.0;              // mm; 0: a quarter of the typical pass spacing
  std::optional<std::filesystem::path> svg; // top view over a scallop heat map
  std::optional<std::filesystem::path> png; // the same picture as PNG
  std::string name;                         // the part, for the picture's title
  // The tool axis's largest angle from +Z, degrees: samples whose normal leans further are
  // out of reach and are not measured for scallop (gouges and touches still are). A path
  // with a vertical tool (no MULTAX) reaches 90 degrees whatever this says.
  double max_tilt_deg = 90.0;
  // The lowest the ball may go (the floor less the stock margin, assembly_clearance.hpp), mm:
  // samples the ball could touch only from below it are out of reach too (the band round a
  // part's foot), counted apart and not measured for scallop.
  std::optional<double> ball_floor_z;
};

// Samples of the surface inside the ball's sweep over moves that must not cut.
struct MoveTouches {
  long samples = 0;     // deeper than 0.1 um
  double deepest = 0.0; // mm
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
};

struct VerifyReport {
  long samples = 0;
  long uncut_samples = 0;         // not reached by any ball within one radius above the surface
  std::vector<UncutRegion> uncut; // where they lie, largest area first
  long out_of_reach_samples = 0;  // normals beyond the tilt: not measured for scallop
  double out_of_reach_area = 0.0; // mm^2
  double reach_angle_deg = 0.0;   // the normal's angle from +Z beyond which they are
  long below_floor_samples = 0;   // the ball would touch them only under ball_floor_z
  double below_floor_area = 0.0;  // mm^2
  double max_scallop = 0.0, mean_scallop = 0.0, p99_scallop = 0.0; // mm
  Eigen::Vector3d max_at = Eigen::Vector3d::Zero();                // where the worst scallop is, mm
  long gouges = 0;                                                 // of the cutting (feed) moves
  double max_gouge = 0.0;                                          // mm
  Eigen::Vector3d gouge_at = Eigen::Vector3d::Zero();              // where the deepest gouge is
  MoveTouches links;                              // plunges and retracts below the surface
  MoveTouches rapids;                             // rapids touching the part at all
  double path_length = 0.0, cutting_length = 0.0; // mm
  long passes = 0, points = 0;
  double area = 0.0;         // mm^2 of the surface measured
  double ideal_length = 0.0; // L*, mm
};

[[nodiscard]] Expected<VerifyReport> verify_path(const LimitSurface& surface,
                                                 const std::filesystem::path& cl,
                                                 const VerifyOptions& options);

} // namespace subfeed::geometry

#pragma once
// How a modelled part sits on the machine: which model axis points up (toward the spindle),
// what the model's unit is in millimetres, and where the program's zero is on the part.
// Applied once, to the cage, when it is read: scaled first, then turned so that `up` becomes
// +Z, then moved so that the origin point becomes (0, 0, 0). Catmull-Clark subdivision
// commutes with these (it is affine invariant), so the limit surface moves exactly with its
// cage. Every command that reads a cage, a CL file or a job applies or checks the same
// setup; its text form ("up=y scale=10 origin=top-centre") is what CL files and job records
// keep.

#include "base/error.hpp"
#include "geometry/cage.hpp"

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <string_view>

namespace subfeed::geometry {

// The model is turned by a quarter or half turn about a horizontal machine axis, never
// mirrored (faces keep their winding): up x or -x about Y (+X up: the model's -Z becomes +X),
// up y or -y about X (+Y up: the model's +Z becomes -Y), up -z half a turn about X.
enum class UpAxis { x, y, z, neg_x, neg_y, neg_z };

enum class OriginKind {
  model,         // the model's own zero (after turning and scaling)
  top_centre,    // centre of the part's extent in X and Y, at its highest point
  bottom_centre, // centre in X and Y, at its lowest point
  min_corner,    // the extent's lowest X, Y and Z
  point,         // `origin_point`, mm, in the turned and scaled model
};

struct PartSetup {
  UpAxis up = UpAxis::z;
  double scale = 1.0; // millimetres per model unit
  OriginKind origin = OriginKind::model;
  Eigen::Vector3d origin_point = Eigen::Vector3d::Zero();

  [[nodiscard]] bool operator==(const PartSetup&) const = default;
  [[nodiscard]] bool is_identity() const { return *this == PartSetup{}; }
};

// Command-line and record words. Each error names the word and what is accepted.
[[nodiscard]] Expected<UpAxis> parse_up_axis(std::string_view word);
// mm, cm, m or in: millimetres per unit.
[[nodiscard]] Expected<double> parse_units(std::string_view word);
// top-centre, bottom-centre, min-corner, model or X,Y,Z (mm).
[[nodiscard]] Expected<void> parse_origin(std::string_view word, PartSetup& setup);

// "up=y scale=10 origin=top-centre": every field, in that order, numbers in shortest form.
[[nodiscard]] std::string setup_text(const PartSetup& setup);
[[nodiscard]] Expected<PartSetup> parse_setup_text(std::string_view text);
// For messages: "up y, 10 mm per unit, zero at the top centre".
[[nodiscard]] std::string describe_setup(const PartSetup& setup);

// Where the setup put the part: the model point (mm, turned and scaled) that became the
// program zero.
struct SetupResult {
  Eigen::Vector3d zero_in_model = Eigen::Vector3d::Zero();
};

// Moves the cage's control points. The extent for the named origins is the limit surface's,
// sampled 16 times along each face edge, so it may fall short of the true one by the
// sampling sagitta (micrometres on machining-size faces).
[[nodiscard]] Expected<SetupResult> set_up_part(Cage& cage, const PartSetup& setup);

// read_obj() then set_up_part().
[[nodiscard]] Expected<Cage> read_part(const std::filesystem::path& path, const PartSetup& setup);

} // namespace subfeed::geometry

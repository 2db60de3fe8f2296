#include "geometry/limit_surface.hpp"

#include "cage_topology.hpp"

#include <Eigen/Geometry>
#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/tessellation.h>

#include <algorithm>
#include <optional>
#include <string>

namespace subfeed::geometry {

namespace osd = OpenSubdiv;

struct LimitSurface::Patches {
  // One Bfr surface and its patch points (x y z per point) per cage face.
  std::vector<std::optional<osd::Bfr::Surface<double>>> surfaces;
  std::vector<std::vector<double>> patch_points;
  std::vector<int> face_sizes;
  std::string source;
  int approx_level = min_approx_level;
};

namespace {

std::vector<double> flat_positions(const Cage& cage) {
  std::vector<double> flat;
  flat.reserve(cage.positions.size() * 3);
  for (const auto& p : cage.positions) {
    flat.insert(flat.end(), {p.x(), p.y(), p.z()});
  }
  return flat;
}

} // namespace

Expected<LimitSurface> LimitSurface::build(const Cage& cage, int approx_level) {
  if (approx_level < min_approx_level || approx_level > max_approx_level) {
    return fail(ErrorCode::bad_input,
                "approximation level " + std::to_string(approx_level) + " is outside " +
                    std::to_string(min_approx_level) + ".." + std::to_string(max_approx_level),
                {cage.source, 0, {}});
  }
  const auto refiner = make_refiner(cage);
  if (!refiner) {
    return fail(ErrorCode::bad_input, "OpenSubdiv rejected the cage topology",
                {cage.source, 0, {}});
  }
  osd::Bfr::RefinerSurfaceFactory<>::Options options;
  options.SetApproxLevelSmooth(approx_level);
  options.SetApproxLevelSharp(approx_level);
  const osd::Bfr::RefinerSurfaceFactory<> factory(*refiner, options);

  auto patches = std::make_unique<Patches>();
  patches->source = cage.source;
  patches->approx_level = approx_level;
  patches->face_sizes = cage.face_sizes;
  patches->surfaces.resize(cage.face_sizes.size());
  patches->patch_points.resize(cage.face_sizes.size());
  const std::vector<double> mesh_points = flat_positions(cage);
  const osd::Bfr::Surface<double>::PointDescriptor xyz(3);
  for (int f = 0; f < cage.face_count(); ++f) {
    osd::Bfr::Surface<double> surface;
    if (!factory.InitVertexSurface<double>(f, &surface)) {
      continue; // a hole: no limit surface for this face
    }
    auto& points = patches->patch_points[f];
    points.resize(static_cast<std::size_t>(surface.GetNumPatchPoints()) * 3);
    surface.PreparePatchPoints(mesh_points.data(), xyz, points.data(), xyz);
    patches->surfaces[f] = surface;
  }
  return LimitSurface(std::move(patches));
}

LimitSurface::LimitSurface(std::unique_ptr<Patches> patches) : patches_(std::move(patches)) {}
LimitSurface::LimitSurface(LimitSurface&&) noexcept = default;
LimitSurface& LimitSurface::operator=(LimitSurface&&) noexcept = default;
LimitSurface::~LimitSurface() = default;

int LimitSurface::face_count() const {
  return static_cast<int>(patches_->surfaces.size());
}

bool LimitSurface::has_patch(int face) const {
  return face >= 0 && face < face_count() && patches_->surfaces[face].has_value();
}

int LimitSurface::approx_level() const {
  return patches_->approx_level;
}

int LimitSurface::face_size(int face) const {
  return patches_->face_sizes.at(face);
}

namespace {

// The sine of the angle between du and dv. Where it is this small the cross product is
// rounding, not a direction: at an interpolated boundary's valence-2 corner du and dv are
// parallel and their cross product came out horizontal, pointing into or out of the part
// depending on the coordinates' magnitude (a dome lifted 20 mm had its corner normals turned
// 90 degrees inward and its CL points 3 mm inside the part).
constexpr double degenerate_sine = 1e-6;
// Below this the first fundamental form is too ill-conditioned for curvature (its inverse
// amplifies rounding by 1 / sine^2): evaluate_regular looks a hair inside instead.
constexpr double regular_sine = 1e-3;
// How far inside it looks for the derivatives and curvature where it must: at a valence-2
// corner one principal curvature grows as 1 / distance (0.1 /mm a hundredth of the way in,
// 1.1 /mm a ten-thousandth, on a 2 mm grid), so the corner point's own value is no value;
// where du and dv are 3 degrees apart (a few hundredths of the way to the centre, the scale
// of the mesh's cells round it) it is its neighbourhood's.
constexpr double curvature_sine = 0.05;

double tangent_sine(const LimitSample& s) {
  const double scale = s.du.norm() * s.dv.norm();
  return scale > 0.0 ? s.du.cross(s.dv).norm() / scale : 0.0;
}

} // namespace

Expected<LimitSample> LimitSurface::sample(int face, double u, double v) const {
  if (!has_patch(face)) {
    return fail(ErrorCode::bad_input, "face " + std::to_string(face + 1) + " has no limit surface",
                {patches_->source, 0, {}});
  }
  const auto& surface = *patches_->surfaces[face];
  const double uv[2] = {u, v};
  LimitSample s;
  surface.Evaluate(uv, patches_->patch_points[face].data(),
                   osd::Bfr::Surface<double>::PointDescriptor(3), s.point.data(), s.du.data(),
                   s.dv.data(), s.duu.data(), s.duv.data(), s.dvv.data());
  const Eigen::Vector3d cross = s.du.cross(s.dv);
  s.normal = cross.norm() > 0.0 ? Eigen::Vector3d(cross.normalized()) : Eigen::Vector3d::Zero();
  return s;
}

Expected<LimitSample> LimitSurface::evaluate(int face, double u, double v) const {
  SUBFEED_TRY_ASSIGN(auto s, sample(face, u, v));
  if (!(tangent_sine(s) >= degenerate_sine)) {
    return fail(ErrorCode::bad_input,
                "degenerate tangent plane on face " + std::to_string(face + 1) + " at (" +
                    std::to_string(u) + ", " + std::to_string(v) + ")",
                {patches_->source, 0, {}});
  }
  return s;
}

} // namespace subfeed::geometry

namespace subfeed::geometry {

Expected<LimitSample> LimitSurface::evaluate_regular(int face, double u, double v) const {
  SUBFEED_TRY_ASSIGN(const auto exact, sample(face, u, v));
  if (tangent_sine(exact) >= regular_sine) {
    return exact;
  }
  // Toward the face's centre: the normal from the first sample where it is a direction (the
  // limit of the neighbourhood's), the rest from the first where curvature means something.
  std::optional<Eigen::Vector3d> normal;
  for (double nudge = 1e-7; nudge <= 0.2; nudge *= 2.0) {
    SUBFEED_TRY_ASSIGN(auto s, sample(face, u + nudge * (0.5 - u), v + nudge * (0.5 - v)));
    const double sine = tangent_sine(s);
    if (!normal && sine >= degenerate_sine) {
      normal = s.normal;
    }
    if (sine >= curvature_sine) {
      s.point = exact.point;
      s.normal = *normal;
      return s;
    }
  }
  return evaluate(face, u, v);
}

FaceTessellation LimitSurface::tessellate(int face, int rate) const {
  if (!has_patch(face)) {
    return {};
  }
  const auto n = static_cast<std::size_t>(patches_->surfaces[face]->GetFaceSize());
  return tessellate(face, std::vector<int>(n, rate), rate);
}

FaceTessellation LimitSurface::tessellate(int face, const std::vector<int>& edge_rates,
                                          int inner) const {
  FaceTessellation out;
  if (!has_patch(face)) {
    return out;
  }
  std::vector<int> rates;
  for (const int r : edge_rates) {
    rates.push_back(std::clamp(r, 1, 256));
  }
  rates.push_back(std::clamp(inner, 1, 256));
  const osd::Bfr::Tessellation tess(patches_->surfaces[face]->GetParameterization(),
                                    static_cast<int>(rates.size()), rates.data(),
                                    osd::Bfr::Tessellation::Options().SetFacetSize(3));
  std::vector<double> coords(static_cast<std::size_t>(tess.GetNumCoords()) * 2);
  tess.GetCoords(coords.data());
  out.uv.reserve(coords.size() / 2);
  for (std::size_t i = 0; i < coords.size(); i += 2) {
    out.uv.emplace_back(coords[i], coords[i + 1]);
  }
  out.triangles.resize(static_cast<std::size_t>(tess.GetNumFacets()));
  tess.GetFacets(out.triangles.front().data());
  return out;
}

FaceTessellation LimitSurface::tessellate_tiles(int face, int rate) const {
  if (!has_patch(face)) {
    return {};
  }
  const auto parameters = patches_->surfaces[face]->GetParameterization();
  if (!parameters.HasSubFaces()) {
    return tessellate(face, rate);
  }
  // Each tile (a corner's quarter of the face) a grid of its own, half the face's rate.
  const int m = std::max(1, (rate + 1) / 2);
  FaceTessellation out;
  for (int tile = 0; tile < parameters.GetFaceSize(); ++tile) {
    const int first = static_cast<int>(out.uv.size());
    for (int j = 0; j <= m; ++j) {
      for (int i = 0; i <= m; ++i) {
        const double local[2] = {static_cast<double>(i) / m, static_cast<double>(j) / m};
        double uv[2];
        parameters.ConvertNormalizedSubFaceToCoord(tile, local, uv);
        out.uv.emplace_back(uv[0], uv[1]);
      }
    }
    const auto at = [&](int i, int j) { return first + j * (m + 1) + i; };
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < m; ++i) {
        out.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        out.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  }
  return out;
}

} // namespace subfeed::geometry

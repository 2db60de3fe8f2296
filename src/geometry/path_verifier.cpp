#include "geometry/path_verifier.hpp"

#include "geometry/assembly_clearance.hpp"

#include "geometry/closest_point.hpp"
#include "geometry/point_grid.hpp"
#include "geometry/scallop_meter.hpp"
#include "geometry/split_work.hpp"
#include "geometry/step_over.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/uncut_regions.hpp"
#include "geometry/verify_picture.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <iterator>
#include <limits>
#include <numbers>
#include <unordered_map>

namespace subfeed::geometry {

namespace {

struct Path {
  std::vector<Capsule> capsules;                       // feed moves: the cut
  std::vector<Capsule> links, rapids;                  // plunges and retracts; rapids
  std::vector<std::vector<Eigen::Vector2d>> passes_xy; // for the picture
  bool multiaxis = false;                              // the tool axis varies (MULTAX)
};

Expected<Path> read_path(const std::filesystem::path& file, double r, VerifyReport& report) {
  SUBFEED_TRY_ASSIGN(auto reader, cl::ClReader::open(file));
  Path path;
  path.multiaxis = reader.header().multiaxis;
  std::optional<cl::ClPose> last;
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto pose, reader.next());
    if (!pose) {
      break;
    }
    const Eigen::Vector3d tip(pose->tip[0], pose->tip[1], pose->tip[2]);
    const Eigen::Vector3d axis(pose->axis[0], pose->axis[1], pose->axis[2]);
    if (last) {
      const Eigen::Vector3d from(last->tip[0], last->tip[1], last->tip[2]);
      const Eigen::Vector3d from_axis(last->axis[0], last->axis[1], last->axis[2]);
      const double length = (tip - from).norm();
      report.path_length += length;
      const Capsule swept{from + r * from_axis, tip + r * axis, r};
      (pose->kind == cl::MoveKind::feed    ? path.capsules
       : pose->kind == cl::MoveKind::rapid ? path.rapids
                                           : path.links)
          .push_back(swept);
      if (pose->kind == cl::MoveKind::feed) {
        report.cutting_length += length;
      }
    }
    if (pose->kind == cl::MoveKind::plunge) {
      ++report.passes;
      path.passes_xy.emplace_back();
    }
    if (pose->kind == cl::MoveKind::feed || pose->kind == cl::MoveKind::plunge) {
      ++report.points;
      if (path.passes_xy.empty()) {
        path.passes_xy.emplace_back();
      }
      path.passes_xy.back().emplace_back(tip.x(), tip.y());
    }
    last = pose;
  }
  return path;
}

// Capsules by the cells of size `cell` their boxes touch, grown by the capsule radius plus
// `reach`: every capsule a ray of length `reach` from a point in a cell can enter.
class CapsuleGrid {
public:
  CapsuleGrid(const std::vector<Capsule>& capsules, double cell, double reach)
      : capsules_(&capsules), cell_(cell) {
    for (std::size_t i = 0; i < capsules.size(); ++i) {
      const auto& c = capsules[i];
      const Eigen::Vector3d lo = c.a.cwiseMin(c.b).array() - (c.radius + reach);
      const Eigen::Vector3d hi = c.a.cwiseMax(c.b).array() + (c.radius + reach);
      const auto a = grid_cell(lo, cell_), b = grid_cell(hi, cell_);
      for (long long x = a[0]; x <= b[0]; ++x) {
        for (long long y = a[1]; y <= b[1]; ++y) {
          for (long long z = a[2]; z <= b[2]; ++z) {
            cells_[grid_cell_key(x, y, z)].push_back(static_cast<int>(i));
          }
        }
      }
    }
  }
  void near(const Eigen::Vector3d& p, std::vector<Capsule>& out) const {
    out.clear();
    const auto c = grid_cell(p, cell_);
    const auto found = cells_.find(grid_cell_key(c[0], c[1], c[2]));
    if (found != cells_.end()) {
      for (const int i : found->second) {
        out.push_back((*capsules_)[static_cast<std::size_t>(i)]);
      }
    }
  }

private:
  const std::vector<Capsule>* capsules_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

// Unit direction across the nearest pass, in the tangent plane at p.
std::optional<Eigen::Vector3d> across_nearest(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                                              const std::vector<Capsule>& near) {
  double best = 1e300;
  std::optional<Eigen::Vector3d> out;
  for (const auto& c : near) {
    const Eigen::Vector3d d = c.b - c.a;
    if (d.squaredNorm() <= 0.0) {
      continue;
    }
    const double dist = (closest_on_segment(p, c.a, c.b) - p).norm();
    const Eigen::Vector3d across = n.cross(d);
    if (dist < best && across.norm() > 1e-12) {
      best = dist;
      out = across.normalized();
    }
  }
  return out;
}

// Signed radius of normal curvature across the nearest pass; "infinite" (1e300) where no
// pass is near or the surface is flat that way.
double radius_across(const LimitSample& s, const std::vector<Capsule>& near) {
  const auto across = across_nearest(s.point, s.normal, near);
  if (!across) {
    return 1e300;
  }
  const double kappa = across->dot(curvature_matrix(s) * *across);
  return kappa != 0.0 ? -1.0 / kappa : 1e300;
}

struct Sample {
  int face;
  double u, v;
  double height;
};

struct Measurer {
  const LimitSurface& surface;
  const CapsuleGrid& grid;
  double r;
  std::vector<Capsule> near;

  std::optional<ScallopSample> at(int face, double u, double v) {
    const auto s = surface.evaluate_regular(face, u, v);
    if (!s) {
      return std::nullopt;
    }
    grid.near(s->point, near);
    return measure_scallop(s->point, s->normal, near, r);
  }
};

// Golden-section search for the highest scallop across the nearest pass, within +-reach.
double refine(Measurer& m, const Sample& s, double reach, double& gouge) {
  const auto base = m.surface.evaluate_regular(s.face, s.u, s.v);
  if (!base || m.surface.face_size(s.face) != 4) {
    return s.height;
  }
  m.grid.near(base->point, m.near);
  const auto across = across_nearest(base->point, base->normal, m.near);
  if (!across) {
    return s.height;
  }
  Eigen::Matrix<double, 3, 2> j;
  j << base->du, base->dv;
  const Eigen::Vector2d step = (j.transpose() * j).ldlt().solve(j.transpose() * *across);
  const auto height = [&](double x) {
    const double u = std::clamp(s.u + x * step.x(), 0.0, 1.0);
    const double v = std::clamp(s.v + x * step.y(), 0.0, 1.0);
    const auto h = m.at(s.face, u, v);
    if (!h) {
      return 0.0;
    }
    gouge = std::max(gouge, h->gouge_depth);
    return std::isfinite(h->height) ? h->height : 0.0;
  };
  constexpr double phi = 0.6180339887498949;
  double lo = -reach, hi = reach;
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
  double f1 = height(x1), f2 = height(x2);
  for (int i = 0; i < 30; ++i) {
    if (f1 > f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - phi * (hi - lo), f1 = height(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + phi * (hi - lo), f2 = height(x2);
    }
  }
  return std::max({s.height, f1, f2});
}

// How far the surface point p lies inside the sweep of the moves near it (0 outside).
double depth_inside(const CapsuleGrid& grid, const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                    double r, std::vector<Capsule>& near) {
  grid.near(p, near);
  return measure_scallop(p, n, near, r).gouge_depth;
}

void count_touch(double depth, const Eigen::Vector3d& p, MoveTouches& touches) {
  if (depth > 1e-7) { // below 0.1 um: rounding of the CL data, as for gouges
    ++touches.samples;
    if (depth > touches.deepest) {
      touches.deepest = depth;
      touches.at = p;
    }
  }
}

// One measured sample of the surface, with what the report and the picture need of it.
struct Measured {
  Sample sample;         // where, and the scallop first measured there
  Eigen::Vector3d point; // on the surface, mm
  char marked = 0;       // cut more than 1 um below: black in the picture
  double weight = 0.0;   // its share of the surface's area, mm^2
  double radius = 0.0;   // of normal curvature across the nearest pass, for L*
  double height = 0.0;   // the scallop shown: refined near the worst
};

// The samples no ball reached, with their shares of the area; and, for a picture, those
// left out of the scallop for reach (beyond the tilt, under the floor).
struct Uncut {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> areas;
  std::vector<LeftSample> out_of_reach;
};

// The grids the samples are measured against, built once.
struct Sweeps {
  CapsuleGrid cuts, links, rapids;
  double reach_z; // a normal with less z than this is out of reach
  double r;
  double ball_floor_z; // mm: a ball touching a sample may not reach under this
  bool pictured;       // a picture is drawn: keep the samples out of reach for it
};

// Each sample stands for a third of the area of the triangles around it (taken on the
// surface, as n-gon faces are parameterised by sub-faces).
std::vector<double> area_shares(const FaceTessellation& tess,
                                const std::vector<std::optional<LimitSample>>& evaluated) {
  std::vector<double> share(tess.uv.size(), 0.0);
  for (const auto& t : tess.triangles) {
    const auto& a = evaluated[static_cast<std::size_t>(t[0])];
    const auto& b = evaluated[static_cast<std::size_t>(t[1])];
    const auto& c = evaluated[static_cast<std::size_t>(t[2])];
    if (a && b && c) {
      const double third = (b->point - a->point).cross(c->point - a->point).norm() / 6.0;
      for (const int k : t) {
        share[static_cast<std::size_t>(k)] += third;
      }
    }
  }
  return share;
}

// Measures one sample against every sweep: counts it in the report, and keeps it unless no
// ball reached it.
void measure_sample(const Sweeps& sweeps, Measurer& m, std::vector<Capsule>& near_moves,
                    const LimitSample& s, const Sample& where, double share, VerifyReport& report,
                    std::vector<Measured>& kept, Uncut& uncut) {
  const double r = sweeps.r;
  sweeps.cuts.near(s.point, m.near);
  const auto h = measure_scallop(s.point, s.normal, m.near, r);
  ++report.samples;
  count_touch(depth_inside(sweeps.links, s.point, s.normal, r, near_moves), s.point, report.links);
  count_touch(depth_inside(sweeps.rapids, s.point, s.normal, r, near_moves), s.point,
              report.rapids);
  if (h.gouge_depth > 1e-7) { // below 0.1 um: rounding of the CL data
    ++report.gouges;
    if (h.gouge_depth > report.max_gouge) {
      report.max_gouge = h.gouge_depth;
      report.gouge_at = s.point;
    }
  }
  if (s.normal.z() < sweeps.reach_z) {
    ++report.out_of_reach_samples;
    report.out_of_reach_area += share;
    if (sweeps.pictured) {
      uncut.out_of_reach.push_back({s.point, LeftUncut::beyond_tilt});
    }
    return;
  }
  if ((s.point + r * s.normal).z() - r <
      sweeps.ball_floor_z - AssemblyClearance::floor_tolerance_mm) {
    ++report.below_floor_samples;
    report.below_floor_area += share;
    if (sweeps.pictured) {
      uncut.out_of_reach.push_back({s.point, LeftUncut::below_floor});
    }
    return;
  }
  if (!std::isfinite(h.height)) {
    ++report.uncut_samples;
    uncut.points.push_back(s.point);
    uncut.areas.push_back(share);
    return;
  }
  Sample sample = where;
  sample.height = h.height;
  kept.push_back({sample, s.point, static_cast<char>(h.gouge_depth > 1e-3 ? 1 : 0), share,
                  radius_across(s, m.near), h.height});
}

// One face's samples, `spacing` apart, measured into its own report and lists.
struct FaceMeasured {
  VerifyReport report;
  std::vector<Measured> kept;
  Uncut uncut;
};

FaceMeasured measure_face(const LimitSurface& surface, const Sweeps& sweeps, Measurer& m,
                          std::vector<Capsule>& near_moves, double spacing, int f) {
  FaceMeasured out;
  const auto centre = surface.evaluate_regular(f, 0.5, 0.5);
  const double extent = centre ? std::max(centre->du.norm(), centre->dv.norm()) : 1.0;
  const int rate = std::clamp(static_cast<int>(std::ceil(extent / spacing)), 2, 256);
  const auto tess = surface.tessellate(f, rate);
  std::vector<std::optional<LimitSample>> evaluated;
  for (const auto& uv : tess.uv) {
    auto e = surface.evaluate_regular(f, uv.x(), uv.y());
    evaluated.push_back(e ? std::optional<LimitSample>(*e) : std::nullopt);
  }
  const auto share = area_shares(tess, evaluated);
  for (std::size_t k = 0; k < tess.uv.size(); ++k) {
    if (evaluated[k]) {
      measure_sample(sweeps, m, near_moves, *evaluated[k], {f, tess.uv[k].x(), tess.uv[k].y(), 0.0},
                     share[k], out.report, out.kept, out.uncut);
    }
  }
  return out;
}

void add_touches(const MoveTouches& from, MoveTouches& to) {
  to.samples += from.samples;
  if (from.deepest > to.deepest) {
    to.deepest = from.deepest;
    to.at = from.at;
  }
}

// A face's counts added to the whole's, in face order: the worst found first stays, as
// measuring face after face on one thread would keep it.
void add_face(FaceMeasured& face, VerifyReport& report, std::vector<Measured>& kept, Uncut& uncut) {
  const auto& r = face.report;
  report.samples += r.samples;
  report.out_of_reach_samples += r.out_of_reach_samples;
  report.out_of_reach_area += r.out_of_reach_area;
  report.below_floor_samples += r.below_floor_samples;
  report.below_floor_area += r.below_floor_area;
  report.uncut_samples += r.uncut_samples;
  report.gouges += r.gouges;
  if (r.max_gouge > report.max_gouge) {
    report.max_gouge = r.max_gouge;
    report.gouge_at = r.gouge_at;
  }
  add_touches(r.links, report.links);
  add_touches(r.rapids, report.rapids);
  std::ranges::move(face.kept, std::back_inserter(kept));
  std::ranges::move(face.uncut.points, std::back_inserter(uncut.points));
  std::ranges::move(face.uncut.areas, std::back_inserter(uncut.areas));
  std::ranges::move(face.uncut.out_of_reach, std::back_inserter(uncut.out_of_reach));
}

// Every face's samples, `spacing` apart, measured, the faces shared between the cores.
std::vector<Measured> measure_surface(const LimitSurface& surface, const Sweeps& sweeps,
                                      const Measurer& m, double spacing, VerifyReport& report,
                                      std::vector<LeftSample>& left) {
  std::vector<FaceMeasured> faces(static_cast<std::size_t>(surface.face_count()));
  split_work(
      faces.size(),
      [&](std::size_t begin, std::size_t end) {
        Measurer own{m.surface, m.grid, m.r, {}};
        std::vector<Capsule> near_moves;
        for (std::size_t f = begin; f < end; ++f) {
          if (surface.has_patch(static_cast<int>(f))) {
            faces[f] = measure_face(surface, sweeps, own, near_moves, spacing, static_cast<int>(f));
          }
        }
      },
      1);
  std::vector<Measured> kept;
  Uncut uncut;
  for (auto& face : faces) {
    add_face(face, report, kept, uncut);
  }
  // Neighbouring samples lie about `spacing` apart (a face's rate follows its size at its
  // centre, so a little more where it stretches): three spacings join a region, not two.
  report.uncut = uncut_regions(uncut.points, uncut.areas, 3.0 * spacing);
  if (sweeps.pictured) {
    left = std::move(uncut.out_of_reach);
    for (const auto& p : uncut.points) {
      left.push_back({p, LeftUncut::no_ball});
    }
  }
  return kept;
}

// Mean and 99th percentile of the samples as first measured; then the worst, refined where
// a sample came within half of the coarse worst (the cusp may lie between samples).
void summarise_heights(const Measurer& m, double spacing, std::vector<Measured>& kept,
                       VerifyReport& report) {
  std::vector<double> sorted;
  double sum = 0.0;
  for (const auto& k : kept) {
    sorted.push_back(k.sample.height);
    sum += k.sample.height;
  }
  std::ranges::sort(sorted);
  const double coarse_max = sorted.empty() ? 0.0 : sorted.back();
  report.mean_scallop = kept.empty() ? 0.0 : sum / static_cast<double>(kept.size());
  report.p99_scallop = sorted.empty() ? 0.0 : sorted[sorted.size() * 99 / 100];
  report.max_scallop = 0.0;
  // Refined on both cores, then the worst taken in order, as one thread would.
  const auto refined = [&](const Measured& k) { return k.sample.height >= 0.5 * coarse_max; };
  std::vector<double> gouges(kept.size(), 0.0);
  split_work(kept.size(), [&](std::size_t begin, std::size_t end) {
    Measurer own{m.surface, m.grid, m.r, {}};
    for (std::size_t i = begin; i < end; ++i) {
      if (refined(kept[i])) {
        kept[i].height = refine(own, kept[i].sample, spacing, gouges[i]);
      }
    }
  });
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (refined(kept[i])) {
      if (kept[i].height > report.max_scallop) {
        report.max_scallop = kept[i].height;
        report.max_at = kept[i].point;
      }
      report.max_gouge = std::max(report.max_gouge, gouges[i]);
    }
  }
}

// The area measured and the ideal length L* for a scallop of `h` (docs/METHOD.md §5).
void add_ideal_length(double r, double h, const std::vector<Measured>& kept, VerifyReport& report) {
  for (const auto& k : kept) {
    report.area += k.weight;
    const double rho = k.radius;
    const double w = std::abs(rho) > 1e9        ? flat_step(r, h)
                     : (rho < 0.0 && -rho <= r) ? 0.0
                                                : contact_step(r, h, rho);
    if (w > 0.0 && h > 0.0) {
      report.ideal_length += k.weight / w;
    }
  }
}

Expected<void> draw_pictures(const VerifyOptions& options, const std::vector<Measured>& kept,
                             std::vector<LeftSample> left, const Path& path,
                             const VerifyReport& report) {
  if (!options.svg && !options.png) {
    return {};
  }
  VerifyPicture picture;
  for (const auto& k : kept) {
    picture.points.push_back(k.point);
    picture.heights.push_back(k.height);
    picture.gouged.push_back(k.marked);
  }
  picture.max_height = report.max_scallop;
  picture.name = options.name;
  picture.target = options.scallop_target;
  picture.passes_xy = path.passes_xy;
  picture.left = std::move(left);
  if (options.svg) {
    SUBFEED_TRY(write_svg(*options.svg, picture));
  }
  if (options.png) {
    SUBFEED_TRY(write_png(*options.png, picture));
  }
  return {};
}

} // namespace

Expected<VerifyReport> verify_path(const LimitSurface& surface, const std::filesystem::path& cl,
                                   const VerifyOptions& options) {
  VerifyReport report;
  const double r = options.ball_radius;
  SUBFEED_TRY_ASSIGN(const auto path, read_path(cl, r, report));
  if (path.capsules.empty()) {
    return fail(ErrorCode::bad_input, "no cutting moves in the CL data", {cl.string(), 0, {}});
  }
  // Rays look for material up to one radius above the surface.
  report.reach_angle_deg = path.multiaxis ? options.max_tilt_deg : 90.0;
  // A normal exactly at the limit (a vertical wall at 90) is in reach: rounding must not
  // take it out.
  const double reach_z = std::cos(report.reach_angle_deg * std::numbers::pi / 180.0) - 1e-9;
  const Sweeps sweeps{CapsuleGrid(path.capsules, r, r),
                      CapsuleGrid(path.links, r, r),
                      CapsuleGrid(path.rapids, r, r),
                      reach_z,
                      r,
                      options.ball_floor_z.value_or(-std::numeric_limits<double>::infinity()),
                      options.svg.has_value() || options.png.has_value()};
  const double spacing = options.sample_spacing > 0.0 ? options.sample_spacing : r / 30.0;
  Measurer m{surface, sweeps.cuts, r, {}};
  std::vector<LeftSample> left;
  auto kept = measure_surface(surface, sweeps, m, spacing, report, left);
  summarise_heights(m, spacing, kept, report);
  add_ideal_length(r, options.scallop_target.value_or(report.max_scallop), kept, report);
  SUBFEED_TRY(draw_pictures(options, kept, std::move(left), path, report));
  return report;
}

} // namespace subfeed::geometry

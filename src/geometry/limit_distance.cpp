#include "geometry/limit_distance.hpp"

#include "geometry/ball_lift.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/triangle_tree.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

namespace subfeed::geometry {

// Named, not anonymous: LimitDistance::Guide holds these, and a unity build would warn that
// a class with external linkage has a member of a type only this file can name.
namespace limit_distance_detail {

// One guide triangle's (u, v) triangle in its face's domain: uv0 + a e1 + b e2 with
// a, b >= 0, a + b <= 1.
struct PatchPiece {
  int face = -1;
  Eigen::Vector2d uv0, e1, e2;
  [[nodiscard]] Eigen::Vector2d at(double a, double b) const { return uv0 + a * e1 + b * e2; }
};

} // namespace limit_distance_detail

using limit_distance_detail::PatchPiece;

namespace {

// The bound is twice the largest stray sampled inside a triangle (its edge midpoints and
// centroid): a quadratic that vanishes at the corners strays at most 4/3 of its largest
// midpoint value, and a bicubic patch over a small triangle is nearly quadratic.
constexpr double bound_factor = 2.0;
constexpr double bound_floor_mm = 1e-7;
constexpr int most_iterations = 30;
// mm a lifted ball ends clear of the point it met: well above Newton's precision, so the
// check that nothing else is inside needs no more than a step or two on each piece near.
constexpr double lift_slack_mm = 1e-7;

// The least of the convex quadratic 1/2 y'Hy + h'y over the prism a, b >= 0, a + b <= 1,
// 0 <= t <= 1 (n = 3) or the triangle alone (n = 2). The free least where it is feasible;
// else each face, edge and corner of the feasible set (the least of the quadratic on the
// affine span of a set of active constraints), the feasible one lowest kept: the least over
// a convex set lies on the span of its own active set. At most 20 small solves.
template <int N> struct PrismQp {
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  // One active set: y = origin + basis * w, w free (`free` columns of basis used).
  struct Span {
    Vec origin;
    Mat basis;
    int free = 0;
  };

  static std::vector<Span> spans() {
    // The triangle's faces in (a, b): its inside, three edges, three corners.
    struct Flat {
      Eigen::Vector2d origin;
      Eigen::Matrix2d basis;
      int free;
    };
    std::vector<Flat> flats;
    flats.push_back({{0, 0}, Eigen::Matrix2d::Identity(), 2});
    Eigen::Matrix2d m;
    m << 0, 0, 1, 0; // a = 0: b free
    flats.push_back({{0, 0}, m, 1});
    m << 1, 0, 0, 0; // b = 0: a free
    flats.push_back({{0, 0}, m, 1});
    m << -1, 0, 1, 0; // a + b = 1: from (1, 0) along (-1, 1)
    flats.push_back({{1, 0}, m, 1});
    for (const Eigen::Vector2d& corner : {Eigen::Vector2d(0, 0), {1, 0}, {0, 1}}) {
      flats.push_back({corner, Eigen::Matrix2d::Zero(), 0});
    }
    std::vector<Span> out;
    for (const auto& f : flats) {
      if constexpr (N == 2) {
        out.push_back({f.origin, f.basis, f.free});
      } else {
        // t free, or held at 0 or 1.
        for (int t = 0; t < 3; ++t) {
          Span s{Vec::Zero(), Mat::Zero(), 0};
          s.origin.template head<2>() = f.origin;
          s.origin[2] = t == 2 ? 1.0 : 0.0;
          s.basis.template topLeftCorner<2, 2>() = f.basis;
          s.free = f.free;
          if (t == 0) {
            s.basis.col(f.free).setZero();
            s.basis(2, f.free) = 1.0;
            ++s.free;
          }
          if (!(f.free == 2 && t == 0)) { // the free least is tried first, on its own
            out.push_back(s);
          }
        }
      }
    }
    if constexpr (N == 2) {
      out.erase(out.begin()); // the free least, likewise
    }
    return out;
  }

  static bool feasible(const Vec& y) {
    constexpr double slack = 1e-12;
    bool ok = y[0] >= -slack && y[1] >= -slack && y[0] + y[1] <= 1.0 + slack;
    if constexpr (N == 3) {
      ok = ok && y[2] >= -slack && y[2] <= 1.0 + slack;
    }
    return ok;
  }
  static Vec clamp(Vec y) {
    y[0] = std::max(y[0], 0.0);
    y[1] = std::max(y[1], 0.0);
    if (const double s = y[0] + y[1]; s > 1.0) {
      y[0] /= s, y[1] /= s;
    }
    if constexpr (N == 3) {
      y[2] = std::clamp(y[2], 0.0, 1.0);
    }
    return y;
  }
  static Vec solve(const Mat& H, const Vec& h, const Vec& fallback) {
    static const std::vector<Span> all = spans();
    const Vec free = H.ldlt().solve(-h);
    if (feasible(free)) {
      return free;
    }
    const auto value = [&](const Vec& y) { return 0.5 * y.dot(H * y) + h.dot(y); };
    Vec best = clamp(fallback);
    double best_value = value(best);
    for (const auto& s : all) {
      Vec y = s.origin;
      const Vec grad = H * s.origin + h;
      if (s.free == 1) {
        const Vec z = s.basis.col(0);
        const double curvature = z.dot(H * z);
        if (curvature > 0.0) {
          y -= (z.dot(grad) / curvature) * z;
        }
      } else if (s.free == 2) {
        const Eigen::Matrix<double, N, 2> Z = s.basis.template leftCols<2>();
        const Eigen::Matrix2d reduced = Z.transpose() * H * Z;
        const double det = reduced.determinant();
        if (det > 0.0) {
          y -= Z * (reduced.inverse() * (Z.transpose() * grad));
        }
      }
      if (feasible(y)) {
        if (const double v = value(y); v < best_value) {
          best = y, best_value = v;
        }
      }
    }
    return best;
  }
};

struct PieceSample {
  Eigen::Vector3d point, da, db, daa, dab, dbb;
};

std::optional<PieceSample> evaluate_piece(const LimitSurface& surface, const PatchPiece& piece,
                                          double a, double b) {
  const Eigen::Vector2d uv = piece.at(a, b);
  const auto s = surface.evaluate_regular(piece.face, uv.x(), uv.y());
  if (!s) {
    return std::nullopt;
  }
  const Eigen::Vector2d& e1 = piece.e1;
  const Eigen::Vector2d& e2 = piece.e2;
  PieceSample e;
  e.point = s->point;
  e.da = e1.x() * s->du + e1.y() * s->dv;
  e.db = e2.x() * s->du + e2.y() * s->dv;
  e.daa = e1.x() * e1.x() * s->duu + 2.0 * e1.x() * e1.y() * s->duv + e1.y() * e1.y() * s->dvv;
  e.dbb = e2.x() * e2.x() * s->duu + 2.0 * e2.x() * e2.y() * s->duv + e2.y() * e2.y() * s->dvv;
  e.dab = e1.x() * e2.x() * s->duu + (e1.x() * e2.y() + e1.y() * e2.x()) * s->duv +
          e1.y() * e2.y() * s->dvv;
  return e;
}

// Newton for the least of |S(a, b) - (p + t d)| over one piece (and t in [0, 1] when d is
// not zero), from (a, b, t) = x. It gives up as soon as the piece cannot come nearer than
// `beat` (mm): when even twice the fall its quadratic model predicts would not take it
// there (then the distance is infinity). None where Bfr cannot evaluate the piece.
template <int N>
std::optional<LimitNearest> refine_piece(const LimitSurface& surface, const PatchPiece& piece,
                                         const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                                         Eigen::Matrix<double, N, 1> x, double beat) {
  using Qp = PrismQp<N>;
  using Vec = typename Qp::Vec;
  using Mat = typename Qp::Mat;
  const auto segment_at = [&](const Vec& y) -> Eigen::Vector3d {
    if constexpr (N == 3) {
      return p + y[2] * d;
    } else {
      return p;
    }
  };
  x = Qp::clamp(x);
  auto e = evaluate_piece(surface, piece, x[0], x[1]);
  for (int iteration = 0; e && iteration < most_iterations; ++iteration) {
    const Eigen::Vector3d r = e->point - segment_at(x);
    Eigen::Matrix<double, 3, N> J;
    J.col(0) = e->da;
    J.col(1) = e->db;
    if constexpr (N == 3) {
      J.col(2) = -d;
    }
    const Vec g = J.transpose() * r;
    Mat H = J.transpose() * J;
    Mat second = Mat::Zero();
    second(0, 0) = r.dot(e->daa);
    second(0, 1) = second(1, 0) = r.dot(e->dab);
    second(1, 1) = r.dot(e->dbb);
    if (const Mat full = H + second; full.llt().info() == Eigen::Success) {
      H = full;
    } else {
      H += Mat::Identity() * (1e-12 + 1e-9 * H.trace());
    }
    // The step's model in absolute coordinates: 1/2 y'Hy + (g - Hx)'y.
    const Vec step = Qp::solve(H, g - H * x, x) - x;
    const double f0 = 0.5 * r.squaredNorm();
    const double d0 = std::sqrt(2.0 * f0);
    const double predicted =
        std::sqrt(std::max(0.0, 2.0 * (f0 + g.dot(step) + 0.5 * step.dot(H * step))));
    if (d0 - 2.0 * (d0 - predicted) - 0.1 * LimitDistance::precision_mm > beat) {
      return LimitNearest{std::numeric_limits<double>::infinity(), segment_at(x), e->point,
                          piece.face, piece.at(x[0], x[1])};
    }
    // Halved until the distance does not grow (the evaluation kept for the next step).
    double alpha = 1.0;
    std::optional<PieceSample> next;
    for (int halving = 0; halving < 12; ++halving, alpha *= 0.5) {
      const Vec y = x + alpha * step;
      next = evaluate_piece(surface, piece, y[0], y[1]);
      if (next && 0.5 * (next->point - segment_at(y)).squaredNorm() <= f0) {
        break;
      }
      next.reset();
    }
    if (!next) {
      break; // no step lowers it: x is the least to rounding
    }
    x += alpha * step;
    e = next;
    if ((J * (alpha * step)).norm() < LimitDistance::precision_mm) {
      break;
    }
  }
  if (!e) {
    return std::nullopt;
  }
  const Eigen::Vector3d on_segment = segment_at(x);
  return LimitNearest{(e->point - on_segment).norm(), on_segment, e->point, piece.face,
                      piece.at(x[0], x[1])};
}

// (a, b) of point m in the triangle ABC (m on it, or nearly).
Eigen::Vector2d triangle_coordinates(const Eigen::Vector3d& m, const Eigen::Vector3d& A,
                                     const Eigen::Vector3d& B, const Eigen::Vector3d& C) {
  const Eigen::Vector3d e1 = B - A, e2 = C - A, w = m - A;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) {
    return {1.0 / 3.0, 1.0 / 3.0};
  }
  const double w1 = w.dot(e1), w2 = w.dot(e2);
  return {(d22 * w1 - d12 * w2) / det, (d11 * w2 - d12 * w1) / det};
}

} // namespace

struct LimitDistance::Guide {
  LimitSurface surface;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  std::vector<PatchPiece> pieces; // per triangle
  std::vector<double> bounds;     // per triangle, mm
  double largest_bound = 0.0;
  std::unique_ptr<TriangleTree> tree;

  explicit Guide(LimitSurface s) : surface(std::move(s)) {}
  void add_face(int face, int rate);
};

void LimitDistance::Guide::add_face(int face, int rate) {
  const auto tess = surface.tessellate_tiles(face, rate);
  const int first = static_cast<int>(points.size());
  for (const auto& uv : tess.uv) {
    const auto s = surface.evaluate_regular(face, uv.x(), uv.y());
    // A point Bfr cannot evaluate is taken from its neighbours' tessellation; it never
    // happens on a validated cage, and a guide point off the surface only widens a bound.
    points.push_back(s ? s->point : (points.empty() ? Eigen::Vector3d::Zero() : points.back()));
  }
  for (const auto& t : tess.triangles) {
    const auto& uv0 = tess.uv[static_cast<std::size_t>(t[0])];
    const PatchPiece piece{face, uv0, tess.uv[static_cast<std::size_t>(t[1])] - uv0,
                           tess.uv[static_cast<std::size_t>(t[2])] - uv0};
    const std::array<int, 3> corners{first + t[0], first + t[1], first + t[2]};
    const auto& A = points[static_cast<std::size_t>(corners[0])];
    const auto& B = points[static_cast<std::size_t>(corners[1])];
    const auto& C = points[static_cast<std::size_t>(corners[2])];
    double stray = 0.0;
    for (const auto& [a, b] : std::array<std::pair<double, double>, 4>{
             {{0.5, 0.0}, {0.0, 0.5}, {0.5, 0.5}, {1.0 / 3.0, 1.0 / 3.0}}}) {
      const Eigen::Vector2d uv = piece.at(a, b);
      if (const auto s = surface.evaluate_regular(face, uv.x(), uv.y())) {
        stray = std::max(stray, (s->point - closest_on_triangle(s->point, A, B, C)).norm());
      }
    }
    const double bound = bound_factor * stray + bound_floor_mm;
    largest_bound = std::max(largest_bound, bound);
    triangles.push_back(corners);
    pieces.push_back(piece);
    bounds.push_back(bound);
  }
}

LimitDistance::LimitDistance(std::unique_ptr<Guide> guide) : guide_(std::move(guide)) {}
LimitDistance::LimitDistance(LimitDistance&&) noexcept = default;
LimitDistance& LimitDistance::operator=(LimitDistance&&) noexcept = default;
LimitDistance::~LimitDistance() = default;

Expected<LimitDistance> LimitDistance::build(const Cage& cage,
                                             const LimitDistanceOptions& options) {
  if (!(options.guide_chord_mm > 0.0) || options.max_rate < 1) {
    return fail(ErrorCode::bad_input, "the limit distance needs a guide chord and rate above 0");
  }
  SUBFEED_TRY_ASSIGN(auto surface, LimitSurface::build(cage, options.approx_level));
  auto guide = std::make_unique<Guide>(std::move(surface));
  const auto rates = rates_for_tolerance(guide->surface, options.guide_chord_mm, options.max_rate);
  for (int f = 0; f < guide->surface.face_count(); ++f) {
    if (guide->surface.has_patch(f)) {
      guide->add_face(f, rates[static_cast<std::size_t>(f)]);
    }
  }
  guide->tree = std::make_unique<TriangleTree>(guide->points, guide->triangles, guide->bounds);
  return LimitDistance(std::move(guide));
}

std::optional<LimitNearest> LimitDistance::nearest(const Eigen::Vector3d& p,
                                                   const Eigen::Vector3d& q, double limit) const {
  const Guide& g = *guide_;
  std::optional<LimitNearest> best;
  double best_distance = limit;
  double bound = limit; // the tree's triangles are grown by their bounds
  const Eigen::Vector3d d = q - p;
  const bool point = d.squaredNorm() == 0.0;
  g.tree->segment_search(p, q, bound, [&](int t, const SegmentTriangleNearest& m) {
    const auto u = static_cast<std::size_t>(t);
    if (m.distance() - g.bounds[u] >= best_distance) {
      return;
    }
    const auto& tri = g.triangles[u];
    const Eigen::Vector2d ab = triangle_coordinates(
        m.on_triangle, g.points[static_cast<std::size_t>(tri[0])],
        g.points[static_cast<std::size_t>(tri[1])], g.points[static_cast<std::size_t>(tri[2])]);
    std::optional<LimitNearest> exact;
    if (point) {
      exact = refine_piece<2>(g.surface, g.pieces[u], p, d, Eigen::Vector2d(ab), best_distance);
    } else {
      const double t0 = std::clamp((m.on_segment - p).dot(d) / d.squaredNorm(), 0.0, 1.0);
      exact = refine_piece<3>(g.surface, g.pieces[u], p, d, Eigen::Vector3d(ab.x(), ab.y(), t0),
                              best_distance);
    }
    if (!exact) { // not evaluable there: the guide's own bound stands in, on the safe side
      exact = LimitNearest{m.distance() - g.bounds[u], m.on_segment, m.on_triangle,
                           g.pieces[u].face, g.pieces[u].at(ab.x(), ab.y())};
    }
    if (exact->distance < best_distance) {
      best_distance = exact->distance;
      best = exact;
      bound = best_distance;
    }
  });
  return best;
}

double LimitDistance::lift(const Eigen::Vector3d& centre, const Eigen::Vector3d& dir,
                           double radius) const {
  return lift_ball(
      [this](const Eigen::Vector3d& at, double limit) -> std::optional<Eigen::Vector3d> {
        if (const auto found = nearest(at, limit)) {
          return found->on_surface;
        }
        return std::nullopt;
      },
      centre, dir, radius, lift_slack_mm);
}

std::optional<Eigen::Vector3d> LimitDistance::pushed_clear(const Eigen::Vector3d& centre,
                                                          double radius) const {
  // Between two walls nearer than the ball's diameter the pushes alternate: a few rounds
  // settle every ball that fits.
  constexpr int rounds = 4;
  Eigen::Vector3d c = centre;
  for (int round = 0; round < rounds; ++round) {
    const auto near = nearest(c, radius);
    if (!near) {
      return c;
    }
    const Eigen::Vector3d out = c - near->on_surface;
    if (out.norm() <= 0.0) {
      return std::nullopt;
    }
    c = near->on_surface + (radius + lift_slack_mm) * out.normalized();
  }
  return nearest(c, radius) ? std::nullopt : std::optional{c};
}

double LimitDistance::lowest_z_under(const Eigen::Vector3d& start) const {
  // The foot of a point depth d below a bottom of curvature k sits 1 / (1 + d k) of the way
  // from the lowest point to straight above the query: two rounds from a metre down leave it
  // far under a nanometre high on any part (and exact on a flat bottom).
  constexpr double depth_mm = 1000.0;
  Eigen::Vector3d at = start;
  for (int round = 0; round < 2; ++round) {
    const auto foot = nearest(at - depth_mm * Eigen::Vector3d::UnitZ(), 2.0 * depth_mm);
    if (!foot) {
      break;
    }
    at = foot->on_surface;
  }
  return std::min(at.z(), start.z());
}

long LimitDistance::guide_triangles() const {
  return static_cast<long>(guide_->triangles.size());
}

double LimitDistance::largest_bound() const {
  return guide_->largest_bound;
}

const LimitSurface& LimitDistance::surface() const {
  return guide_->surface;
}

} // namespace subfeed::geometry

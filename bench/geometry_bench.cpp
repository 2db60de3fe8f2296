// Geometry throughput: reading and validating a large cage against reading its lines alone,
// and limit-surface evaluation through LimitSurface against OpenSubdiv's Bfr called directly.

#include "bench_harness.hpp"
#include "wavy_cage.hpp"

#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <sstream>

namespace {

using namespace subfeed;

std::string wavy_grid(int n) {
  return bench::wavy_grid_obj(n, 1.0, 1.0);
}

void bench_obj_reader() {
  const std::string text = wavy_grid(400);
  const double megabytes = static_cast<double>(text.size()) / 1e6;
  const double parse = bench::best_seconds(3, [&] {
    std::istringstream in(text);
    auto cage = geometry::parse_obj(in, "bench.obj");
    bench::keep(cage);
  });
  const double lines = bench::best_seconds(3, [&] {
    std::istringstream in(text);
    std::string line;
    std::size_t count = 0;
    while (std::getline(in, line)) {
      count += line.size();
    }
    bench::keep(count);
  });
  bench::report({"obj read+validate (160k quads)", megabytes / parse, "MB/s", "getline only",
                 megabytes / lines});
}

// Bfr directly: the same work LimitSurface::evaluate does, without its checks and normal.
double bfr_direct_rate(const geometry::Cage& cage, int evaluations) {
  namespace osd = OpenSubdiv;
  osd::Far::TopologyDescriptor desc;
  desc.numVertices = cage.vertex_count();
  desc.numFaces = cage.face_count();
  desc.numVertsPerFace = cage.face_sizes.data();
  desc.vertIndicesPerFace = cage.face_indices.data();
  osd::Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = osd::Far::TopologyRefinerFactory<osd::Far::TopologyDescriptor>;
  std::unique_ptr<osd::Far::TopologyRefiner> refiner(
      Factory::Create(desc, Factory::Options(osd::Sdc::SCHEME_CATMARK, sdc)));
  osd::Bfr::RefinerSurfaceFactory<>::Options options;
  options.SetApproxLevelSmooth(4);
  const osd::Bfr::RefinerSurfaceFactory<> factory(*refiner, options);
  std::vector<double> mesh;
  for (const auto& p : cage.positions) {
    mesh.insert(mesh.end(), {p.x(), p.y(), p.z()});
  }
  const osd::Bfr::Surface<double>::PointDescriptor xyz(3);
  std::vector<osd::Bfr::Surface<double>> surfaces(cage.face_sizes.size());
  std::vector<std::vector<double>> points(cage.face_sizes.size());
  for (int f = 0; f < cage.face_count(); ++f) {
    factory.InitVertexSurface<double>(f, &surfaces[f]);
    points[f].resize(static_cast<std::size_t>(surfaces[f].GetNumPatchPoints()) * 3);
    surfaces[f].PreparePatchPoints(mesh.data(), xyz, points[f].data(), xyz);
  }
  const double seconds = bench::best_seconds(3, [&] {
    double sum = 0.0;
    for (int k = 0; k < evaluations; ++k) {
      const int f = k % cage.face_count();
      const double uv[2] = {(k % 97) / 97.0, (k % 89) / 89.0};
      double p[3], du[3], dv[3], duu[3], duv[3], dvv[3];
      surfaces[f].Evaluate(uv, points[f].data(), xyz, p, du, dv, duu, duv, dvv);
      sum += p[2];
    }
    bench::keep(sum);
  });
  return evaluations / seconds;
}

void bench_limit_evaluation() {
  std::istringstream in(wavy_grid(60));
  const auto cage = geometry::parse_obj(in, "bench.obj").value();
  const auto surface = geometry::LimitSurface::build(cage).value();
  constexpr int evaluations = 2'000'000;
  const double seconds = bench::best_seconds(3, [&] {
    double sum = 0.0;
    for (int k = 0; k < evaluations; ++k) {
      const auto s = surface.evaluate(k % cage.face_count(), (k % 97) / 97.0, (k % 89) / 89.0);
      sum += s->normal.z();
    }
    bench::keep(sum);
  });
  bench::report({"limit eval (point, d1, d2, normal)", evaluations / seconds, "evals/s",
                 "Bfr Evaluate direct", bfr_direct_rate(cage, evaluations)});
}

} // namespace

int main() {
  bench_obj_reader();
  bench_limit_evaluation();
}

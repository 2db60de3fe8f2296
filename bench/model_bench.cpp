// Real models: a generated body shell of 1,600 faces (Y up, centimetres, creases, extraordinary
// vertices; bench/body_cage.hpp), set up as a user would, planned at ball 6 against the number
// of cage faces (1x, 4x, 16x: the same limit surface, its cage subdivided) and against the
// scallop height H (0.04, 0.02, 0.01). Each plan runs in its own process, so its peak memory
// is its own, and is stopped after SUBFEED_BENCH_LIMIT_S seconds (default 600). Baseline:
// meshing the limit surface alone, in the same way. Aims (issue 22): under 60 s and 1 GiB at
// 1x and H 0.01, and time growing with the work (area over step-over), not with the faces.
// SUBFEED_BENCH_WRITE_OBJ=FILE also writes the shell's cage there.

#include "bench_harness.hpp"
#include "body_cage.hpp"

#include "geometry/cage_refinement.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/part_setup.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/toolpath_planner.hpp"

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using namespace subfeed;

struct Measured {
  bool finished = false;
  double seconds = 0.0;
  double peak_mib = 0.0;
};

// Runs `work` in a child process, stopped after `limit_s`: its wall time and peak memory.
template <class Work> Measured in_child(double limit_s, Work&& work) {
  std::fflush(stdout); // or the child's copy of the buffer is printed twice
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  if (child == 0) {
    alarm(static_cast<unsigned>(std::ceil(limit_s)));
    _exit(work() ? 0 : 1);
  }
  int status = 0;
  rusage usage{};
  wait4(child, &status, 0, &usage);
  Measured m;
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;
  m.finished = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return m;
}

bool plan(const geometry::Cage& cage, double scallop) {
  auto surface = geometry::LimitSurface::build(cage);
  if (!surface) {
    return false;
  }
  geometry::PlanOptions options;
  options.ball_radius = 3.0;
  options.scallop = scallop;
  auto planner = geometry::ToolpathPlanner::prepare(cage, *surface, options);
  if (!planner) {
    std::fprintf(stderr, "plan: %s\n", planner.error().describe().c_str());
    return false;
  }
  long points = 0;
  const auto ran = planner->run([&](const cl::ClPose&) -> Expected<void> {
    ++points;
    return {};
  });
  bench::keep(points);
  // Where the time went, stage by stage, for the figures below.
  const auto& times = planner->summary().times;
  std::string stages;
  for (std::size_t i = 0; i < geometry::plan_stage_count; ++i) {
    const auto stage = static_cast<geometry::PlanStage>(i);
    stages +=
        fmt::format("{}{} {:.1f} s", i == 0 ? "" : ", ", geometry::stage_name(stage), times[stage]);
  }
  std::printf("    (%ld vertices, the cage subdivided %d more time(s) by the planner; %s; %d "
              "solves)\n",
              planner->summary().mesh_vertices, planner->summary().cage_levels, stages.c_str(),
              planner->summary().solves);
  std::fflush(stdout); // the child leaves by _exit, which flushes nothing
  return ran.has_value();
}

bool mesh_only(const geometry::Cage& cage, double scallop) {
  auto surface = geometry::LimitSurface::build(cage);
  if (!surface) {
    return false;
  }
  const double chord = std::min(scallop / 10.0, 4e-4); // the planner's default tolerance
  auto mesh =
      geometry::mesh_surface(cage, *surface, geometry::rates_for_tolerance(*surface, chord, 96));
  if (mesh) {
    std::printf("    (mesh alone: %d vertices, %d faces)\n", mesh->vertex_count(),
                cage.face_count());
    std::fflush(stdout);
  }
  bench::keep(mesh);
  return mesh.has_value();
}

std::string shown(const Measured& m, double limit_s) {
  return m.finished
             ? fmt::format("{:.1f} s, {:.0f} MiB", m.seconds, m.peak_mib)
             : fmt::format("not finished in {:.0f} s ({:.0f} MiB by then)", limit_s, m.peak_mib);
}

} // namespace

int main() {
  const char* limit_text = std::getenv("SUBFEED_BENCH_LIMIT_S");
  const double limit_s = limit_text != nullptr ? std::atof(limit_text) : 600.0;
  const auto body = bench::body_cage_obj(40, 17, 8);
  // The shell as a user would get it (Y up, centimetres), to plan and verify by hand.
  if (const char* out = std::getenv("SUBFEED_BENCH_WRITE_OBJ")) {
    std::ofstream(out) << body.obj;
  }
  std::istringstream in(body.obj);
  auto cage = geometry::parse_obj(in, "body.obj").value();
  geometry::PartSetup setup;
  setup.up = geometry::UpAxis::y;
  setup.scale = 10.0;
  setup.origin = geometry::OriginKind::bottom_centre;
  (void)geometry::set_up_part(cage, setup).value();
  std::printf("body shell: %d faces, %d creased edges, %d vertices (Y up, cm, set up)\n",
              body.faces, body.creases, cage.vertex_count());

  std::vector<Measured> by_faces;
  for (const int levels : {0, 1, 2}) {
    const auto refined = geometry::refine_cage(cage, levels).value();
    const auto m = in_child(limit_s, [&] { return plan(refined, 0.01); });
    const auto floor = in_child(limit_s, [&] { return mesh_only(refined, 0.01); });
    const auto name =
        fmt::format("plan {} faces ({}x), H 0.01", refined.face_count(), 1 << (2 * levels));
    std::printf("%s: %s; meshing alone %s\n", name.c_str(), shown(m, limit_s).c_str(),
                shown(floor, limit_s).c_str());
    bench::report({name + " time", m.finished ? m.seconds : limit_s, "s", "meshing alone",
                   floor.seconds, false});
    bench::report({name + " peak", m.peak_mib, "MiB", "meshing alone", floor.peak_mib, false});
    by_faces.push_back(m);
  }
  std::vector<Measured> by_h;
  for (const double h : {0.04, 0.02, 0.01}) {
    const auto m = in_child(limit_s, [&] { return plan(cage, h); });
    std::printf("plan 1x, H %.2f: %s\n", h, shown(m, limit_s).c_str());
    bench::report({fmt::format("plan 1x, H {:.2f} time", h), m.finished ? m.seconds : limit_s, "s",
                   "the aim", 60.0, false});
    by_h.push_back(m);
  }
  // Growth exponents: time ~ faces^a and ~ (1/H)^b. The work (area over step-over) does not
  // grow with the faces (a = 0) and grows as (1/H)^0.5 (the step-over goes as sqrt(H)).
  const auto exponent = [](const Measured& a, const Measured& b, double ratio) {
    return a.finished && b.finished ? std::log(b.seconds / a.seconds) / std::log(ratio) : NAN;
  };
  bench::report({"time exponent against faces", exponent(by_faces[0], by_faces[2], 16.0), "",
                 "the work's", 0.0, false});
  bench::report(
      {"time exponent against 1/H", exponent(by_h[0], by_h[2], 4.0), "", "the work's", 0.5, false});
  return 0;
}

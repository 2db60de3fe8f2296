// Planning: time and CL points per second against cage size and scallop target, peak memory,
// and the path length of every sample part against the ideal bound L* and the iso-planar
// baseline. Baselines: meshing the limit surface alone (the floor any planner pays), the
// baseline planner's point rate, the memory of the mesh alone, and `--baseline` paths; the
// motion gate against the rest of the plan; the whole tool against the ball alone.

#include "bench_harness.hpp"
#include "wavy_cage.hpp"

#include "cl/cl_reader.hpp"
#include "cl/cl_writer.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/motion_gate.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/path_verifier.hpp"
#include "geometry/surface_mesh.hpp"
#include "geometry/toolpath_planner.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using namespace subfeed;

// 5 mm apart, waves of 2 mm: radii well above the ball's.
geometry::Cage wavy_cage(int n) {
  std::istringstream in(bench::wavy_grid_obj(n, 5.0, 2.0));
  return geometry::parse_obj(in, "wavy.obj").value();
}

struct PlanRun {
  double seconds = 0.0;
  geometry::PlanSummary summary;
};

PlanRun plan(const geometry::Cage& cage, const geometry::LimitSurface& surface, double radius,
             double scallop, bool baseline, const std::filesystem::path& out,
             bool choose_direction = false, const geometry::ToolAssembly* tool = nullptr,
             geometry::AxisLean lean = {}) {
  geometry::PlanOptions options;
  options.ball_radius = radius;
  options.scallop = scallop;
  options.baseline = baseline;
  options.choose_direction = choose_direction;
  options.lean = lean;
  if (tool != nullptr) {
    options.whole_tool = true;
    options.tool = *tool;
    options.floor_at_lowest = true;
  }
  PlanRun run;
  run.seconds = bench::best_seconds(1, [&] {
    auto planner = geometry::ToolpathPlanner::prepare(cage, surface, options).value();
    auto writer = cl::ClWriter::create(out, {"BENCH", {2 * radius, radius}, true, {}, {}}).value();
    (void)planner.run([&](const cl::ClPose& p) -> Expected<void> {
      writer.write(p);
      return {};
    });
    (void)writer.finish();
    run.summary = planner.summary();
  });
  return run;
}

void bench_plan_scaling(const std::filesystem::path& dir) {
  for (const int n : {11, 23, 33}) {
    const auto cage = wavy_cage(n);
    const auto surface = geometry::LimitSurface::build(cage).value();
    for (const double h : {0.02, 0.005}) {
      const double chord = std::min(h / 10.0, 4e-4);
      const double mesh_seconds = bench::best_seconds(1, [&] {
        const auto rates = geometry::rates_for_tolerance(surface, chord, 96);
        bench::keep(geometry::mesh_surface(cage, surface, rates));
      });
      const auto run = plan(cage, surface, 3.0, h, false, dir / "wavy.cl");
      bench::report({fmt::format("plan {} faces, H {} mm", cage.face_count(), h), run.seconds, "s",
                     "meshing the surface alone", mesh_seconds, false});
      if (n == 33) {
        const auto iso = plan(cage, surface, 3.0, h, true, dir / "wavy-baseline.cl");
        bench::report({fmt::format("CL points/s {} faces, H {}", cage.face_count(), h),
                       static_cast<double>(run.summary.points) / run.seconds, "points/s",
                       "iso-planar baseline plan",
                       static_cast<double>(iso.summary.points) / iso.seconds});
      }
    }
  }
}

void bench_memory(const std::filesystem::path& dir) {
  const auto cage = wavy_cage(33);
  const auto surface = geometry::LimitSurface::build(cage).value();
  const auto mesh =
      geometry::mesh_surface(cage, surface, geometry::rates_for_tolerance(surface, 4e-4, 96));
  const double mesh_peak = bench::peak_rss_mib();
  (void)plan(cage, surface, 3.0, 0.005, false, dir / "memory.cl");
  bench::report({"peak memory, 1,024 faces H 0.005", bench::peak_rss_mib(), "MiB",
                 "after meshing alone", mesh_peak, false});
}

void bench_path_lengths(const std::filesystem::path& dir) {
  struct Part {
    const char* name;
    double radius, scallop;
  };
  for (const Part part :
       {Part{"bowl", 3.0, 0.01}, Part{"saddle", 3.0, 0.01}, Part{"dome", 3.0, 0.01},
        Part{"ridge", 3.0, 0.01}, Part{"seat", 1.0, 0.005}}) {
    const auto cage =
        geometry::read_obj(std::string(SUBFEED_SOURCE_DIR) + "/examples/" + part.name + ".obj")
            .value();
    const auto surface = geometry::LimitSurface::build(cage).value();
    // Feed along X, its --baseline, and the pattern chosen (--direction auto: a direction or
    // concentric rings).
    double ratio[3] = {0.0, 0.0, 0.0};
    for (const int k : {0, 1, 2}) {
      const auto file = dir / fmt::format("{}-{}.cl", part.name, k);
      const auto run = plan(cage, surface, part.radius, part.scallop, k == 1, file, k == 2);
      geometry::VerifyOptions verify;
      verify.ball_radius = part.radius;
      verify.scallop_target = part.scallop;
      const auto report = geometry::verify_path(surface, file, verify).value();
      ratio[k] = report.cutting_length / report.ideal_length;
      if (k == 2) {
        if (run.summary.rings()) {
          std::printf("  %s: --direction auto chose concentric rings (%.0f mm predicted against "
                      "%.0f mm of parallel passes)\n",
                      part.name, run.summary.ring_price, run.summary.parallel_price);
        } else {
          std::printf("  %s: --direction auto chose %g deg\n", part.name,
                      run.summary.direction_deg);
        }
      }
    }
    bench::report(
        {fmt::format("L/L* {}, feed X", part.name), ratio[0], "", "--baseline", ratio[1], false});
    bench::report({fmt::format("L/L* {}, --direction auto", part.name), ratio[2], "", "feed X",
                   ratio[0], false});
  }
}

// The motion gate's share of a plan: every plan runs it, so its cost is timed on its own by
// building it and replaying the plan's poses through it, and set against the rest of the
// plan (plan time less that).
void bench_gate(const std::filesystem::path& dir) {
  struct Part {
    std::string name;
    geometry::Cage cage;
    double scallop;
  };
  std::vector<Part> parts;
  parts.push_back({"wavy 256 faces", wavy_cage(17), 0.01});
  parts.push_back({"wavy 1,024 faces", wavy_cage(33), 0.005});
  parts.push_back(
      {"dome", geometry::read_obj(std::string(SUBFEED_SOURCE_DIR) + "/examples/dome.obj").value(),
       0.01});
  for (const auto& part : parts) {
    const auto surface = geometry::LimitSurface::build(part.cage).value();
    const auto file = dir / "gate.cl";
    const auto run = plan(part.cage, surface, 3.0, part.scallop, false, file);
    const double gate = bench::best_seconds(3, [&] {
      auto g = geometry::MotionGate::build(part.cage, surface, {3.0, 1e-3, false, {}, {}}).value();
      auto reader = cl::ClReader::open(file).value();
      while (auto pose = reader.next().value()) {
        (void)g.check(*pose);
      }
      bench::keep(g.report());
    });
    bench::report({fmt::format("motion gate, {} H {}", part.name, part.scallop), gate, "s",
                   "the rest of the plan", run.seconds - gate, false});
  }
}

// The peak resident memory of `work` run in a child process of its own, MiB: each plan's
// peak apart, where one process's peak would only ever grow.
template <class Work> double child_peak_mib(Work&& work) {
  int fds[2];
  if (::pipe(fds) != 0) {
    return 0.0;
  }
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(fds[0]);
    work();
    const double peak = bench::peak_rss_mib();
    (void)!::write(fds[1], &peak, sizeof peak);
    ::_exit(0);
  }
  ::close(fds[1]);
  double peak = 0.0;
  (void)!::read(fds[0], &peak, sizeof peak);
  ::close(fds[0]);
  ::waitpid(child, nullptr, 0);
  return peak;
}

// The whole tool (a 6 mm ball on a 6 mm shank, 40 mm out of a 32 mm holder, the floor at
// the part's lowest point): plan time and peak memory against the same plan of the ball
// alone; and with a lead, against the same without.
void bench_whole_tool(const std::filesystem::path& dir) {
  struct Part {
    std::string name;
    geometry::Cage cage;
    double scallop;
  };
  std::vector<Part> parts;
  parts.push_back({"wavy 1,024 faces", wavy_cage(33), 0.01});
  parts.push_back(
      {"dome", geometry::read_obj(std::string(SUBFEED_SOURCE_DIR) + "/examples/dome.obj").value(),
       0.01});
  const geometry::ToolAssembly tool{.ball_radius = 3,
                                    .flute_length = 18,
                                    .shank_diameter = 6,
                                    .stickout = 40,
                                    .holder = {{32, 32, 40}}};
  for (const auto& part : parts) {
    const auto surface = geometry::LimitSurface::build(part.cage).value();
    const auto file = dir / "tool.cl";
    const auto ball = plan(part.cage, surface, 3.0, part.scallop, false, file);
    const auto whole = plan(part.cage, surface, 3.0, part.scallop, false, file, false, &tool);
    bench::report({fmt::format("whole tool, {} H {}", part.name, part.scallop), whole.seconds, "s",
                   "the ball alone", ball.seconds, false});
    const double ball_peak =
        child_peak_mib([&] { (void)plan(part.cage, surface, 3.0, part.scallop, false, file); });
    const double whole_peak = child_peak_mib(
        [&] { (void)plan(part.cage, surface, 3.0, part.scallop, false, file, false, &tool); });
    bench::report({fmt::format("whole tool peak, {}", part.name), whole_peak, "MiB",
                   "the ball alone", ball_peak, false});
    // A 15 degree lead, eased where the holder would hit: each point checked again.
    const auto led = plan(part.cage, surface, 3.0, part.scallop, false, file, false, &tool,
                          geometry::AxisLean{15.0, 0.0});
    bench::report({fmt::format("whole tool, lead 15, {} H {}", part.name, part.scallop),
                   led.seconds, "s", "the whole tool without a lead", whole.seconds, false});
  }
}

} // namespace

int main() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("subfeed-plan-bench-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  bench_memory(dir); // first, so the peak it reads is its own
  bench_gate(dir);
  bench_whole_tool(dir);
  bench_plan_scaling(dir);
  bench_path_lengths(dir);
  std::filesystem::remove_all(dir);
  return 0;
}

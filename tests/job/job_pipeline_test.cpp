#include "job/job_pipeline.hpp"
#include "job/job_record.hpp"
#include "job/plan_settings.hpp"
#include "job/restart_point.hpp"

#include "post/post_file.hpp"

#include "support/hand_made_cl.hpp"
#include "support/temp_dir.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

using namespace subfeed;
using namespace subfeed::job;
using subfeed::testing::lines_of;
using subfeed::testing::read_text;
using subfeed::testing::TempDir;

namespace {

const std::string source_dir = SUBFEED_SOURCE_DIR;

// A three-axis job on the sample plane: small, so it runs in every build.
JobRecord plane_job(const TempDir& dir) {
  JobRecord o;
  o.cage = source_dir + "/examples/plane.obj";
  o.machine = source_dir + "/configs/grbl-router-3axis.toml";
  o.plan.tool = "ball:6";
  o.plan.scallop = 0.05;
  o.plan.axis = "fixed";
  o.output = (dir.path() / "job").string();
  return o;
}

JobSpec spec_of(const JobRecord& o) {
  std::ostringstream out, err;
  Logger log(Verbosity::quiet, out, err);
  auto spec = job_spec(o, log);
  REQUIRE(spec);
  return std::move(*spec);
}

// Every line the job hands to the stream, up to the end or an error in its place.
std::vector<std::string> drain(JobPipeline& job, std::optional<Error>* error = nullptr) {
  std::vector<std::string> lines;
  while (auto line = job.program().pop()) {
    if (!*line) {
      REQUIRE(error != nullptr);
      *error = line->error();
      break;
    }
    lines.push_back(**line);
  }
  return lines;
}

// What `post` writes of a job's CL data, to compare the job's program with.
struct PostAlone {
  JobFiles files;
  post::MachineConfig machine;
  post::PostFileOptions options;

  explicit PostAlone(const JobSpec& spec)
      : files(spec.files), machine(spec.machine), options(spec.post) {}
  void write(const std::filesystem::path& nc) const {
    REQUIRE(post::post_file(files.cl, machine, options, nc));
  }
};

} // namespace

TEST_CASE("job pipeline: a planned job's lines reach the stream in order, as its program file "
          "has them, with exact progress") {
  const TempDir dir;
  const auto record = plane_job(dir);
  auto spec = spec_of(record);
  const auto files = spec.files;
  JobPipeline job(std::move(spec));
  job.start();
  const auto streamed = drain(job);
  const auto totals = job.finish();
  REQUIRE(totals);
  CHECK(streamed == lines_of(files.nc));
  CHECK(totals->lines == static_cast<long>(streamed.size()));
  CHECK(totals->plan.passes > 0);
  CHECK(totals->cut_mm > 0.0);
  CHECK(totals->machine_min > 0.0);

  CHECK(lines_of(post::map_path_for(files.nc)).size() == streamed.size() + 1); // and its header
  CHECK(std::filesystem::exists(files.cl));

  // The first motion line is the first that moves an axis.
  const long first = job.first_motion_line();
  REQUIRE(first > 0);
  CHECK(moves_an_axis(streamed[static_cast<std::size_t>(first - 1)]));
  for (long i = 1; i < first; ++i) {
    CHECK_FALSE(moves_an_axis(streamed[static_cast<std::size_t>(i - 1)]));
  }

  // Progress is asked for as lines are acknowledged, in order: halfway, less is done than in
  // all; once every line is acknowledged it is exact and complete.
  const auto half = job.progress(totals->lines / 2);
  const auto p = job.progress(totals->lines);
  CHECK(half.cut_done_mm < p.cut_done_mm);
  CHECK(half.minutes_done < p.minutes_done);
  CHECK(p.planned);
  CHECK(p.lines_posted == totals->lines);
  CHECK(p.cut_done_mm == Approx(totals->cut_mm));
  CHECK(p.cut_total_mm == Approx(totals->cut_mm));
  CHECK(p.minutes_done == Approx(totals->machine_min));
  CHECK(p.minutes_total == Approx(totals->machine_min));
}

// The plane job's CL data, planned once, as a job of its own (what `run PART.cl` does).
JobRecord cl_job(const TempDir& dir) {
  const auto planned = plane_job(dir);
  {
    JobPipeline plan(spec_of(planned));
    plan.detach();
    plan.start();
    REQUIRE(plan.finish());
  }
  JobRecord o;
  o.cage = planned.output + ".cl";
  o.check_cage = planned.cage;
  o.machine = planned.machine;
  o.output = (dir.path() / "from-cl").string();
  return o;
}

// That job started, with `post`'s program of the same CL data to compare it with.
struct StartedClJob {
  PostAlone alone;
  JobFiles files;
  std::unique_ptr<JobPipeline> job;
};

StartedClJob start_cl_job(const TempDir& dir) {
  auto spec = spec_of(cl_job(dir));
  StartedClJob started{PostAlone(spec), spec.files, nullptr};
  started.job = std::make_unique<JobPipeline>(std::move(spec));
  started.job->start();
  return started;
}

TEST_CASE("job pipeline: a job on CL data streams what post writes of it, byte for byte") {
  const TempDir dir;
  auto [alone, files, job] = start_cl_job(dir);
  const auto streamed = drain(*job);
  REQUIRE(job->finish());
  alone.write(dir.path() / "alone.nc");
  CHECK(read_text(files.nc) == read_text(dir.path() / "alone.nc"));
  CHECK(read_text(post::map_path_for(files.nc)) == read_text(dir.path() / "alone.nc.map"));
  CHECK(streamed == lines_of(files.nc));
}

TEST_CASE("job pipeline: detached from the stream, it finishes the files alone") {
  const TempDir dir;
  auto [alone, files, job] = start_cl_job(dir);
  const bool took = job->program().pop().has_value(); // the stream took a line, then stopped
  REQUIRE(took);
  job->detach();
  const auto totals = job->finish();
  REQUIRE(totals);
  alone.write(dir.path() / "alone.nc");
  CHECK(read_text(files.nc) == read_text(dir.path() / "alone.nc"));
  CHECK(totals->lines == static_cast<long>(lines_of(files.nc).size()));
}

TEST_CASE("job pipeline: CL data the gate refuses stops before the refused pose is posted, "
          "and no file is left") {
  const TempDir dir;
  const auto cl = dir.path() / "through.cl";
  {
    std::ofstream out(cl);
    out << subfeed::testing::rapid_through_plane_cl;
  }
  JobRecord o;
  o.cage = cl.string();
  o.check_cage = source_dir + "/examples/plane.obj";
  o.machine = source_dir + "/configs/grbl-router-3axis.toml";
  o.output = (dir.path() / "job").string();
  auto spec = spec_of(o);
  const auto nc = spec.files.nc;
  JobPipeline job(std::move(spec));
  job.start();
  std::optional<Error> streamed_error;
  const auto streamed = drain(job, &streamed_error);
  const auto totals = job.finish();
  REQUIRE_FALSE(totals);
  REQUIRE(streamed_error); // the stream learns it in the queue, before any later line
  CHECK(streamed_error->where.line == 16);
  CHECK(totals.error().where.line == 16);
  CHECK(totals.error().message.find("tool path refused: the rapid") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(nc));
  CHECK_FALSE(std::filesystem::exists(post::map_path_for(nc)));
  for (const auto& line : streamed) {
    CHECK(line.find("Z-1.") == std::string::npos); // the refused rapid's target never streamed
  }
}

TEST_CASE("job spec: the tilt is the machine's unless said, and never more than it turns",
          "[unit]") {
  TempDir dir;
  auto o = plane_job(dir);
  o.plan.axis = "normal";
  o.machine = source_dir + "/configs/grblhal-xyzac-trt.toml"; // A -100..50, C endless
  CHECK(spec_of(o).plan->options.max_tilt_deg == 100.0);
  o.plan.max_tilt = 45.0;
  CHECK(spec_of(o).plan->options.max_tilt_deg == 45.0);
  o.plan.max_tilt = 120.0;
  std::ostringstream out, err;
  Logger log(Verbosity::quiet, out, err);
  const auto refused = job_spec(o, log);
  REQUIRE_FALSE(refused);
  CHECK(refused.error().where.key == "--max-tilt");
  CHECK(refused.error().message ==
        "120 degrees is more than " + o.machine + " tilts the tool (100 degrees)");
  // A three-axis machine: the tool stays vertical, and a plan without a machine leans 90.
  o.machine = source_dir + "/configs/grbl-router-3axis.toml";
  o.plan.max_tilt = -1.0;
  CHECK(spec_of(o).plan->options.fixed_axis);
  geometry::PlanOptions alone = *plan_options_from(o.plan);
  CHECK(alone.max_tilt_deg == 90.0);
}

TEST_CASE("job pipeline: progress tells the planner's stages and solves, for the display") {
  const TempDir dir;
  auto spec = spec_of(plane_job(dir));
  const int most = spec.plan->options.refine_iterations;
  JobPipeline job(std::move(spec));
  CHECK_FALSE(job.progress(0).stage); // nothing entered yet
  job.start();
  (void)drain(job);
  REQUIRE(job.finish());
  const auto p = job.progress(0);
  // The last stage entered before slicing, and the deformation's solves with their bound.
  REQUIRE(p.stage);
  CHECK(*p.stage == geometry::PlanStage::clearing);
  CHECK(p.solve >= 1);
  CHECK(p.solve <= most);
  CHECK(p.most_solves == most);
  // Clearing tells no share of its own: the reach stage's is not carried over into it.
  CHECK(p.stage_share < 0.0);
}

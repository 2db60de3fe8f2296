// The part's setup in a job: the job record keeps exactly what the command line said, reads
// back to it, and a said setup meets a recorded one only where they agree.

#include "job/job_record.hpp"
#include "job/setup_flags.hpp"

#include <catch2/catch.hpp>

using namespace subfeed;
using namespace subfeed::job;
namespace g = subfeed::geometry;

namespace {

JobRecord job_with(const SetupFlags& setup) {
  JobRecord o;
  o.cage = "part with space.obj";
  o.machine = "m.toml";
  o.plan.tool = "ball:6";
  o.plan.scallop = 0.02;
  o.setup = setup;
  return o;
}

g::PartSetup origin(const char* word) {
  g::PartSetup s;
  REQUIRE(g::parse_origin(word, s));
  return s;
}

} // namespace

TEST_CASE("a job record keeps the setup fields said, and only those") {
  const std::vector<SetupFlags> said{
      {},
      {.up = g::UpAxis::y},
      {.scale = 25.4},
      {.origin = origin("top-centre")},
      {.up = g::UpAxis::neg_x, .scale = 0.1 + 0.2, .origin = origin("-1.5,2e-3,7")},
  };
  for (const auto& flags : said) {
    const auto text = encode_job(job_with(flags));
    CAPTURE(text);
    CHECK((text.find("setup_up=") != std::string::npos) == flags.up.has_value());
    CHECK((text.find("setup_scale=") != std::string::npos) == flags.scale.has_value());
    CHECK((text.find("setup_origin=") != std::string::npos) == flags.origin.has_value());
    const auto back = decode_job(text, {"j.journal", 0, "job"});
    REQUIRE(back);
    CHECK(back->cage == "part with space.obj");
    CHECK(back->setup.up == flags.up);
    CHECK(back->setup.scale == flags.scale);
    CHECK(back->setup.origin.has_value() == flags.origin.has_value());
    CHECK(back->setup.with_defaults() == flags.with_defaults());
  }
}

TEST_CASE("a damaged setup field in a job record is named") {
  auto text = encode_job(job_with({.up = g::UpAxis::y}));
  text.replace(text.find("setup_up=y"), 10, "setup_up=q");
  const auto back = decode_job(text, {"j.journal", 0, "job"});
  REQUIRE_FALSE(back);
  CHECK(back.error().describe() ==
        "j.journal: job: job record setup: up axis 'q' is not x, y, z, -x, -y or -z");
}

TEST_CASE("a said setup meets a recorded one field by field") {
  const std::string recorded = "up=y scale=10 origin=top-centre";
  SECTION("nothing recorded: the flags over the defaults") {
    const auto s = agreed_setup({.scale = 10.0}, "", "a.cl");
    REQUIRE(s);
    CHECK(*s == g::PartSetup{g::UpAxis::z, 10.0, g::OriginKind::model, Eigen::Vector3d::Zero()});
  }
  SECTION("nothing said, or the same said: the recorded one") {
    for (const auto& said :
         {SetupFlags{}, SetupFlags{.up = g::UpAxis::y},
          SetupFlags{.up = g::UpAxis::y, .scale = 10.0, .origin = origin("top-centre")}}) {
      const auto s = agreed_setup(said, recorded, "a.cl");
      REQUIRE(s);
      CHECK(*s ==
            g::PartSetup{g::UpAxis::y, 10.0, g::OriginKind::top_centre, Eigen::Vector3d::Zero()});
    }
  }
  SECTION("a field said otherwise is named") {
    const std::vector<std::pair<SetupFlags, std::string>> cases{
        {{.up = g::UpAxis::z}, "--up"},
        {{.scale = 1.0}, "--units/--scale"},
        {{.origin = origin("model")}, "--origin"},
        {{.origin = origin("0,0,0")}, "--origin"}};
    for (const auto& [said, flag] : cases) {
      const auto s = agreed_setup(said, recorded, "a.cl");
      REQUIRE_FALSE(s);
      CHECK(s.error().describe() == "a.cl: " + flag +
                                        ": disagrees with the setup the part was planned in "
                                        "(up=y scale=10 origin=top-centre): leave it out or "
                                        "give the same");
    }
  }
  SECTION("a damaged record is named") {
    const auto s = agreed_setup({}, "up=y scale=ten origin=model", "a.cl");
    REQUIRE_FALSE(s);
    CHECK(s.error().describe() ==
          "a.cl: setup 'up=y scale=ten origin=model': setup scale 'ten' is not a number above 0");
  }
}

TEST_CASE("a job record keeps the tilt said, and reads an older record as not said") {
  for (const double tilt : {-1.0, 0.0, 37.5, 90.0, 180.0}) {
    auto job = job_with({});
    job.plan.max_tilt = tilt;
    const auto back = decode_job(encode_job(job), {"j.journal", 0, "job"});
    REQUIRE(back);
    CHECK(back->plan.max_tilt == tilt);
  }
  auto text = encode_job(job_with({}));
  const auto at = text.find(" max_tilt=");
  REQUIRE(at != std::string::npos);
  text.erase(at, text.find(' ', at + 1) - at);
  const auto older = decode_job(text, {"j.journal", 0, "job"});
  REQUIRE(older);
  CHECK(older->plan.max_tilt == -1.0);
}

TEST_CASE("a job record keeps the whole tool and fixture, and reads an older record as the "
          "ball alone") {
  auto job = job_with({});
  job.plan.flute = 18;
  job.plan.shank = 6;
  job.plan.stickout = 40;
  job.plan.holder = {"32:40", "40:20:10"};
  job.plan.floor = "-1.25";
  job.plan.stock_margin = 2;
  job.plan.clearance_min = 0.75;
  const auto back = decode_job(encode_job(job), {"j.journal", 0, "job"});
  REQUIRE(back);
  CHECK(back->plan.whole_tool);
  CHECK(back->plan.flute == 18);
  CHECK(back->plan.shank == 6);
  CHECK(back->plan.stickout == 40);
  CHECK(back->plan.holder == std::vector<std::string>{"32:40", "40:20:10"});
  CHECK(back->plan.floor == "-1.25");
  CHECK(back->plan.stock_margin == 2);
  CHECK(back->plan.clearance_min == 0.75);
  // The defaults (no holder, the floor at the part's lowest point) read back as said.
  const auto plain = decode_job(encode_job(job_with({})), {"j.journal", 0, "job"});
  REQUIRE(plain);
  CHECK(plain->plan.whole_tool);
  CHECK(plain->plan.holder.empty());
  CHECK(plain->plan.floor.empty());
  // A record from before the whole tool re-plans as it was planned.
  auto text = encode_job(job);
  const auto at = text.find(" whole_tool=");
  REQUIRE(at != std::string::npos);
  text.erase(at, text.find(' ', at + 1) - at);
  const auto older = decode_job(text, {"j.journal", 0, "job"});
  REQUIRE(older);
  CHECK_FALSE(older->plan.whole_tool);
  const auto options = plan_options_from(older->plan);
  REQUIRE(options);
  CHECK_FALSE(options->whole_tool);
}

TEST_CASE("a job record keeps the lead and tilt, an older one has none, and a vertical tool "
          "refuses them") {
  auto job = job_with({});
  job.plan.lead = 12.5;
  job.plan.tilt = -4;
  const auto back = decode_job(encode_job(job), {"j.journal", 0, "job"});
  REQUIRE(back);
  CHECK(back->plan.lead == 12.5);
  CHECK(back->plan.tilt == -4);
  const auto options = plan_options_from(back->plan);
  REQUIRE(options);
  CHECK(options->lean.lead_deg == 12.5);
  CHECK(options->lean.tilt_deg == -4);
  auto text = encode_job(job);
  for (const char* key : {" lead=", " tilt="}) {
    const auto at = text.find(key);
    REQUIRE(at != std::string::npos);
    text.erase(at, text.find(' ', at + 1) - at);
  }
  const auto older = decode_job(text, {"j.journal", 0, "job"});
  REQUIRE(older);
  CHECK(older->plan.lead == 0.0);
  CHECK(older->plan.tilt == 0.0);
  job.plan.axis = "fixed";
  const auto fixed = plan_options_from(job.plan);
  REQUIRE_FALSE(fixed);
  CHECK(fixed.error().describe() == "--lead: a vertical tool (--axis fixed) cannot lead or tilt");
}

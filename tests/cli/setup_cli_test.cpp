// The part's setup as a user gives it: a cage modelled Y up in centimetres plans, posts and
// runs exactly as the same part modelled Z up in millimetres; the CL file and the job record
// keep the setup; verify, post, check and resume use it and refuse flags that contradict it.

#include "support/output_lines.hpp"
#include "support/run_process.hpp"
#include "support/temp_dir.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

using subfeed::testing::has_line;
using subfeed::testing::read_text;
using subfeed::testing::run_process;
using subfeed::testing::split_lines;
using subfeed::testing::TempDir;

namespace {

const std::string bin = SUBFEED_BIN;
const std::string source_dir = SUBFEED_SOURCE_DIR;
const std::string dome = source_dir + "/examples/dome.obj";
const std::string grblhal = source_dir + "/configs/grblhal-xyzac-trt.toml";

struct Modelled {
  std::string up;
  std::string units;
  double mm;
};

// The dome as a modeller with `m.up` up and `m.units` units would have written it: each
// vertex through the inverse of the documented turn (README "Setting up the part").
std::string remodelled(const Modelled& m) {
  std::istringstream in(read_text(dome));
  std::string line, out;
  while (std::getline(in, line)) {
    double x = 0, y = 0, z = 0;
    if (std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z) == 3) {
      double mx = x, my = y, mz = z;
      if (m.up == "y") {
        mx = x, my = z, mz = -y;
      } else if (m.up == "-x") {
        mx = -z, my = y, mz = x;
      } else if (m.up == "-z") {
        mx = x, my = -y, mz = -z;
      }
      line = fmt::format("v {:.17g} {:.17g} {:.17g}", mx / m.mm, my / m.mm, mz / m.mm);
    }
    out += line + "\n";
  }
  return out;
}

// The CL records after the header, each GOTO's numbers parsed.
std::vector<std::vector<double>> gotos(const std::string& cl) {
  std::vector<std::vector<double>> all;
  for (const auto& line : split_lines(read_text(cl))) {
    if (line.starts_with("GOTO/")) {
      std::vector<double> values;
      std::istringstream in(line.substr(5));
      std::string number;
      while (std::getline(in, number, ',')) {
        values.push_back(std::stod(number));
      }
      all.push_back(values);
    }
  }
  return all;
}

std::vector<std::string> plan(const std::string& cage, const std::string& cl) {
  return {bin,    "plan",        cage,    "--tool", "ball:6", "--scallop",
          "0.05", "--tolerance", "0.002", "-o",     cl};
}

} // namespace

// Whole sample-part plans and measurements run in the release build only (label parts); the
// refusals below run in both, on CL data made by hand.
TEST_CASE("a cage modelled in any orientation and unit plans the path of the part set up",
          "[parts][slow]") {
  const TempDir dir;
  const auto reference = (dir.path() / "ref.cl").string();
  REQUIRE(run_process(plan(dome, reference)).exit_code == 0);
  const auto want = gotos(reference);
  REQUIRE(want.size() > 100);
  for (const Modelled& m :
       {Modelled{"y", "cm", 10.0}, Modelled{"-x", "in", 25.4}, Modelled{"-z", "m", 1000.0}}) {
    CAPTURE(m.up, m.units);
    const auto cage = dir.write("dome-" + m.units + ".obj", remodelled(m));
    const auto cl = (dir.path() / ("dome-" + m.units + ".cl")).string();
    auto argv = plan(cage.string(), cl);
    argv.insert(argv.end(), {"--up", m.up, "--units", m.units, "--origin", "top-centre"});
    const auto r = run_process(argv);
    REQUIRE(r.exit_code == 0);
    CHECK(has_line(read_text(cl), "PPRINT SETUP up=" + m.up + " scale=" + fmt::format("{}", m.mm) +
                                      " origin=top-centre"));
    const auto got = gotos(cl);
    REQUIRE(got.size() == want.size());
    // The dome's top is its zero now: every tip 15.3403 mm (its height) lower, the same path.
    const double height = 15.340277777777779;
    double worst = 0.0;
    for (std::size_t i = 0; i < got.size(); ++i) {
      REQUIRE(got[i].size() == want[i].size());
      for (std::size_t k = 0; k < got[i].size(); ++k) {
        worst = std::max(worst, std::abs(got[i][k] - want[i][k] + (k == 2 ? height : 0.0)));
      }
    }
    CHECK(worst <= 2e-6); // the CL file's 6 decimals, and the setup's rounding
  }
}

TEST_CASE("verify and post --cage on a set-up part measure and check what was planned",
          "[parts][slow]") {
  const TempDir dir;
  const auto cage = dir.write("dome-cm.obj", remodelled({"y", "cm", 10.0}));
  const auto cl = (dir.path() / "dome.cl").string();
  auto argv = plan(cage.string(), cl);
  argv.insert(argv.end(), {"--up", "y", "--units", "cm"});
  REQUIRE(run_process(argv).exit_code == 0);
  // Set up as planned, the path measures exactly as the millimetre Z-up model's own.
  const auto reference = (dir.path() / "ref.cl").string();
  REQUIRE(run_process(plan(dome, reference)).exit_code == 0);
  const auto want =
      run_process({bin, "verify", dome, reference, "--tool", "ball:6", "--spacing", "0.5"});
  const auto got =
      run_process({bin, "verify", cage.string(), cl, "--tool", "ball:6", "--spacing", "0.5"});
  CHECK(got.exit_code == 0);
  const auto want_lines = split_lines(want.out);
  const auto got_lines = split_lines(got.out);
  // The scallop and gouge lines, then the whole tool's, body by body.
  REQUIRE(got_lines.size() >= 6);
  REQUIRE(want_lines.size() == got_lines.size());
  CHECK(got_lines[0].substr(got_lines[0].find(':')) ==
        want_lines[0].substr(want_lines[0].find(':')));
  for (std::size_t i = 1; i < got_lines.size(); ++i) {
    CHECK(got_lines[i] == want_lines[i]);
  }
  // The gate checks the set-up part: the plan's own 5 um (2.5 x its 2 um tolerance) holds.
  const auto nc = (dir.path() / "dome.nc").string();
  const auto posted = run_process({bin, "post", cl, "--machine", grblhal, "--cage", cage.string(),
                                   "--units", "cm", "--gate-tolerance", "0.005", "-o", nc});
  CHECK(posted.exit_code == 0);
  CHECK(posted.out.find("no cut deeper than 5 um, no rapid touching it; least clearance: ") !=
        std::string::npos);
}

TEST_CASE("verify, post and check refuse a setup that contradicts the CL file's") {
  const TempDir dir;
  // Two poses over the dome, in a CL file that says how the part was set up.
  const auto cl = dir.write("kept.cl", "PARTNO KEPT\nUNITS/MM\nCUTTER/6,3\nMULTAX/ON\n"
                                       "PPRINT SETUP up=y scale=10 origin=model\n"
                                       "RAPID\nGOTO/0,0,40,0,0,1\nFEDRAT/500\n"
                                       "GOTO/0,0,30,0,0,1\nFINI\n")
                      .string();
  const auto cage = dir.write("dome-cm.obj", remodelled({"y", "cm", 10.0})).string();
  const std::string kept = "(up=y scale=10 origin=model): leave it out or give the same\n";
  const auto refused = [&](const std::vector<std::string>& argv, const std::string& flag) {
    const auto r = run_process(argv);
    CAPTURE(argv);
    CHECK(r.exit_code == 2);
    CHECK(r.err == "subfeed: error: " + cl + ": " + flag +
                       ": disagrees with the setup the part was planned in " + kept);
  };
  refused({bin, "verify", cage, cl, "--tool", "ball:6", "--up", "z"}, "--up");
  const auto nc = (dir.path() / "kept.nc").string();
  refused({bin, "post", cl, "--machine", grblhal, "--cage", cage, "--scale", "1", "-o", nc},
          "--units/--scale");
  refused({bin, "post", cl, "--machine", grblhal, "--origin", "top-centre", "-o", nc}, "--origin");
  CHECK_FALSE(std::filesystem::exists(nc));
  // The same flags as kept are taken, and the CL file's setup is used without them.
  REQUIRE(
      run_process({bin, "post", cl, "--machine", grblhal, "--up", "y", "--units", "cm", "-o", nc})
          .exit_code == 0);
  CHECK(run_process({bin, "check", nc, "--machine", grblhal, "--cl", cl, "--up", "y"}).exit_code ==
        0);
  refused({bin, "check", nc, "--machine", grblhal, "--cl", cl, "--up", "-y"}, "--up");
  const auto no_cl = run_process({bin, "check", nc, "--machine", grblhal, "--up", "y"});
  CHECK(no_cl.exit_code == 1);
  CHECK(no_cl.err == "subfeed: error: --cl: a setup is checked against the CL data's own "
                     "record: give --cl as well\n");
}

TEST_CASE("bad setup words are refused in one line naming the flag") {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"--up", "w"}, "--up: up axis 'w' is not x, y, z, -x, -y or -z"},
      {{"--units", "ft"}, "--units: units 'ft' are not mm, cm, m or in"},
      {{"--scale", "-2"}, "--scale: '-2' is not a number above 0"},
      {{"--origin", "1,2"},
       "--origin: origin '1,2' is not top-centre, bottom-centre, min-corner, model or X,Y,Z in mm"},
      {{"--units", "cm", "--scale", "10"}, "--units excludes --scale"}};
  for (const auto* command : {"inspect", "plan"}) {
    for (const auto& [flags, message] : cases) {
      std::vector<std::string> argv{bin, command, dome, "--tool", "ball:6", "--scallop", "0.05"};
      if (std::string(command) == "inspect") {
        argv.resize(3);
      }
      argv.insert(argv.end(), flags.begin(), flags.end());
      const auto r = run_process(argv);
      CAPTURE(command, message);
      CHECK(r.exit_code == 1);
      CHECK(r.err == "subfeed: usage: " + message + " (see subfeed --help)\n");
    }
  }
}

TEST_CASE("inspect shows where the setup puts the part") {
  const TempDir dir;
  const auto cage = dir.write("dome-in.obj", remodelled({"-x", "in", 25.4}));
  const auto r = run_process(
      {bin, "inspect", cage.string(), "--up", "-x", "--units", "in", "--origin", "bottom-centre"});
  CHECK(r.exit_code == 0);
  const auto lines = split_lines(r.out);
  REQUIRE(lines.size() == 7);
  CHECK(lines[1] == "setup: up -x, 25.4 mm per model unit, zero at the bottom centre (program "
                    "zero at model point 0.0000, 0.0000, 0.0000 mm)");
  CHECK(lines[3] == "  X   -10.0000 ..    10.0000 mm  (size 20.0000 mm)");
  CHECK(lines[5] == "  Z     0.0000 ..    15.3403 mm  (size 15.3403 mm)");
}

TEST_CASE("run keeps the setup said in its job record, and resume refuses one that contradicts "
          "it",
          "[pty]") {
  const TempDir dir;
  const auto cage = dir.write("dome-cm.obj", remodelled({"y", "cm", 10.0}));
  const auto job = [&](const std::string& part, const std::string& base,
                       std::vector<std::string> setup) {
    std::vector<std::string> argv{bin,           "run",       part,
                                  "--machine",   grblhal,     "--tool",
                                  "ball:6",      "--scallop", "0.05",
                                  "--tolerance", "0.002",     "--sim",
                                  "--sim-speed", "1000",      "--sim-baud",
                                  "0",           "-o",        (dir.path() / base).string()};
    argv.insert(argv.end(), setup.begin(), setup.end());
    return run_process(argv);
  };
  REQUIRE(job(cage.string(), "cm", {"--up", "y", "--units", "cm"}).exit_code == 0);
  REQUIRE(job(dome, "mm", {}).exit_code == 0);
  // The same part set up the same way: the same program, byte for byte.
  CHECK(read_text((dir.path() / "cm.nc").string()) == read_text((dir.path() / "mm.nc").string()));
  const auto journal = read_text((dir.path() / "cm.journal").string());
  const auto lines = split_lines(journal);
  REQUIRE(lines.size() > 2);
  REQUIRE(lines[1].find(" event job ") != std::string::npos);
  CHECK(lines[1].ends_with(" setup_up=y setup_scale=10"));

  // The job cut short after its record: resume reads the setup back from it.
  const auto cut = dir.write("cut.journal", lines[0] + "\n" + lines[1] + "\n");
  const auto r = run_process(
      {bin, "resume", cut.string(), "--port", "/dev/null", "--yes", "--origin", "top-centre"});
  CHECK(r.exit_code == 2);
  CHECK(r.err == "subfeed: error: " + cut.string() +
                     ": --origin: disagrees with the setup the part was planned in (up=y "
                     "scale=10 origin=model): leave it out or give the same\n");
}

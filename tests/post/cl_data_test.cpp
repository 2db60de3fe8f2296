#include "cl/cl_reader.hpp"
#include "cl/cl_writer.hpp"
#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace subfeed;
using subfeed::testing::TempDir;

namespace {

const std::string good = "$$ made by hand\n"
                         "PARTNO TEST PART\n"
                         "UNITS/MM\n"
                         "CUTTER/6,3\n"
                         "MULTAX/ON\n"
                         "RAPID\n"
                         "GOTO/0,0,10,0,0,1\n"
                         "FEDRAT/300,MMPM\n"
                         "PLUNGE\n"
                         "GOTO/0,0,0,0,0,1\n"
                         "FEDRAT/1200\n"
                         "GOTO/1.5, -2 ,+0.25,0.6,0,0.8\n"
                         "RETRACT\n"
                         "GOTO/1.5,-2,5,0.6,0,0.8\n"
                         "FINI\n";

std::string error_of(const std::string& text) {
  TempDir dir;
  const auto path = dir.write("p.cl", text);
  auto reader = cl::ClReader::open(path);
  while (reader) {
    auto pose = reader->next();
    if (!pose) {
      return pose.error().describe().substr(path.string().size() + 1);
    }
    if (!*pose) {
      return "no error";
    }
  }
  return reader.error().describe().substr(path.string().size() + 1);
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

} // namespace

TEST_CASE("the CL reader gives poses with kind, feed and source line") {
  TempDir dir;
  auto reader = cl::ClReader::open(dir.write("p.cl", good));
  REQUIRE(reader);
  CHECK(reader->header().part_name == "TEST PART");
  CHECK(reader->header().cutter.diameter == 6.0);
  CHECK(reader->header().cutter.corner_radius == 3.0);
  CHECK(reader->header().multiaxis);
  std::vector<cl::ClPose> poses;
  for (int pass = 0; pass < 2; ++pass) { // and again after rewind
    poses.clear();
    while (true) {
      auto pose = reader->next();
      REQUIRE(pose);
      if (!*pose) {
        break;
      }
      poses.push_back(**pose);
    }
    REQUIRE(poses.size() == 4);
    REQUIRE(reader->rewind());
  }
  CHECK(poses[0].kind == cl::MoveKind::rapid);
  CHECK(poses[0].line == 7);
  CHECK(poses[1].kind == cl::MoveKind::plunge);
  CHECK(poses[1].feed == 300.0);
  CHECK(poses[2].kind == cl::MoveKind::feed);
  CHECK(poses[2].feed == 1200.0);
  CHECK(poses[2].tip == std::array<double, 3>{1.5, -2.0, 0.25});
  CHECK(poses[2].axis[0] == Approx(0.6));
  CHECK(poses[3].kind == cl::MoveKind::retract);
  CHECK(poses[3].line == 14);
}

TEST_CASE("what the CL writer writes the reader reads back to a nanometre") {
  TempDir dir;
  const auto path = dir.path() / "w.cl";
  auto writer = cl::ClWriter::create(path, {"ROUND TRIP",
                                            {6.0, 3.0},
                                            true,
                                            "up=y scale=10 origin=top-centre",
                                            {"flute=18 shank=6 stickout=40 holder=32:40",
                                             "floor=-1.5 margin=0 clearance=0.5", 0, 0}});
  REQUIRE(writer);
  std::vector<cl::ClPose> written;
  for (int i = 0; i < 50; ++i) {
    const double a = 0.1 * i;
    cl::ClPose pose{{std::cos(a) * 10.123456789, std::sin(a) * 7.5, -0.001 * i},
                    {std::sin(a) * 0.6, 0.0, 0.0},
                    i == 0 ? cl::MoveKind::rapid : cl::MoveKind::feed,
                    i == 0 ? 0.0 : (i < 25 ? 800.0 : 1000.0),
                    0};
    pose.axis[2] = std::sqrt(1.0 - pose.axis[0] * pose.axis[0]);
    pose.line = writer->write(pose); // the line the setup record must not shift
    written.push_back(pose);
  }
  CHECK_FALSE(std::filesystem::exists(path)); // not before finish()
  REQUIRE(writer->finish());
  auto reader = cl::ClReader::open(path);
  REQUIRE(reader);
  CHECK(reader->header().setup == "up=y scale=10 origin=top-centre");
  CHECK(reader->header().part_name == "ROUND TRIP");
  CHECK(reader->header().whole_tool.tool == "flute=18 shank=6 stickout=40 holder=32:40");
  CHECK(reader->header().whole_tool.tool_line == 6);
  CHECK(reader->header().whole_tool.fixture == "floor=-1.5 margin=0 clearance=0.5");
  CHECK(reader->header().whole_tool.fixture_line == 7);
  for (const auto& w : written) {
    auto pose = reader->next();
    REQUIRE(pose);
    REQUIRE(*pose);
    CHECK((*pose)->line == w.line);
    for (std::size_t i = 0; i < 3; ++i) {
      CHECK(std::abs((*pose)->tip[i] - w.tip[i]) <= 5e-7);
      CHECK(std::abs((*pose)->axis[i] - w.axis[i]) <= 1e-8);
    }
    CHECK((*pose)->kind == w.kind);
    CHECK((*pose)->feed == w.feed);
  }
  auto end = reader->next();
  REQUIRE(end);
  CHECK_FALSE(*end);
}

TEST_CASE("bad CL data is refused with its line") {
  CHECK(error_of(good) == "no error");
  CHECK(error_of(replace(good, "FINI\n", "")) == "15: ends without FINI: the CL data is truncated");
  CHECK(error_of(replace(good, "UNITS/MM", "UNITS/INCHES")) ==
        "3: UNITS/INCHES: only UNITS/MM is supported");
  CHECK(error_of(replace(good, "UNITS/MM\n", "")) ==
        "5: motion before UNITS/MM: the units must be stated");
  CHECK(error_of(replace(good, "GOTO/0,0,0,0,0,1", "GOTO/0,0,0,0,0.5,1")) ==
        "10: tool axis (i,j,k) is not a unit vector");
  CHECK(error_of(replace(good, "GOTO/0,0,0,0,0,1", "GOTO/0,0,0")) ==
        "10: GOTO needs x,y,z,i,j,k (MULTAX/ON)");
  CHECK(error_of(replace(good, "GOTO/0,0,0,0,0,1", "GOTO/0,0,nan,0,0,1")) ==
        "10: GOTO needs x,y,z,i,j,k (MULTAX/ON)");
  CHECK(error_of(replace(good, "FEDRAT/300,MMPM\n", "")) == "9: feed move before any FEDRAT");
  CHECK(error_of(replace(good, "FEDRAT/1200", "FEDRAT/-5")) ==
        "11: FEDRAT needs a feed > 0 in mm/min (optionally ,MMPM)");
  CHECK(error_of(replace(good, "RETRACT", "SPINDL/3000")) == "13: unknown record 'SPINDL'");
  CHECK(error_of(replace(good, "RETRACT", "CUTTER/6")) ==
        "13: CUTTER after the first motion record");
  CHECK(error_of(good + "GOTO/1,2,3,0,0,1\n") == "16: records after FINI");
  CHECK(error_of(replace(good, "CUTTER/6,3", "CUTTER/6,4")) ==
        "4: CUTTER needs a diameter > 0 and a corner radius from 0 to half of it");
  CHECK(error_of("") == "1: no motion records and no FINI: not CL data, or truncated");
}

TEST_CASE("without MULTAX a GOTO has three numbers and the tool points up") {
  TempDir dir;
  auto reader =
      cl::ClReader::open(dir.write("p.cl", "UNITS/MM\nCUTTER/6\nFEDRAT/100\nGOTO/1,2,3\nFINI\n"));
  REQUIRE(reader);
  auto pose = reader->next();
  REQUIRE(pose);
  REQUIRE(*pose);
  CHECK((*pose)->axis == std::array<double, 3>{0, 0, 1});
}

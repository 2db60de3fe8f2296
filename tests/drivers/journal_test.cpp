#include "drivers/journal.hpp"
#include "drivers/journal_reader.hpp"

#include "support/temp_dir.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <regex>

using namespace subfeed;
using namespace subfeed::drivers;
using subfeed::testing::lines_of;
using subfeed::testing::TempDir;

TEST_CASE("journal: one event a line, in the documented form, read back by the reader") {
  const TempDir dir;
  const auto path = dir.path() / "job.journal";
  {
    auto journal = Journal::open(path).value();
    journal.start("grbl", "job.nc", "/dev/pts/7");
    journal.event("job", "cage=part.obj tool=ball:6");
    journal.sent(1, 10);
    journal.sent(2, 23);
    journal.answered(1, 0);
    journal.sent(3, 7);
    journal.answered(2, 20);
    journal.event("alarm", "ALARM:1");
    journal.end(fail(ErrorCode::machine_fault, "controller alarm"));
  }
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 9);
  const std::regex stamped(R"(\d+ .+)");
  for (const auto& line : lines) {
    CHECK(std::regex_match(line, stamped));
  }
  const auto record = [&](std::size_t i) { return lines[i].substr(lines[i].find(' ') + 1); };
  CHECK(record(0) == "start protocol=grbl program=job.nc link=/dev/pts/7");
  CHECK(record(1) == "event job cage=part.obj tool=ball:6");
  CHECK(record(2) == "sent line=1 bytes=10");
  CHECK(record(4) == "answered line=1 ok");
  CHECK(record(6) == "answered line=2 error:20");
  CHECK(record(7) == "event alarm ALARM:1");
  CHECK(record(8) ==
        "end failed " + fail(ErrorCode::machine_fault, "controller alarm").error().describe());

  const auto s = read_journal(path).value();
  CHECK(s.protocol == "grbl");
  CHECK(s.program == "job.nc");
  CHECK(s.link == "/dev/pts/7");
  REQUIRE(s.job);
  CHECK(*s.job == "cage=part.obj tool=ball:6");
  CHECK(s.last_sent == 3);
  CHECK(s.last_sent_bytes == 7);
  CHECK(s.last_acked == 1); // line 2 was answered with an error
  CHECK_FALSE(s.finished);
  CHECK(s.last_end.starts_with("failed "));
}

TEST_CASE("journal reader: a resumed job appends, a crash cuts a line, the end counts last") {
  const TempDir dir;
  const auto path = dir.path() / "job.journal";
  {
    std::ofstream out(path);
    out << "0 start protocol=fanuc program=a.nc link=/dev/ttyS0\n"
           "5 sent line=40 bytes=31\n"
           "9 end failed link lost\n"
           "0 start protocol=fanuc program=a.nc link=/dev/ttyS0\n"
           "3 event resume after=39\n"
           "4 sent line=0 bytes=12\n" // a restart block: not a program line
           "7 sent line=41 bytes=18\n"
           "12 sen"; // cut short by a crash: no end record
  }
  const auto s = read_journal(path).value();
  CHECK(s.protocol == "fanuc");
  CHECK(s.last_sent == 41);
  CHECK(s.last_sent_bytes == 18);
  CHECK_FALSE(s.finished);
  CHECK(s.last_end == "failed link lost");
  {
    std::ofstream out(path, std::ios::app);
    out << "\n13 end done\n";
  }
  CHECK(read_journal(path).value().finished);
}

TEST_CASE("journal reader: anything else is refused, naming the file") {
  const TempDir dir;
  const auto path = dir.path() / "notes.txt";
  {
    std::ofstream out(path);
    out << "just some text\nno start here\n";
  }
  const auto r = read_journal(path);
  REQUIRE_FALSE(r);
  CHECK(r.error().code == ErrorCode::bad_input);
  CHECK(r.error().where.file == path.string());
  CHECK(r.error().message == "not a subfeed journal (no start record)");
  CHECK_FALSE(read_journal(dir.path() / "missing.journal"));
}

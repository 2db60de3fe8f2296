// After a fault is read (error:N, ALARM:N, the controller's own reset) not one program line
// more goes out, and the "sent but not run" report names exactly the lines the controller
// received and did not run: the simulator keeps its own account, compared line by line.
// The faults come while the RX buffer is full and the planner busy, where a sender that
// handles a whole batch of answers before looking at the fault would send more.

#include "support/grbl_fixture.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>

using subfeed::ErrorCode;
using subfeed::sim::GrblSimOptions;
using subfeed::testing::GrblBench;
using subfeed::testing::lines_of;
using subfeed::testing::stripped_lines;

namespace {

// Moves of 20 mm at 600 mm/min, 50 ms each at speed 40: the 15-block planner stays full
// and the RX buffer behind it fills, one line freed every 50 ms.
std::string busy_program(int moves) {
  std::string p = "G21G90\nG1F600\n";
  for (int i = 1; i <= moves; ++i) {
    p += "G1X" + std::to_string(i % 2 == 0 ? 0 : 20) + "Y" + std::to_string(i) + "\n";
  }
  return p;
}

// "lines 41-43, 47" (or "line 41") back to numbers.
std::vector<long> parse_lines(const std::string& text) {
  std::vector<long> lines;
  const std::regex run(R"((\d+)(?:-(\d+))?)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), run); it != std::sregex_iterator();
       ++it) {
    const long first = std::stol((*it)[1]);
    const long last = (*it)[2].matched ? std::stol((*it)[2]) : first;
    for (long n = first; n <= last; ++n) {
      lines.push_back(n);
    }
  }
  return lines;
}

// The file lines the stream reported as sent but not run; the count it gave must agree.
std::vector<long> reported_not_run(const std::string& message) {
  const std::regex note(R"((\d+) line\(s\) sent but not run \((lines? [^)]*)\))");
  std::smatch m;
  if (!std::regex_search(message, m, note)) {
    return {};
  }
  auto lines = parse_lines(m[2]);
  CHECK(static_cast<long>(lines.size()) == std::stol(m[1]));
  return lines;
}

} // namespace

TEST_CASE("not one line is sent after a fault is read, and what did not run is told exactly",
          "[pty]") {
  const bool grblhal = GENERATE(false, true);
  const std::string fault = GENERATE(as<std::string>{}, "error", "alarm", "reset");
  CAPTURE(grblhal, fault);
  GrblSimOptions o;
  o.baud = 0;
  o.motion.speed = 40.0;
  o.grblhal = grblhal;
  o.rx_buffer = grblhal ? 256 : 128;
  if (fault == "error") {
    o.faults.error_on_line = 40;
  } else if (fault == "alarm") {
    o.faults.alarm_after_s = 1.0;
  } else {
    o.faults.reset_on_line = 40;
  }
  GrblBench bench(o);
  const std::string program = busy_program(300);
  const auto journal_path = bench.dir.path() / "job.journal";
  const auto result = bench.stream_journaled(program, journal_path);
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::machine_fault);
  const auto stats = bench.sim->stats();
  CHECK(stats.max_rx_fill >= o.rx_buffer - 12); // the buffer was full when it came
  CHECK(stats.overrun_bytes == 0);

  // The journal: the first fault reply, then no `sent`.
  const auto journal = lines_of(journal_path);
  const std::regex fault_reply(R"(^\d+ (answered line=\d+ error:\d+|event alarm|event reset))");
  const auto first_fault = std::ranges::find_if(
      journal, [&](const std::string& l) { return std::regex_search(l, fault_reply); });
  REQUIRE(first_fault != journal.end());
  const auto sent_before = std::count_if(journal.begin(), first_fault, [](const std::string& l) {
    return l.find(" sent line=") != std::string::npos;
  });
  CHECK(sent_before > 30);
  const auto sent_after = std::find_if(first_fault, journal.end(), [](const std::string& l) {
    return l.find(" sent line=") != std::string::npos;
  });
  if (sent_after != journal.end()) {
    FAIL_CHECK("sent after the fault (" + *first_fault + "): " + *sent_after);
  }

  // Every line sent was received: run, or refused, dropped or left waiting unread.
  const auto sent_total = std::ranges::count_if(
      journal, [](const std::string& l) { return l.find(" sent line=") != std::string::npos; });
  CHECK(stats.executed_count + stats.refused_count + stats.dropped_count + stats.waiting_count ==
        sent_total);

  // The report against the simulator's own account. The program has no blank lines, so file
  // line n is the n-th program line.
  const auto lines = stripped_lines(program);
  std::map<std::string, long> file_line;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    file_line[lines[i]] = static_cast<long>(i) + 1;
  }
  std::vector<long> not_run;
  for (const auto* group : {&stats.refused, &stats.dropped, &stats.waiting}) {
    for (const auto& text : *group) {
      REQUIRE(file_line.contains(text));
      not_run.push_back(file_line[text]);
    }
  }
  if (fault == "error") { // named as the error, not among the lines not run
    std::erase(not_run, result.error().where.line);
    CHECK(result.error().where.line == 40);
  }
  std::ranges::sort(not_run);
  CAPTURE(result.error().message);
  CHECK_FALSE(not_run.empty());
  CHECK(reported_not_run(result.error().message) == not_run);
  // And what ran is what the stream saw acknowledged.
  const auto acked_ok = std::ranges::count_if(journal, [](const std::string& l) {
    return l.find(" answered ") != std::string::npos && l.ends_with(" ok");
  });
  CHECK(acked_ok == stats.executed_count);
}

#include "gcode/modal_state.hpp"
#include "gcode/words.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using namespace subfeed::gcode;

namespace {

// "G1 X-1.5" -> {"G1", "X-1.5"}: each word as letter and number text.
std::vector<std::string> texts(std::string_view line) {
  std::vector<std::string> out;
  const auto words = split_words(line);
  REQUIRE(words);
  for (const auto& w : *words) {
    out.push_back(w.letter + w.number);
  }
  return out;
}

} // namespace

TEST_CASE("words: letters upper-cased, numbers as written, blanks and comments dropped") {
  CHECK(texts("G01 X1.5 Y-2. Z+.25") == std::vector<std::string>{"G01", "X1.5", "Y-2.", "Z+.25"});
  CHECK(texts("g1x1y2") == std::vector<std::string>{"G1", "X1", "Y2"});
  CHECK(texts("N10 G1 (MOVE X9) X3 ; Y7 after the end of block") ==
        std::vector<std::string>{"N10", "G1", "X3"});
  CHECK(texts("%").empty());
  CHECK(texts("  \t\r").empty());
  CHECK(texts("G 1 X 1 . 5") == std::vector<std::string>{"G1", "X1.5"});
  const auto words = split_words("G43.4 H2 F1000.").value();
  REQUIRE(words.size() == 3);
  CHECK(words[0].value == 43.4);
  CHECK(words[1].value == 2.0);
  CHECK(words[2].value == 1000.0);
}

TEST_CASE("words: what is not a word is refused with what is wrong") {
  const auto message = [](std::string_view line) { return split_words(line).error().message; };
  CHECK(message("G1 (open comment") == "comment not closed");
  CHECK(message("X") == "word X has no valid number");
  CHECK(message("X1..2") == "word X has no valid number");
  CHECK(message("1.5") == "'1' where a letter should be");
  CHECK(message("G1 #5") == "'#' where a letter should be");
}

TEST_CASE("words: the visitor sees each word in order, up to an error") {
  std::string seen;
  const auto done = for_each_word("G1 X2 Y", [&seen](const Word& w) { seen += w.letter; });
  CHECK_FALSE(done);
  CHECK(seen == "GX");
}

TEST_CASE("modal state: words tracked by group, restored in blocks that move nothing") {
  ModalState modal;
  REQUIRE(modal.apply("G20 G18 G91 (COMMENT G21) G55"));
  REQUIRE(modal.apply("G00 X1 S5000 M04 T7"));
  REQUIRE(modal.apply("M09"));
  CHECK(modal.restore_blocks({}).value() ==
        std::vector<std::string>{"G20 G18 G91 G55", "T7", "S5000 M04", "M09", "G00"});
}

TEST_CASE("modal state: the later word of a group wins, as written") {
  ModalState modal;
  REQUIRE(modal.apply("G21 G17 G90 G94 G54"));
  REQUIRE(modal.apply("T3 M06"));
  REQUIRE(modal.apply("G43.4 H3"));
  REQUIRE(modal.apply("S12000 M03 M08"));
  REQUIRE(modal.apply("G93 G01 X1 F250.5"));
  REQUIRE(modal.apply("G56 G02 X2 Y2 I1 J0 F300."));
  CHECK(modal.restore_blocks({}).value() ==
        std::vector<std::string>{"G21 G17 G90 G93 G56", "T3 M06", "G43.4 H3", "S12000 M03", "M08",
                                 "G02 F300."});
  REQUIRE(modal.apply("G49"));
  CHECK(modal.restore_blocks({}).value()[2] == "G49");
}

TEST_CASE("modal state: no restart inside cutter compensation or G43.5") {
  ModalState comp;
  REQUIRE(comp.apply("G41 D1 G01 X1"));
  const auto refused = comp.restore_blocks({"job.nc", 12, "--from"});
  REQUIRE_FALSE(refused);
  CHECK(refused.error().where.line == 12);
  CHECK(refused.error().message.find("G41") != std::string::npos);
  REQUIRE(comp.apply("G40"));
  CHECK(comp.restore_blocks({}));
  ModalState tcp;
  REQUIRE(tcp.apply("G43.5 H1 I0 J0 K1"));
  CHECK_FALSE(tcp.restore_blocks({}));
}

TEST_CASE("modal state: a block that is not words is an error naming where") {
  ModalState modal;
  const auto bad = modal.apply("G1 X(", {"job.nc", 7, {}});
  REQUIRE_FALSE(bad);
  CHECK(bad.error().where.file == "job.nc");
  CHECK(bad.error().where.line == 7);
  CHECK(bad.error().message == "comment not closed");
}

TEST_CASE("strip: the line as a controller reads it, an open comment told") {
  CHECK(strip("g1 x1.5 (a comment) y2 ; the rest").text == "G1X1.5Y2");
  CHECK_FALSE(strip("G1 X1").open_comment);
  const auto open = strip("G1 X1 (never closed Y2");
  CHECK(open.text == "G1X1");
  CHECK(open.open_comment);
  CHECK(strip("%").text == "%"); // the sender decides what a '%' line is
  CHECK(strip("$H").text == "$H");
}

#include "base/error.hpp"

#include <catch2/catch.hpp>

using subfeed::Error;
using subfeed::ErrorCode;

TEST_CASE("an error describes itself as file:line: key: message") {
  const Error e{
      ErrorCode::bad_input, "expected a number, got a string", {"m.toml", 12, "axes.x.min"}};
  CHECK(e.describe() == "m.toml:12: axes.x.min: expected a number, got a string");
}

TEST_CASE("empty parts of the location are left out") {
  CHECK(Error{ErrorCode::bad_input, "boom", {}}.describe() == "boom");
  CHECK(Error{ErrorCode::bad_input, "boom", {"f.obj", 0, {}}}.describe() == "f.obj: boom");
  CHECK(Error{ErrorCode::usage, "boom", {{}, 0, "--port"}}.describe() == "--port: boom");
}

TEST_CASE("a description is always a single line") {
  const Error e{ErrorCode::bad_input, "line one\nline two\r", {"a\nb.obj", 3, {}}};
  const auto text = e.describe();
  CHECK(text.find('\n') == std::string::npos);
  CHECK(text.find('\r') == std::string::npos);
}

TEST_CASE("exit codes follow the documented table") {
  CHECK(subfeed::exit_code(ErrorCode::usage) == 1);
  CHECK(subfeed::exit_code(ErrorCode::bad_input) == 2);
  CHECK(subfeed::exit_code(ErrorCode::machine_fault) == 3);
  CHECK(subfeed::exit_code(ErrorCode::stopped) == 4);
}

namespace {

subfeed::Expected<int> parse_positive(int v) {
  if (v <= 0) {
    return subfeed::fail(ErrorCode::bad_input, "not positive");
  }
  return v;
}

subfeed::Expected<int> doubled(int v) {
  SUBFEED_TRY_ASSIGN(const int x, parse_positive(v));
  return 2 * x;
}

} // namespace

TEST_CASE("SUBFEED_TRY_ASSIGN passes values through and errors out unchanged") {
  CHECK(doubled(4).value() == 8);
  const auto bad = doubled(-1);
  REQUIRE_FALSE(bad);
  CHECK(bad.error().message == "not positive");
}

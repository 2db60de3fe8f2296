// The number reader against the locale: under a comma-decimal C locale strtod reads "1.5"
// as 1 (checked, so the test knows the locale is in force); parse_double must not.

#include "base/number_text.hpp"
#include "support/run_process.hpp"
#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>

#include <clocale>
#include <cstdlib>
#include <limits>

using namespace subfeed;

namespace {

// A German locale compiled into a temporary directory with localedef (from Debian's
// `locales`, which scripts/bootstrap installs): a fresh machine has no comma locale built.
class CommaLocale {
public:
  CommaLocale() {
    const auto made = testing::run_process({"/usr/bin/localedef", "-i", "de_DE", "-f", "UTF-8",
                                            (dir_.path() / "de_DE.UTF-8").string()});
    INFO(made.err);
    REQUIRE(made.exit_code <= 1); // 1: warnings only, the locale is written
    ::setenv("LOCPATH", dir_.path().c_str(), 1);
    REQUIRE(std::setlocale(LC_NUMERIC, "de_DE.UTF-8") != nullptr);
  }
  CommaLocale(const CommaLocale&) = delete;
  CommaLocale& operator=(const CommaLocale&) = delete;
  ~CommaLocale() {
    std::setlocale(LC_NUMERIC, "C");
    ::unsetenv("LOCPATH");
  }

private:
  testing::TempDir dir_;
};

} // namespace

TEST_CASE("numbers read the same under a comma-decimal locale") {
  const CommaLocale german;
  REQUIRE(std::strtod("1.5", nullptr) == 1.0); // the locale is in force: strtod stops at '.'
  REQUIRE(std::strtod("1,5", nullptr) == 1.5);
  CHECK(parse_double("1.5") == 1.5);
  CHECK(parse_double("-0.25") == -0.25);
  CHECK(parse_double("+12.") == 12.0);
  CHECK(parse_double(".5") == 0.5);
  CHECK_FALSE(parse_double("1,5"));
  const auto prefix = parse_double_prefix("-12.5X3");
  REQUIRE(prefix);
  CHECK(prefix->value == -12.5);
  CHECK(prefix->used == 5);
}

TEST_CASE("the whole text is the number, or it is refused") {
  CHECK(parse_double("3.125") == 3.125);
  CHECK(parse_double("1e3") == 1000.0);
  for (const char* bad : {"", " 1", "1 ", "1.5mm", "abc", "--1", "++1", "+", "-", ".", "inf", "nan",
                          "-inf", "1e999", "0x10"}) {
    CAPTURE(bad);
    CHECK_FALSE(parse_double(bad));
  }
  CHECK(parse_int("42") == 42);
  CHECK(parse_int("+7") == 7);
  CHECK(parse_int("-3") == -3);
  for (const char* bad : {"", "4.0", "99999999999", "12a", " 1", "abc"}) {
    CAPTURE(bad);
    CHECK_FALSE(parse_int(bad));
  }
  CHECK(parse_long("99999999999") == 99999999999L);
  CHECK_FALSE(parse_long("1.5"));
}

TEST_CASE("a G-code word's number is plain digits, a sign and one point") {
  const auto read = [](const char* text) { return parse_double_prefix(text); };
  CHECK(read("10Y2")->value == 10.0);
  CHECK(read("10Y2")->used == 2);
  CHECK(read("+.5")->value == 0.5);
  CHECK(read("+.5")->used == 3);
  CHECK(read("1.2.3")->value == 1.2);
  CHECK(read("1E5")->used == 1); // no exponents: X1E5 is X1 then E5
  CHECK_FALSE(read("X1"));
  CHECK_FALSE(read("-"));
  CHECK_FALSE(read("."));
  CHECK_FALSE(read("inf"));
}

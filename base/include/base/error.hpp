#pragma once
// The one error type every subfeed library returns. An Error says what kind of failure it
// is (which decides the process exit code), what went wrong, and where: a file with an
// optional line, and/or a config key. The command-line front prints it as one line.

#include <expected>
#include <string>

namespace subfeed {

// Values are the process exit codes documented in the README.
enum class ErrorCode {
  usage = 1,         // the command line itself is wrong
  bad_input = 2,     // a file, config or argument value is wrong
  machine_fault = 3, // controller error, alarm, reset, lost link
  stopped = 4,       // the user stopped the job
};

struct Where {
  std::string file; // empty when the error is not about a file
  int line = 0;     // 1-based; 0 when unknown or not meaningful
  std::string key;  // dotted config key or command-line option; may be empty
};

struct Error {
  ErrorCode code = ErrorCode::bad_input;
  std::string message;
  Where where;

  // "file:line: key: message", leaving out the parts that are empty. Never contains a
  // newline, so a front can always print exactly one line per error.
  [[nodiscard]] std::string describe() const;
};

[[nodiscard]] int exit_code(ErrorCode code);

template <class T> using Expected = std::expected<T, Error>;

[[nodiscard]] std::unexpected<Error> fail(ErrorCode code, std::string message, Where where = {});

} // namespace subfeed

// Propagation for functions that return Expected<U>: on error, return it unchanged.
#define SUBFEED_CONCAT_INNER(a, b) a##b
#define SUBFEED_CONCAT(a, b) SUBFEED_CONCAT_INNER(a, b)
#define SUBFEED_TRY_ASSIGN_IMPL(tmp, lhs, expr)                                                    \
  auto tmp = (expr);                                                                               \
  if (!tmp) {                                                                                      \
    return std::unexpected(std::move(tmp).error());                                                \
  }                                                                                                \
  lhs = std::move(*tmp)
// SUBFEED_TRY_ASSIGN(auto x, f()); or SUBFEED_TRY_ASSIGN(config.x, f());
#define SUBFEED_TRY_ASSIGN(lhs, expr)                                                              \
  SUBFEED_TRY_ASSIGN_IMPL(SUBFEED_CONCAT(subfeed_try_, __LINE__), lhs, expr)
// SUBFEED_TRY(f()); for Expected<void>.
#define SUBFEED_TRY(expr)                                                                          \
  do {                                                                                             \
    if (auto subfeed_try_void = (expr); !subfeed_try_void) {                                       \
      return std::unexpected(std::move(subfeed_try_void).error());                                 \
    }                                                                                              \
  } while (false)

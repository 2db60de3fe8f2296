#include "base/error.hpp"

#include <algorithm>

namespace subfeed {

namespace {

// A message built from file contents may carry control characters; a one-line report
// must not, or a hostile file could forge extra log lines.
std::string single_line(std::string text) {
  std::ranges::replace_if(
      text, [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return text;
}

} // namespace

std::string Error::describe() const {
  std::string out;
  if (!where.file.empty()) {
    out += where.file;
    if (where.line > 0) {
      out += ':' + std::to_string(where.line);
    }
    out += ": ";
  }
  if (!where.key.empty()) {
    out += where.key + ": ";
  }
  out += message;
  return single_line(std::move(out));
}

int exit_code(ErrorCode code) {
  return static_cast<int>(code);
}

std::unexpected<Error> fail(ErrorCode code, std::string message, Where where) {
  return std::unexpected(Error{code, std::move(message), std::move(where)});
}

} // namespace subfeed

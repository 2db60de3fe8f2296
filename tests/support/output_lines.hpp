#pragma once
// Exact assertions on a command's output, line by line: a line is either there whole or not,
// so a test pins down every word of a line we write, not a fragment of it. Where a line
// carries measured numbers, a pattern matches the whole line with the numbers left open.

#include <string>
#include <string_view>
#include <vector>

namespace subfeed::testing {

// The lines of `text`, without their endings (a last line without one counts).
[[nodiscard]] std::vector<std::string> split_lines(std::string_view text);

// Whether one line of `text` is exactly `line`.
[[nodiscard]] bool has_line(std::string_view text, std::string_view line);

// Whether one whole line of `text` matches the ECMAScript regular expression `pattern`.
[[nodiscard]] bool has_line_matching(std::string_view text, const std::string& pattern);

// The groups captured by the first whole line of `text` that matches `pattern` (the whole
// line first); empty when no line matches.
[[nodiscard]] std::vector<std::string> line_captures(std::string_view text,
                                                     const std::string& pattern);

// `text` with every regular-expression metacharacter escaped, to build patterns from
// literal pieces and open numbers.
[[nodiscard]] std::string literal(std::string_view text);

} // namespace subfeed::testing

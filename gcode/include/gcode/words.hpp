#pragma once
// One line of G-code as letter/number words: comments in parentheses or after ';', '%'
// and white space dropped, letters upper-cased. The one tokenizer of the project's own
// G-code readers (the simulators keep theirs apart on purpose: a simulator that shares the
// sender's parser would hide its bugs).

#include "base/error.hpp"

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace subfeed::gcode {

// A line as a controller reads it: comments (in parentheses, or from ';') dropped, spaces
// and tabs dropped, letters upper-cased; what GRBL is sent.
struct Stripped {
  std::string text;
  bool open_comment = false; // a '(' without its ')': the rest of the line was dropped
};
[[nodiscard]] Stripped strip(std::string_view line);

struct Word {
  char letter = 0;    // 'A'..'Z'
  std::string number; // as written, e.g. "01" or "-1.5"
  double value = 0.0;
};

// Calls `visit` with each word of the stripped line in order ('%' and CR are blanks too). An
// error (message only: the caller adds the file
// and line) on a letter without a number, a number without a letter, or an unclosed comment;
// the words before it have been visited.
[[nodiscard]] Expected<void> for_each_word(std::string_view line,
                                           const std::function<void(const Word&)>& visit);

// Every word of the line, or the error of for_each_word.
[[nodiscard]] Expected<std::vector<Word>> split_words(std::string_view line);

} // namespace subfeed::gcode

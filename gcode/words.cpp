#include "gcode/words.hpp"

#include "base/number_text.hpp"

#include <cctype>
#include <string>

namespace subfeed::gcode {

namespace {

bool blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '%';
}

bool number_char(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '-' || c == '+';
}

// The line without comments and blanks, upper-cased: words may be written with spaces
// inside ("G 1", "X 1.5").
Expected<std::string> compact(std::string_view line) {
  std::string text;
  bool comment = false;
  for (const char c : line) {
    if (comment) {
      comment = c != ')';
    } else if (c == '(') {
      comment = true;
    } else if (c == ';') {
      break;
    } else if (!blank(c)) {
      text += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
  }
  if (comment) {
    return fail(ErrorCode::bad_input, "comment not closed");
  }
  return text;
}

} // namespace

Expected<void> for_each_word(std::string_view line,
                             const std::function<void(const Word&)>& visit) {
  SUBFEED_TRY_ASSIGN(const std::string text, compact(line));
  std::size_t i = 0;
  while (i < text.size()) {
    const char letter = text[i];
    if (letter < 'A' || letter > 'Z') {
      return fail(ErrorCode::bad_input, std::string("'") + letter + "' where a letter should be");
    }
    std::size_t j = i + 1;
    while (j < text.size() && number_char(text[j])) {
      ++j;
    }
    const std::string_view number(text.data() + i + 1, j - i - 1);
    const auto value = parse_double(number);
    if (!value) {
      return fail(ErrorCode::bad_input, std::string("word ") + letter + " has no valid number");
    }
    visit(Word{letter, std::string(number), *value});
    i = j;
  }
  return {};
}

Expected<std::vector<Word>> split_words(std::string_view line) {
  std::vector<Word> words;
  SUBFEED_TRY(for_each_word(line, [&words](const Word& w) { words.push_back(w); }));
  return words;
}

} // namespace subfeed::gcode

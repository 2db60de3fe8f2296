#include "gcode_words.hpp"

#include "base/number_text.hpp"

#include <cctype>
#include <charconv>
#include <string>

namespace subfeed::post {

Expected<std::vector<GcodeWord>> split_words(std::string_view line) {
  std::string text;
  bool comment = false;
  for (const char c : line) {
    if (comment) {
      comment = c != ')';
    } else if (c == '(') {
      comment = true;
    } else if (c == ';') {
      break;
    } else if (c != ' ' && c != '\t' && c != '\r' && c != '%') {
      text += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
  }
  if (comment) {
    return fail(ErrorCode::bad_input, "comment not closed");
  }
  std::vector<GcodeWord> words;
  std::size_t i = 0;
  while (i < text.size()) {
    const char letter = text[i];
    if (letter < 'A' || letter > 'Z') {
      return fail(ErrorCode::bad_input, std::string("'") + letter + "' where a letter should be");
    }
    std::size_t j = i + 1;
    while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) ||
                               text[j] == '.' || text[j] == '-' || text[j] == '+')) {
      ++j;
    }
    const auto value = parse_double(std::string_view(text.data() + i + 1, j - i - 1));
    if (!value) {
      return fail(ErrorCode::bad_input, std::string("word ") + letter + " has no valid number");
    }
    words.push_back(GcodeWord{letter, *value});
    i = j;
  }
  return words;
}

} // namespace subfeed::post

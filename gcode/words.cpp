#include "gcode/words.hpp"

#include "base/number_text.hpp"

#include <cctype>
#include <string>

namespace subfeed::gcode {

namespace {

bool number_char(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '-' || c == '+';
}

} // namespace

Stripped strip(std::string_view line) {
  Stripped out;
  for (const char c : line) {
    if (out.open_comment) {
      out.open_comment = c != ')';
    } else if (c == '(') {
      out.open_comment = true;
    } else if (c == ';') {
      break;
    } else if (c != ' ' && c != '\t') {
      out.text += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
  }
  return out;
}

Expected<void> for_each_word(std::string_view line, const std::function<void(const Word&)>& visit) {
  const Stripped stripped = strip(line);
  if (stripped.open_comment) {
    return fail(ErrorCode::bad_input, "comment not closed");
  }
  const std::string& text = stripped.text;
  std::size_t i = 0;
  while (i < text.size()) {
    const char letter = text[i];
    if (letter == '%' || letter == '\r') {
      ++i;
      continue;
    }
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

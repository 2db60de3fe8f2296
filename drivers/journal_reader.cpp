#include "drivers/journal_reader.hpp"

#include "base/number_text.hpp"

#include <charconv>
#include <fstream>

namespace subfeed::drivers {

namespace {

// The value of `key=` in a record, up to the next space.
std::optional<std::string_view> field(std::string_view record, std::string_view key) {
  const std::string needle = std::string(key) + "=";
  std::size_t at = 0;
  while ((at = record.find(needle, at)) != std::string_view::npos) {
    if (at == 0 || record[at - 1] == ' ') {
      const auto start = at + needle.size();
      return record.substr(start, record.find(' ', start) - start);
    }
    ++at;
  }
  return std::nullopt;
}

long number(std::optional<std::string_view> text) {
  return text ? parse_long(*text).value_or(0) : 0;
}

} // namespace

Expected<JournalSummary> read_journal(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot read the journal", {path.string(), 0, {}});
  }
  JournalSummary s;
  std::string text;
  int line = 0;
  bool started = false;
  while (std::getline(in, text)) {
    ++line;
    const auto space = text.find(' ');
    if (space == std::string::npos) {
      continue; // a line cut short by a crash
    }
    const std::string_view record = std::string_view(text).substr(space + 1);
    if (record.starts_with("start ")) {
      started = true;
      s.protocol = std::string(field(record, "protocol").value_or(""));
      s.program = std::string(field(record, "program").value_or(""));
      s.link = std::string(field(record, "link").value_or(""));
      s.finished = false;
    } else if (record.starts_with("event job ")) {
      s.job = std::string(record.substr(10));
    } else if (record.starts_with("sent ")) {
      const long sent = number(field(record, "line"));
      if (sent > 0) {
        s.last_sent = sent;
        s.last_sent_bytes = number(field(record, "bytes"));
      }
    } else if (record.starts_with("answered ")) {
      const long answered = number(field(record, "line"));
      if (answered > 0 && record.ends_with(" ok")) {
        s.last_acked = answered;
      }
    } else if (record.starts_with("end ")) {
      s.last_end = std::string(record.substr(4));
      s.finished = s.last_end == "done";
    }
  }
  if (!started || s.program.empty()) {
    return fail(ErrorCode::bad_input, "not a subfeed journal (no start record)",
                {path.string(), line, {}});
  }
  return s;
}

} // namespace subfeed::drivers

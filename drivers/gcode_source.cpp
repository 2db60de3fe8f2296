#include "drivers/gcode_source.hpp"

namespace subfeed::drivers {

Expected<GcodeSource> GcodeSource::open(const std::filesystem::path& path, LineRules rules) {
  GcodeSource source(path.string(), rules);
  source.in_.open(path, std::ios::binary);
  if (!source.in_) {
    return fail(ErrorCode::bad_input, "cannot open G-code file", {source.name_, 0, {}});
  }
  return source;
}

Expected<void> GcodeSource::rewind() {
  in_.clear();
  in_.seekg(0);
  line_ = 0;
  if (!in_) {
    return fail(ErrorCode::bad_input, "cannot rewind G-code file", {name_, 0, {}});
  }
  return {};
}

Expected<std::optional<SourceLine>> GcodeSource::next() {
  std::string raw;
  while (std::getline(in_, raw)) {
    ++line_;
    if (!raw.empty() && raw.back() == '\r') {
      raw.pop_back();
    }
    SUBFEED_TRY_ASSIGN(auto prepared,
                       prepare_line(raw, rules_, {name_, static_cast<int>(line_), {}}));
    if (!prepared.text.empty()) {
      return SourceLine{line_, std::move(prepared)};
    }
  }
  if (in_.bad()) {
    return fail(ErrorCode::bad_input, "read error", {name_, static_cast<int>(line_), {}});
  }
  return std::optional<SourceLine>();
}

Expected<ScanSummary> GcodeSource::scan() {
  SUBFEED_TRY(rewind());
  ScanSummary summary;
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto line, next());
    if (!line) {
      break;
    }
    ++summary.lines_to_send;
    summary.bytes_to_send += static_cast<long>(line->line.text.size()) + 1;
  }
  SUBFEED_TRY(rewind());
  return summary;
}

} // namespace subfeed::drivers

#include "cl/cl_reader.hpp"

#include "base/number_text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <span>
#include <utility>

namespace subfeed::cl {

namespace {

// A writer's axis, rounded to 9 decimals, is unit to ~1e-9; anything off by more than this
// is not a direction someone meant.
constexpr double unit_tolerance = 1e-6;

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) {
    return {};
  }
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// Comma-separated numbers; nullopt on anything that is not one.
std::optional<std::size_t> parse_numbers(std::string_view text, std::span<double> out) {
  std::size_t count = 0;
  while (true) {
    const auto comma = text.find(',');
    const auto value = parse_double(trim(text.substr(0, comma)));
    if (count == out.size() || !value) {
      return std::nullopt;
    }
    out[count++] = *value;
    if (comma == std::string_view::npos) {
      return count;
    }
    text.remove_prefix(comma + 1);
  }
}

// "WORD/args" -> ("WORD", "args"); "WORD" -> ("WORD", "").
std::pair<std::string_view, std::string_view> split_record(std::string_view record) {
  const auto slash = record.find('/');
  if (slash == std::string_view::npos) {
    return {trim(record), {}};
  }
  return {trim(record.substr(0, slash)), trim(record.substr(slash + 1))};
}

} // namespace

ClReader::ClReader(std::string file, std::ifstream in)
    : file_(std::move(file)), in_(std::move(in)) {}

Expected<ClReader> ClReader::open(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot open CL data file", {path.string(), 0, {}});
  }
  ClReader reader(path.string(), std::move(in));
  SUBFEED_TRY(reader.read_header());
  return reader;
}

std::unexpected<Error> ClReader::error(std::string message) const {
  return fail(ErrorCode::bad_input, std::move(message), {file_, static_cast<int>(line_), {}});
}

Expected<void> ClReader::read_header() {
  while (true) {
    const auto position = in_.tellg();
    if (!std::getline(in_, text_)) {
      ++line_;
      return error("no motion records and no FINI: not CL data, or truncated");
    }
    ++line_;
    const auto record = trim(text_);
    if (record.empty() || record.starts_with("$$")) {
      continue;
    }
    SUBFEED_TRY_ASSIGN(const bool header, header_record(record));
    if (!header) {
      if (!units_seen_) {
        return error("motion before UNITS/MM: the units must be stated");
      }
      data_start_ = position;
      data_start_line_ = line_ - 1;
      return rewind();
    }
  }
}

Expected<bool> ClReader::header_record(std::string_view record) {
  if (record.starts_with("PARTNO")) {
    header_.part_name = std::string(trim(record.substr(6)));
    return true;
  }
  // PPRINT is free text for the operator; only subfeed's setup, tool and fixture records
  // mean anything here.
  if (record.starts_with("PPRINT")) {
    const auto text = trim(record.substr(6));
    if (text.starts_with("SETUP ")) {
      header_.setup = std::string(trim(text.substr(6)));
    } else if (text.starts_with("TOOL ")) {
      header_.whole_tool.tool = std::string(trim(text.substr(5)));
      header_.whole_tool.tool_line = line_;
    } else if (text.starts_with("FIXTURE ")) {
      header_.whole_tool.fixture = std::string(trim(text.substr(8)));
      header_.whole_tool.fixture_line = line_;
    }
    return true;
  }
  const auto [word, args] = split_record(record);
  if (word == "UNITS") {
    if (args != "MM") {
      return error("UNITS/" + std::string(args) + ": only UNITS/MM is supported");
    }
    units_seen_ = true;
    return true;
  }
  if (word == "CUTTER") {
    std::array<double, 7> values{};
    const auto count = parse_numbers(args, values);
    if (!count || values[0] <= 0.0 || values[1] < 0.0 || 2.0 * values[1] > values[0] + 1e-12) {
      return error("CUTTER needs a diameter > 0 and a corner radius from 0 to half of it");
    }
    header_.cutter = {values[0], *count > 1 ? values[1] : 0.0};
    return true;
  }
  if (word == "MULTAX") {
    if (args != "" && args != "ON" && args != "OFF") {
      return error("MULTAX takes ON or OFF");
    }
    header_.multiaxis = args != "OFF";
    return true;
  }
  return false;
}

Expected<void> ClReader::rewind() {
  in_.clear();
  in_.seekg(data_start_);
  if (!in_) {
    return error("cannot seek back in the CL data (a pipe?)");
  }
  line_ = data_start_line_;
  modal_ = {};
  finished_ = false;
  return {};
}

Expected<std::optional<ClPose>> ClReader::next() {
  while (!finished_) {
    if (!std::getline(in_, text_)) {
      ++line_;
      return error("ends without FINI: the CL data is truncated");
    }
    ++line_;
    const auto record = trim(text_);
    if (record.empty() || record.starts_with("$$")) {
      continue;
    }
    SUBFEED_TRY_ASSIGN(auto pose, motion_record(record));
    if (pose) {
      return pose;
    }
  }
  return std::optional<ClPose>{};
}

Expected<std::optional<ClPose>> ClReader::motion_record(std::string_view record) {
  const auto [word, args] = split_record(record);
  if (word == "RAPID" || word == "PLUNGE" || word == "RETRACT") {
    if (!args.empty()) {
      return error(std::string(word) + " takes no arguments");
    }
    modal_.next_kind = word == "RAPID"    ? MoveKind::rapid
                       : word == "PLUNGE" ? MoveKind::plunge
                                          : MoveKind::retract;
    return std::optional<ClPose>{};
  }
  if (word == "FEDRAT") {
    std::array<double, 1> feed{};
    auto number = args.substr(0, args.find(','));
    const auto unit =
        args.find(',') == std::string_view::npos ? "" : trim(args.substr(args.find(',') + 1));
    if (!parse_numbers(number, feed) || feed[0] <= 0.0 || (unit != "" && unit != "MMPM")) {
      return error("FEDRAT needs a feed > 0 in mm/min (optionally ,MMPM)");
    }
    modal_.feed = feed[0];
    return std::optional<ClPose>{};
  }
  if (word == "FINI") {
    finished_ = true;
    while (std::getline(in_, text_)) {
      ++line_;
      const auto rest = trim(text_);
      if (!rest.empty() && !rest.starts_with("$$")) {
        return error("records after FINI");
      }
    }
    return std::optional<ClPose>{};
  }
  if (word != "GOTO") {
    if (word == "PARTNO" || word == "UNITS" || word == "CUTTER" || word == "MULTAX" ||
        word.starts_with("PPRINT")) {
      return error(std::string(word) + " after the first motion record");
    }
    return error("unknown record '" + std::string(word) + "'");
  }
  return goto_record(args);
}

Expected<std::optional<ClPose>> ClReader::goto_record(std::string_view args) {
  std::array<double, 6> v{0, 0, 0, 0, 0, 1};
  const std::size_t wanted = header_.multiaxis ? 6 : 3;
  const auto count = parse_numbers(args, std::span(v.data(), wanted));
  if (!count || *count != wanted) {
    return error(header_.multiaxis ? "GOTO needs x,y,z,i,j,k (MULTAX/ON)"
                                   : "GOTO needs x,y,z (MULTAX is off)");
  }
  const double norm = std::hypot(v[3], v[4], v[5]);
  if (std::abs(norm - 1.0) > unit_tolerance) {
    return error("tool axis (i,j,k) is not a unit vector");
  }
  ClPose pose;
  pose.tip = {v[0], v[1], v[2]};
  pose.axis = {v[3] / norm, v[4] / norm, v[5] / norm};
  pose.kind = std::exchange(modal_.next_kind, MoveKind::feed);
  pose.line = line_;
  if (pose.kind != MoveKind::rapid) {
    if (modal_.feed <= 0.0) {
      return error("feed move before any FEDRAT");
    }
    pose.feed = modal_.feed;
  }
  return pose;
}

Error in_cl_file(Error error, const std::filesystem::path& file) {
  if (error.where.file.empty() && error.where.line > 0) {
    error.where.file = file.string();
  }
  return error;
}

} // namespace subfeed::cl

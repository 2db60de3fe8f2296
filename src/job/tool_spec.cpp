#include "job/tool_spec.hpp"

#include "base/number_text.hpp"
#include "post/tool_table.hpp"

#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <vector>

namespace subfeed::job {

namespace {

std::vector<std::string_view> split(std::string_view text, char by) {
  std::vector<std::string_view> out;
  while (true) {
    const auto at = text.find(by);
    out.push_back(text.substr(0, at));
    if (at == std::string_view::npos) {
      return out;
    }
    text.remove_prefix(at + 1);
  }
}

// "D:L" or "D1:D2:L"; nothing when it is neither.
std::optional<geometry::HolderStage> holder_stage(std::string_view text) {
  const auto parts = split(text, ':');
  std::vector<double> values;
  for (const auto part : parts) {
    const auto v = parse_double(part);
    if (!v || !(*v > 0.0) || *v > 10000.0) {
      return std::nullopt;
    }
    values.push_back(*v);
  }
  if (values.size() == 2) {
    return geometry::HolderStage{values[0], values[0], values[1]};
  }
  if (values.size() == 3) {
    return geometry::HolderStage{values[0], values[1], values[2]};
  }
  return std::nullopt;
}

std::string holder_text(const std::vector<geometry::HolderStage>& holder) {
  std::string out;
  for (const auto& h : holder) {
    out += (out.empty() ? "" : ",") + h.text();
  }
  return out;
}

// "key=value" words.
std::map<std::string, std::string, std::less<>> fields_of(std::string_view text) {
  std::map<std::string, std::string, std::less<>> fields;
  for (const auto word : split(text, ' ')) {
    if (const auto eq = word.find('='); eq != std::string_view::npos) {
      fields[std::string(word.substr(0, eq))] = std::string(word.substr(eq + 1));
    }
  }
  return fields;
}

} // namespace

Expected<std::optional<std::string>> resolve_tool_name(PlanSettings& s) {
  // A cutter spelt out (ball:D, or a shape not yet planned) is no name.
  if (s.tool.empty() || s.tool.find(':') != std::string::npos) {
    return std::optional<std::string>();
  }
  if (!std::filesystem::exists(s.tool_table)) {
    return fail(ErrorCode::usage,
                fmt::format("'{}' is not ball:D, and there is no tool table {} to look it up in "
                            "(give --tools FILE)",
                            s.tool, s.tool_table),
                {{}, 0, "--tool"});
  }
  SUBFEED_TRY_ASSIGN(const auto table, post::load_tool_table(s.tool_table));
  const auto* entry = table.find(s.tool);
  if (entry == nullptr) {
    std::string names;
    for (const auto& t : table.tools) {
      names += (names.empty() ? "" : ", ") + t.name;
    }
    return fail(ErrorCode::usage,
                fmt::format("'{}' is neither ball:D nor a tool in {} (it has: {})", s.tool,
                            table.file, names),
                {{}, 0, "--tool"});
  }
  s.tool = fmt::format("ball:{:g}", entry->diameter);
  s.flute = s.flute > 0.0 ? s.flute : entry->flute.value_or(0.0);
  s.shank = s.shank > 0.0 ? s.shank : entry->shank.value_or(0.0);
  s.stickout = s.stickout > 0.0 ? s.stickout : entry->stickout.value_or(0.0);
  if (s.holder.empty()) {
    for (const auto& h : entry->holder) {
      s.holder.push_back(geometry::HolderStage{h.bottom_diameter, h.top_diameter, h.length}.text());
    }
  }
  return std::optional<std::string>(table.file + ":" + std::to_string(entry->line));
}

Expected<double> parse_ball_tool(const std::string& spec) {
  const std::string prefix = "ball:";
  if (spec.starts_with(prefix)) {
    const auto diameter = parse_double(std::string_view(spec).substr(prefix.size()));
    if (diameter && *diameter > 0.0 && *diameter <= 100.0) {
      return *diameter / 2.0;
    }
  }
  return fail(ErrorCode::usage,
              "'" + spec + "': expected ball:D, a ball-end mill of diameter D mm (0 < D <= 100)",
              {{}, 0, "--tool"});
}

Expected<geometry::ToolAssembly> tool_assembly_from(const PlanSettings& o) {
  SUBFEED_TRY_ASSIGN(const double r, parse_ball_tool(o.tool));
  auto tool = geometry::ToolAssembly::ball_only(r);
  if (o.flute > 0.0 || o.shank > 0.0 || o.stickout > 0.0 || !o.holder.empty()) {
    tool.defaulted = false;
    tool.flute_length = o.flute > 0.0 ? o.flute : tool.flute_length;
    tool.shank_diameter = o.shank > 0.0 ? o.shank : tool.shank_diameter;
    tool.stickout = o.stickout > 0.0 ? o.stickout : std::max(tool.stickout, tool.flute_length);
    for (const auto& text : o.holder) {
      const auto stage = holder_stage(text);
      if (!stage) {
        return fail(ErrorCode::usage,
                    "'" + text +
                        "': expected D:L or D1:D2:L (diameters and length in mm, each "
                        "above 0 and at most 10000)",
                    {{}, 0, "--holder"});
      }
      tool.holder.push_back(*stage);
    }
  }
  const char* key = o.stickout > 0.0 ? "--stickout" : (o.flute > 0.0 ? "--flute" : "--tool");
  SUBFEED_TRY(tool.validate(key));
  return tool;
}

Expected<FixtureChoice> fixture_from(const PlanSettings& o) {
  FixtureChoice out;
  out.fixture.stock_margin = o.stock_margin;
  out.fixture.clearance_min = o.clearance_min;
  if (o.floor.empty()) {
    out.floor_at_lowest = true;
  } else if (o.floor != "none") {
    const auto z = parse_double(o.floor);
    if (!z) {
      return fail(ErrorCode::usage,
                  "'" + o.floor + "': expected a height in mm, or none (no floor is checked)",
                  {{}, 0, "--floor"});
    }
    out.fixture.floor_z = *z;
  }
  return out;
}

std::string tool_record(const geometry::ToolAssembly& tool) {
  const std::string holder = holder_text(tool.holder);
  return fmt::format("flute={:g} shank={:g} stickout={:g} holder={}", tool.flute_length,
                     tool.shank_diameter, tool.stickout, holder.empty() ? "none" : holder);
}

Expected<geometry::ToolAssembly> parse_tool_record(double ball_radius, std::string_view text,
                                                   const Where& where) {
  const auto fields = fields_of(text);
  auto tool = geometry::ToolAssembly::ball_only(ball_radius);
  tool.defaulted = false;
  const auto number = [&](const char* key) -> std::optional<double> {
    const auto it = fields.find(key);
    return it == fields.end() ? std::nullopt : parse_double(it->second);
  };
  const auto flute = number("flute"), shank = number("shank"), stickout = number("stickout");
  const auto holder = fields.find("holder");
  if (!flute || !shank || !stickout || holder == fields.end()) {
    return fail(ErrorCode::bad_input,
                "PPRINT TOOL needs flute=, shank=, stickout= and holder= (mm; holder=none or "
                "D:L,... bottom first)",
                where);
  }
  tool.flute_length = *flute;
  tool.shank_diameter = *shank;
  tool.stickout = *stickout;
  if (holder->second != "none") {
    for (const auto stage_text : split(holder->second, ',')) {
      const auto stage = holder_stage(stage_text);
      if (!stage) {
        return fail(ErrorCode::bad_input,
                    "PPRINT TOOL: holder stage '" + std::string(stage_text) +
                        "': expected D:L or D1:D2:L",
                    where);
      }
      tool.holder.push_back(*stage);
    }
  }
  if (auto valid = tool.validate("PPRINT TOOL"); !valid) {
    return fail(ErrorCode::bad_input, "PPRINT TOOL: " + valid.error().message, where);
  }
  return tool;
}

std::string fixture_record(const geometry::Fixture& fixture) {
  return fmt::format("floor={} margin={:g} clearance={:g}",
                     fixture.floor_z ? fmt::format("{:.6f}", *fixture.floor_z) : "none",
                     fixture.stock_margin, fixture.clearance_min);
}

Expected<std::optional<RecordedTool>> recorded_tool(const cl::ClHeader& header,
                                                    const std::string& cl_file) {
  const auto& records = header.whole_tool;
  if (records.tool.empty() || records.fixture.empty()) {
    return std::optional<RecordedTool>();
  }
  RecordedTool out;
  SUBFEED_TRY_ASSIGN(out.tool,
                     parse_tool_record(header.cutter.diameter / 2, records.tool,
                                       {cl_file, static_cast<int>(records.tool_line), {}}));
  SUBFEED_TRY_ASSIGN(
      out.fixture,
      parse_fixture_record(records.fixture, {cl_file, static_cast<int>(records.fixture_line), {}}));
  return std::optional<RecordedTool>(std::move(out));
}

Expected<geometry::Fixture> parse_fixture_record(std::string_view text, const Where& where) {
  const auto fields = fields_of(text);
  geometry::Fixture fixture;
  const auto floor = fields.find("floor");
  const auto margin = fields.find("margin");
  const auto clearance = fields.find("clearance");
  const double m = margin == fields.end() ? -1.0 : parse_double(margin->second).value_or(-1.0);
  const double c =
      clearance == fields.end() ? -1.0 : parse_double(clearance->second).value_or(-1.0);
  const auto z =
      floor == fields.end() || floor->second == "none" ? std::nullopt : parse_double(floor->second);
  if (floor == fields.end() || (floor->second != "none" && !z) || m < 0.0 || c < 0.0) {
    return fail(ErrorCode::bad_input,
                "PPRINT FIXTURE needs floor= (mm or none), margin= and clearance= (mm, at least 0)",
                where);
  }
  fixture.floor_z = z;
  fixture.stock_margin = m;
  fixture.clearance_min = c;
  return fixture;
}

void record_tool(cl::ClHeader& header, const geometry::PlanOptions& options,
                 const geometry::PlanSummary& summary) {
  if (options.whole_tool) {
    header.whole_tool.tool = tool_record(options.tool);
    header.whole_tool.fixture = fixture_record(summary.fixture);
  }
}

} // namespace subfeed::job

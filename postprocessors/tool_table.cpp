#include "post/tool_table.hpp"

#include "toml_table_reader.hpp"

#include <algorithm>
#include <sstream>

namespace subfeed::post {

namespace {

constexpr double largest_size = 10000.0; // mm: any size above is a typing slip

Expected<double> size_of(TomlTableReader& table, std::string_view key) {
  SUBFEED_TRY_ASSIGN(const double value, table.number(key));
  if (!(value > 0.0 && value <= largest_size)) {
    std::ostringstream message;
    message << value << " mm is outside 0 (excluded) .. " << largest_size << " mm";
    return table.invalid(key, message.str());
  }
  return value;
}

Expected<std::optional<double>> optional_size(TomlTableReader& table, std::string_view key) {
  if (!table.has(key)) {
    return std::optional<double>();
  }
  SUBFEED_TRY_ASSIGN(const double value, size_of(table, key));
  return std::optional<double>(value);
}

Expected<std::vector<ToolTableHolderStage>> holder_of(TomlTableReader& table) {
  std::vector<ToolTableHolderStage> stages;
  if (!table.has("holder")) {
    return stages;
  }
  SUBFEED_TRY_ASSIGN(const auto lists, table.number_lists("holder"));
  for (const auto& l : lists) {
    const bool sizes_ok =
        std::ranges::all_of(l, [](double v) { return v > 0.0 && v <= largest_size; });
    if ((l.size() != 2 && l.size() != 3) || !sizes_ok) {
      return table.invalid("holder", "expected stages [D, L] or [D1, D2, L], bottom first, each "
                                     "size above 0 and at most 10000 mm");
    }
    stages.push_back(l.size() == 2 ? ToolTableHolderStage{l[0], l[0], l[1]}
                                   : ToolTableHolderStage{l[0], l[1], l[2]});
  }
  return stages;
}

Expected<ToolTableEntry> read_tool(TomlTableReader table, std::string name, int line) {
  ToolTableEntry tool;
  tool.name = std::move(name);
  tool.line = line;
  SUBFEED_TRY_ASSIGN(tool.cutter, table.choice("cutter", {"ball"}));
  SUBFEED_TRY_ASSIGN(tool.diameter, size_of(table, "diameter"));
  SUBFEED_TRY_ASSIGN(tool.flute, optional_size(table, "flute"));
  SUBFEED_TRY_ASSIGN(tool.shank, optional_size(table, "shank"));
  SUBFEED_TRY_ASSIGN(tool.stickout, optional_size(table, "stickout"));
  SUBFEED_TRY_ASSIGN(tool.holder, holder_of(table));
  SUBFEED_TRY(table.finish());
  return tool;
}

} // namespace

const ToolTableEntry* ToolTable::find(std::string_view name) const {
  const auto it = std::ranges::find(tools, name, &ToolTableEntry::name);
  return it == tools.end() ? nullptr : &*it;
}

Expected<ToolTable> parse_tool_table(std::string_view text, const std::string& source) {
  SUBFEED_TRY_ASSIGN(const auto root, parse_toml(text, source));
  ToolTable out;
  out.file = source;
  TomlTableReader top(root, "", source, 1);
  for (const auto& [key, node] : root) {
    const std::string name(key.str());
    if (name.find(':') != std::string::npos) {
      return fail(ErrorCode::bad_input,
                  "a tool's name may not hold ':' (--tool would read it as a cutter, ball:D)",
                  {source, static_cast<int>(key.source().begin.line), name});
    }
    SUBFEED_TRY_ASSIGN(auto table, top.table(name));
    SUBFEED_TRY_ASSIGN(
        auto tool, read_tool(std::move(table), name, static_cast<int>(key.source().begin.line)));
    out.tools.push_back(std::move(tool));
  }
  if (out.tools.empty()) {
    return fail(ErrorCode::bad_input, "no tools: expected one [NAME] table per tool",
                {source, 0, {}});
  }
  return out;
}

Expected<ToolTable> load_tool_table(const std::filesystem::path& path) {
  SUBFEED_TRY_ASSIGN(const auto text, read_config_text(path, "tool table"));
  return parse_tool_table(text, path.string());
}

} // namespace subfeed::post

#pragma once
// A shop's tool table (configs/tools.toml): one TOML table per tool, named by its key, so
// `--tool NAME` stands for the cutter and everything above it. Read as strictly as a
// machine config: an unknown key, a wrong type or a size out of range is one error naming
// the file, the line and the dotted key. Sizes in mm; a holder stage is [D, L] (a cylinder)
// or [D1, D2, L] (a cone, D1 nearer the tip), bottom stage first. Plain numbers only: what
// they mean for the tool's shape is the planner's (geometry/tool_assembly.hpp).

#include "base/error.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace subfeed::post {

struct ToolTableHolderStage {
  double bottom_diameter = 0.0; // mm
  double top_diameter = 0.0;    // mm; the bottom's for a cylinder
  double length = 0.0;          // mm
};

struct ToolTableEntry {
  std::string name;
  int line = 0;                   // of its table in the file
  std::string cutter = "ball";    // the only kind cut today
  double diameter = 0.0;          // mm
  std::optional<double> flute;    // mm from the tip; default 3 D
  std::optional<double> shank;    // mm; default the cutter's diameter
  std::optional<double> stickout; // mm, tip to holder face; default 4 D
  std::vector<ToolTableHolderStage> holder;
};

struct ToolTable {
  std::string file;
  std::vector<ToolTableEntry> tools; // by name

  [[nodiscard]] const ToolTableEntry* find(std::string_view name) const;
};

[[nodiscard]] Expected<ToolTable> load_tool_table(const std::filesystem::path& path);
[[nodiscard]] Expected<ToolTable> parse_tool_table(std::string_view text,
                                                   const std::string& source);

} // namespace subfeed::post

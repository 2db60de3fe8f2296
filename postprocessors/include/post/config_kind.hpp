#pragma once
// What a config file under configs/ holds, told by its content: a machine config has a
// [machine] table (post/machine_config.hpp); any other is a tool table
// (post/tool_table.hpp). `subfeed config` checks either.

#include "base/error.hpp"

#include <filesystem>

namespace subfeed::post {

enum class ConfigKind { machine, tool_table };

// Errors: the file cannot be read, or is not TOML (file and line named).
[[nodiscard]] Expected<ConfigKind> config_kind(const std::filesystem::path& path);

} // namespace subfeed::post

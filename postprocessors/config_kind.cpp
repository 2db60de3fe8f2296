#include "post/config_kind.hpp"

#include "toml_table_reader.hpp"

namespace subfeed::post {

Expected<ConfigKind> config_kind(const std::filesystem::path& path) {
  SUBFEED_TRY_ASSIGN(const auto text, read_config_text(path, "config"));
  SUBFEED_TRY_ASSIGN(const auto root, parse_toml(text, path.string()));
  return root.contains("machine") ? ConfigKind::machine : ConfigKind::tool_table;
}

} // namespace subfeed::post

#include "post/config_kind.hpp"

#include <toml++/toml.h>

#include <fstream>
#include <sstream>

namespace subfeed::post {

Expected<ConfigKind> config_kind(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot open config", {path.string(), 0, {}});
  }
  std::ostringstream text;
  text << in.rdbuf();
  try {
    const auto root = toml::parse(text.str(), path.string());
    return root.contains("machine") ? ConfigKind::machine : ConfigKind::tool_table;
  } catch (const toml::parse_error& e) {
    return fail(ErrorCode::bad_input, "TOML syntax: " + std::string(e.description()),
                {path.string(), static_cast<int>(e.source().begin.line), {}});
  }
}

} // namespace subfeed::post

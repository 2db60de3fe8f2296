#pragma once
// Reads one TOML table strictly: every read names its dotted key, every error carries the
// file, line and key, and finish() rejects the keys nobody asked for, so a misspelt key is
// an error instead of a silently ignored setting. Internal to the postprocessors target.

#include "base/error.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace subfeed::post {

// The text of a config file; `what` names it in the error ("machine config").
[[nodiscard]] Expected<std::string> read_config_text(const std::filesystem::path& path,
                                                     std::string_view what);
// TOML text parsed, or its syntax error with the file (`source`) and line.
[[nodiscard]] Expected<toml::table> parse_toml(std::string_view text, const std::string& source);

class TomlTableReader {
public:
  TomlTableReader(const toml::table& table, std::string prefix, std::string file, int line);

  [[nodiscard]] bool has(std::string_view key) const;

  [[nodiscard]] Expected<double> number(std::string_view key);
  [[nodiscard]] Expected<long> integer(std::string_view key);
  [[nodiscard]] Expected<bool> boolean(std::string_view key);
  [[nodiscard]] Expected<std::string> string(std::string_view key);
  [[nodiscard]] Expected<std::vector<double>> numbers(std::string_view key, std::size_t count);
  [[nodiscard]] Expected<TomlTableReader> table(std::string_view key);
  // An array of arrays of numbers, each inner array of any length.
  [[nodiscard]] Expected<std::vector<std::vector<double>>> number_lists(std::string_view key);

  // One of `choices`, else an error listing them.
  [[nodiscard]] Expected<std::string> choice(std::string_view key,
                                             std::initializer_list<std::string_view> choices);

  // An error for `key` (which must exist) that is about its value.
  [[nodiscard]] std::unexpected<Error> invalid(std::string_view key, std::string message) const;
  // An error about the table itself (e.g. a missing combination of keys).
  [[nodiscard]] std::unexpected<Error> invalid_table(std::string message) const;

  [[nodiscard]] Expected<void> finish() const;

private:
  [[nodiscard]] Expected<const toml::node*> required(std::string_view key, std::string_view type);
  [[nodiscard]] Where where(std::string_view key) const;

  const toml::table* table_;
  std::string prefix_;
  std::string file_;
  int line_;
  std::set<std::string, std::less<>> used_;
};

} // namespace subfeed::post

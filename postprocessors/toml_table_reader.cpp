#include "toml_table_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>

namespace subfeed::post {

namespace {

std::string_view type_name(const toml::node& node) {
  switch (node.type()) {
  case toml::node_type::table:
    return "a table";
  case toml::node_type::array:
    return "an array";
  case toml::node_type::string:
    return "a string";
  case toml::node_type::integer:
    return "an integer";
  case toml::node_type::floating_point:
    return "a number";
  case toml::node_type::boolean:
    return "a boolean";
  default:
    return "a date or time";
  }
}

// Levenshtein distance, for suggesting the key a user probably meant.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) {
    row[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

} // namespace

Expected<std::string> read_config_text(const std::filesystem::path& path, std::string_view what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot open " + std::string(what), {path.string(), 0, {}});
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Expected<toml::table> parse_toml(std::string_view text, const std::string& source) {
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    return fail(ErrorCode::bad_input, "TOML syntax: " + std::string(e.description()),
                {source, static_cast<int>(e.source().begin.line), {}});
  }
}

TomlTableReader::TomlTableReader(const toml::table& table, std::string prefix, std::string file,
                                 int line)
    : table_(&table), prefix_(std::move(prefix)), file_(std::move(file)), line_(line) {}

bool TomlTableReader::has(std::string_view key) const {
  return table_->contains(key);
}

Where TomlTableReader::where(std::string_view key) const {
  const toml::node* node = table_->get(key);
  const int line = node != nullptr ? static_cast<int>(node->source().begin.line) : line_;
  return {file_, line, prefix_ + std::string(key)};
}

std::unexpected<Error> TomlTableReader::invalid(std::string_view key, std::string message) const {
  return fail(ErrorCode::bad_input, std::move(message), where(key));
}

std::unexpected<Error> TomlTableReader::invalid_table(std::string message) const {
  std::string key =
      prefix_.empty() ? std::string("(top level)") : prefix_.substr(0, prefix_.size() - 1);
  return fail(ErrorCode::bad_input, std::move(message), {file_, line_, std::move(key)});
}

Expected<const toml::node*> TomlTableReader::required(std::string_view key, std::string_view type) {
  used_.emplace(key);
  const toml::node* node = table_->get(key);
  if (node == nullptr) {
    // A misspelt key shows up as a missing one; point at the misspelling instead.
    for (const auto& [present, value] : *table_) {
      const std::size_t distance = edit_distance(present.str(), key);
      if (!used_.contains(present.str()) && distance <= 2 && 3 * distance < key.size()) {
        return fail(ErrorCode::bad_input, "unknown key; did you mean '" + std::string(key) + "'?",
                    {file_, static_cast<int>(present.source().begin.line),
                     prefix_ + std::string(present.str())});
      }
    }
    return fail(ErrorCode::bad_input, "missing required key (" + std::string(type) + ")",
                {file_, line_, prefix_ + std::string(key)});
  }
  return node;
}

Expected<double> TomlTableReader::number(std::string_view key) {
  auto node = required(key, "a number");
  if (!node) {
    return std::unexpected(node.error());
  }
  if (!(*node)->is_number()) {
    return invalid(key, "expected a number, got " + std::string(type_name(**node)));
  }
  const double value = *(*node)->value<double>();
  if (!std::isfinite(value)) {
    return invalid(key, "expected a finite number");
  }
  return value;
}

Expected<long> TomlTableReader::integer(std::string_view key) {
  auto node = required(key, "an integer");
  if (!node) {
    return std::unexpected(node.error());
  }
  if (!(*node)->is_integer()) {
    return invalid(key, "expected an integer, got " + std::string(type_name(**node)));
  }
  return static_cast<long>(*(*node)->value<std::int64_t>());
}

Expected<bool> TomlTableReader::boolean(std::string_view key) {
  auto node = required(key, "true or false");
  if (!node) {
    return std::unexpected(node.error());
  }
  if (!(*node)->is_boolean()) {
    return invalid(key, "expected true or false, got " + std::string(type_name(**node)));
  }
  return *(*node)->value<bool>();
}

Expected<std::string> TomlTableReader::string(std::string_view key) {
  auto node = required(key, "a string");
  if (!node) {
    return std::unexpected(node.error());
  }
  if (!(*node)->is_string()) {
    return invalid(key, "expected a string, got " + std::string(type_name(**node)));
  }
  return *(*node)->value<std::string>();
}

Expected<std::vector<double>> TomlTableReader::numbers(std::string_view key, std::size_t count) {
  auto node = required(key, "an array of numbers");
  if (!node) {
    return std::unexpected(node.error());
  }
  const toml::array* array = (*node)->as_array();
  const std::string expected = "expected an array of " + std::to_string(count) + " numbers";
  if (array == nullptr || array->size() != count) {
    return invalid(key, expected);
  }
  std::vector<double> values;
  for (const toml::node& element : *array) {
    if (!element.is_number() || !std::isfinite(*element.value<double>())) {
      return invalid(key, expected);
    }
    values.push_back(*element.value<double>());
  }
  return values;
}

Expected<std::vector<std::vector<double>>> TomlTableReader::number_lists(std::string_view key) {
  auto node = required(key, "an array of arrays of numbers");
  if (!node) {
    return std::unexpected(node.error());
  }
  const toml::array* outer = (*node)->as_array();
  const std::string expected = "expected an array of arrays of numbers";
  if (outer == nullptr) {
    return invalid(key, expected + ", got " + std::string(type_name(**node)));
  }
  std::vector<std::vector<double>> lists;
  for (const toml::node& element : *outer) {
    const toml::array* inner = element.as_array();
    if (inner == nullptr) {
      return invalid(key, expected);
    }
    auto& list = lists.emplace_back();
    for (const toml::node& value : *inner) {
      if (!value.is_number() || !std::isfinite(*value.value<double>())) {
        return invalid(key, expected);
      }
      list.push_back(*value.value<double>());
    }
  }
  return lists;
}

Expected<TomlTableReader> TomlTableReader::table(std::string_view key) {
  auto node = required(key, "a table");
  if (!node) {
    return std::unexpected(node.error());
  }
  const toml::table* sub = (*node)->as_table();
  if (sub == nullptr) {
    return invalid(key, "expected a table, got " + std::string(type_name(**node)));
  }
  return TomlTableReader(*sub, prefix_ + std::string(key) + ".", file_,
                         static_cast<int>(sub->source().begin.line));
}

Expected<std::string> TomlTableReader::choice(std::string_view key,
                                              std::initializer_list<std::string_view> choices) {
  auto value = string(key);
  if (!value) {
    return value;
  }
  std::string listed;
  for (const auto c : choices) {
    if (c == *value) {
      return value;
    }
    listed += (listed.empty() ? "" : ", ") + std::string(c);
  }
  return invalid(key, "'" + *value + "' is not one of " + listed);
}

Expected<void> TomlTableReader::finish() const {
  for (const auto& [key, node] : *table_) {
    if (!used_.contains(key.str())) {
      return fail(
          ErrorCode::bad_input, "unknown key",
          {file_, static_cast<int>(key.source().begin.line), prefix_ + std::string(key.str())});
    }
  }
  return {};
}

} // namespace subfeed::post

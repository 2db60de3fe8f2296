#pragma once
// Whole text files for assertions: the content, or its lines without their endings.

#include <filesystem>
#include <string>
#include <vector>

namespace subfeed::testing {

// Empty when the file cannot be read (the assertion on the content then fails visibly).
[[nodiscard]] std::string read_text(const std::filesystem::path& path);
[[nodiscard]] std::vector<std::string> lines_of(const std::filesystem::path& path);

} // namespace subfeed::testing

#pragma once
// An output file that appears under its name only when complete: text goes to a temporary
// file beside the target, and commit() flushes, syncs and renames it over the target. If
// the object dies without commit() (an error, an exception, a stop) the temporary is
// removed and any earlier file under the target name is untouched. Not copyable.

#include "base/error.hpp"

#include <cstdio>
#include <filesystem>
#include <string_view>

namespace subfeed {

class AtomicOutputFile {
public:
  [[nodiscard]] static Expected<AtomicOutputFile> create(const std::filesystem::path& target);

  AtomicOutputFile(AtomicOutputFile&& other) noexcept;
  AtomicOutputFile& operator=(AtomicOutputFile&&) = delete;
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;
  ~AtomicOutputFile();

  // Buffered; a failed write shows in commit().
  void write(std::string_view text);
  [[nodiscard]] Expected<void> commit();
  [[nodiscard]] const std::filesystem::path& target() const { return target_; }

private:
  AtomicOutputFile(std::FILE* file, std::filesystem::path target, std::filesystem::path temp);
  void discard();

  std::FILE* file_;
  std::filesystem::path target_;
  std::filesystem::path temp_;
};

} // namespace subfeed

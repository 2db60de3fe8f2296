#include "base/atomic_output_file.hpp"

#include <cerrno>
#include <cstring>
#include <unistd.h>
#include <utility>

namespace subfeed {

namespace {

std::unexpected<Error> io_error(const std::filesystem::path& path, std::string_view what) {
  return fail(ErrorCode::bad_input, std::string(what) + ": " + std::strerror(errno),
              {path.string(), 0, {}});
}

} // namespace

Expected<AtomicOutputFile> AtomicOutputFile::create(const std::filesystem::path& target) {
  auto temp = target;
  temp += ".part-" + std::to_string(::getpid());
  std::FILE* file = std::fopen(temp.c_str(), "wb");
  if (file == nullptr) {
    return io_error(target, "cannot create output file");
  }
  return AtomicOutputFile(file, target, std::move(temp));
}

AtomicOutputFile::AtomicOutputFile(std::FILE* file, std::filesystem::path target,
                                   std::filesystem::path temp)
    : file_(file), target_(std::move(target)), temp_(std::move(temp)) {}

AtomicOutputFile::AtomicOutputFile(AtomicOutputFile&& other) noexcept
    : file_(std::exchange(other.file_, nullptr)), target_(std::move(other.target_)),
      temp_(std::move(other.temp_)) {}

AtomicOutputFile::~AtomicOutputFile() {
  discard();
}

void AtomicOutputFile::discard() {
  if (file_ != nullptr) {
    std::fclose(file_);
    file_ = nullptr;
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
  }
}

void AtomicOutputFile::write(std::string_view text) {
  if (file_ != nullptr) {
    std::fwrite(text.data(), 1, text.size(), file_);
  }
}

Expected<void> AtomicOutputFile::commit() {
  if (file_ == nullptr) {
    return fail(ErrorCode::bad_input, "output already closed", {target_.string(), 0, {}});
  }
  const bool written =
      std::fflush(file_) == 0 && std::ferror(file_) == 0 && ::fsync(::fileno(file_)) == 0;
  if (!written) {
    const auto error = io_error(target_, "cannot write output file");
    discard();
    return error;
  }
  std::fclose(std::exchange(file_, nullptr));
  if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
    const auto error = io_error(target_, "cannot rename the finished output into place");
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
    return error;
  }
  return {};
}

} // namespace subfeed

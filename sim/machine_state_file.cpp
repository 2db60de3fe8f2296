#include "sim/machine_state_file.hpp"

#include "base/number_text.hpp"

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <unistd.h>

namespace subfeed::sim {

namespace {

constexpr std::size_t field = 16;             // "%15.6f " per axis
constexpr std::size_t record = 6 * field + 1; // and a newline

std::optional<AxisArray> parse(const char* text, std::size_t size) {
  if (size < record) {
    return std::nullopt;
  }
  AxisArray p{};
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::string_view word(text + i * field, field);
    const auto first = word.find_first_not_of(' ');
    const auto last = word.find_last_not_of(' ');
    const auto value = first == std::string_view::npos
                           ? std::nullopt
                           : parse_double(word.substr(first, last - first + 1));
    if (!value) {
      return std::nullopt;
    }
    p[i] = *value;
  }
  return p;
}

} // namespace

Expected<MachineStateFile> MachineStateFile::open(const std::filesystem::path& path) {
  UniqueFd fd(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644));
  if (!fd.valid()) {
    return fail(ErrorCode::bad_input,
                std::string("cannot open the machine state file: ") + std::strerror(errno),
                {path.string(), 0, {}});
  }
  std::array<char, record> text{};
  const ssize_t got = ::pread(fd.get(), text.data(), text.size(), 0);
  if (got > 0 && !parse(text.data(), static_cast<std::size_t>(got))) {
    return fail(ErrorCode::bad_input, "not a machine state record (six axis positions)",
                {path.string(), 1, {}});
  }
  const auto stored = got > 0 ? parse(text.data(), static_cast<std::size_t>(got)) : std::nullopt;
  return MachineStateFile(std::move(fd), stored);
}

void MachineStateFile::save(const AxisArray& position) {
  if (saved_ == position) {
    return;
  }
  std::array<char, record + 1> text{};
  for (std::size_t i = 0; i < position.size(); ++i) {
    std::snprintf(text.data() + i * field, field + 1, "%15.6f ", position[i]);
  }
  text[record - 1] = '\n';
  if (::pwrite(fd_.get(), text.data(), record, 0) == static_cast<ssize_t>(record)) {
    saved_ = position;
  }
}

} // namespace subfeed::sim

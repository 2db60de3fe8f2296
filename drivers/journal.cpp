#include "drivers/journal.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace subfeed::drivers {

Expected<Journal> Journal::open(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) {
    return fail(ErrorCode::bad_input, std::string("cannot open journal: ") + std::strerror(errno),
                {path.string(), 0, "--journal"});
  }
  return Journal(fd);
}

void Journal::write_line(std::string_view text) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::steady_clock::now() - start_);
  std::string line = std::to_string(ms.count()) + " ";
  line += text;
  line += '\n';
  // One write per event, O_APPEND: a line is whole or absent, and on disk once the OS has it.
  (void)!::write(fd_.get(), line.data(), line.size());
}

void Journal::start(std::string_view protocol, std::string_view program, std::string_view link) {
  write_line("start protocol=" + std::string(protocol) + " program=" + std::string(program) +
             " link=" + std::string(link));
}

void Journal::sent(long line, long bytes) {
  write_line("sent line=" + std::to_string(line) + " bytes=" + std::to_string(bytes));
}

void Journal::answered(long line, int error_code) {
  write_line("answered line=" + std::to_string(line) +
             (error_code == 0 ? std::string(" ok") : " error:" + std::to_string(error_code)));
}

void Journal::event(std::string_view name, std::string_view detail) {
  write_line("event " + std::string(name) + (detail.empty() ? "" : " " + std::string(detail)));
}

void Journal::end(const Expected<StreamSummary>& outcome) {
  write_line(outcome ? "end done" : "end failed " + outcome.error().describe());
}

void JournaledObserver::progress(const StreamProgress& p) {
  const std::string state = p.status ? p.status->state : p.link_state;
  if (state != last_state_) { // state changes, not every poll
    last_state_ = state;
    journal_.event("state", state);
  }
  inner_.progress(p);
}

void JournaledObserver::phase(std::string_view name) {
  journal_.event("phase", name);
  inner_.phase(name);
}

} // namespace subfeed::drivers

#include "drivers/control_inbox.hpp"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <sys/eventfd.h>
#include <unistd.h>

namespace subfeed::drivers {

Expected<std::unique_ptr<ControlInbox>> ControlInbox::create() {
  const int fd = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (fd < 0) {
    return fail(ErrorCode::machine_fault, std::string("eventfd: ") + std::strerror(errno));
  }
  return std::unique_ptr<ControlInbox>(new ControlInbox(fd));
}

void ControlInbox::push(ControlCommand command) {
  {
    const std::lock_guard lock(mutex_);
    commands_.push_back(command);
  }
  const std::uint64_t one = 1;
  (void)!::write(event_fd_.get(), &one, sizeof one);
}

std::vector<ControlCommand> ControlInbox::take() {
  std::uint64_t count = 0;
  (void)!::read(event_fd_.get(), &count, sizeof count);
  const std::lock_guard lock(mutex_);
  std::vector<ControlCommand> taken(commands_.begin(), commands_.end());
  commands_.clear();
  return taken;
}

} // namespace subfeed::drivers

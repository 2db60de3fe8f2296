#include "drivers/transport.hpp"

namespace subfeed::drivers {

Expected<void> write_all(Transport& link, std::span<const char> bytes,
                         std::chrono::milliseconds timeout) {
  while (!bytes.empty()) {
    SUBFEED_TRY_ASSIGN(const std::size_t n, link.write(bytes, timeout));
    if (n == 0) {
      return fail(ErrorCode::machine_fault,
                  "link accepted no bytes for " + std::to_string(timeout.count()) + " ms",
                  {link.name(), 0, {}});
    }
    bytes = bytes.subspan(n);
  }
  return {};
}

} // namespace subfeed::drivers

#pragma once
// The simulators' one way of reporting a failed system call: what failed, errno's text, and
// the device or address it failed on.

#include "base/error.hpp"

#include <cerrno>
#include <cstring>
#include <string>

namespace subfeed::sim {

[[nodiscard]] inline std::unexpected<Error> os_failure(const std::string& what,
                                                       const std::string& where) {
  return fail(ErrorCode::machine_fault, what + ": " + std::strerror(errno), {where, 0, {}});
}

} // namespace subfeed::sim

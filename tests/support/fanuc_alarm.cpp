#include "support/fanuc_alarm.hpp"

#include <thread>

namespace subfeed::testing {

std::string alarm_within(const sim::FanucSim& control, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (control.stats().alarm.empty() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return control.stats().alarm;
}

} // namespace subfeed::testing

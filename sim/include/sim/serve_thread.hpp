#pragma once
// The thread a simulator serves on when used in-process: started with the serving loop,
// asked to stop and joined on stop() or destruction.

#include <functional>
#include <stop_token>
#include <thread>

namespace subfeed::sim {

class ServeThread {
public:
  ServeThread() = default;
  ServeThread(const ServeThread&) = delete;
  ServeThread& operator=(const ServeThread&) = delete;
  ~ServeThread() { stop(); }

  void start(std::function<void(const std::stop_token&)> serve) {
    thread_ =
        std::jthread([serve = std::move(serve)](const std::stop_token& stop) { serve(stop); });
  }
  void stop() {
    if (thread_.joinable()) {
      thread_.request_stop();
      thread_.join();
    }
  }

private:
  std::jthread thread_;
};

} // namespace subfeed::sim

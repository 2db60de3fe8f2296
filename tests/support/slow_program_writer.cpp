#include "support/slow_program_writer.hpp"

#include <condition_variable>
#include <mutex>
#include <stop_token>

namespace subfeed::testing {

std::jthread write_slowly(drivers::ProgramQueue& queue, std::vector<std::string> program,
                          std::size_t pause_after, std::chrono::milliseconds pause) {
  return std::jthread(
      [&queue, program = std::move(program), pause_after, pause](const std::stop_token& stop) {
        for (std::size_t i = 0; i < program.size(); ++i) {
          if (i == pause_after) {
            std::mutex m;
            std::condition_variable_any cv;
            std::unique_lock lock(m);
            if (cv.wait_for(lock, stop, pause, [] { return false; }) || stop.stop_requested()) {
              return;
            }
          }
          if (!queue.push(program[i])) {
            return;
          }
        }
        queue.close();
      });
}

} // namespace subfeed::testing

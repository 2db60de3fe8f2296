// The queue between the post and the sender: ready() tells whether pop() would wait.

#include "base/bounded_queue.hpp"

#include <catch2/catch.hpp>
#include <string>
#include <thread>

using namespace std::chrono_literals;

TEST_CASE("a queue is ready with an item in it or once closed, never while empty and open") {
  subfeed::BoundedQueue<std::string> queue(2);
  CHECK_FALSE(queue.ready(0ms));
  CHECK_FALSE(queue.ready(20ms));
  REQUIRE(queue.push("G1X1"));
  CHECK(queue.ready(0ms));
  CHECK(queue.pop() == std::optional<std::string>("G1X1"));
  CHECK_FALSE(queue.ready(0ms));
  queue.close();
  CHECK(queue.ready(0ms));
  CHECK_FALSE(queue.pop());
}

TEST_CASE("a queue's ready() wakes when the writer pushes") {
  subfeed::BoundedQueue<std::string> queue(2);
  std::jthread writer([&queue] {
    std::this_thread::sleep_for(50ms);
    (void)queue.push("G1X2");
  });
  CHECK(queue.ready(60s)); // returns with the push, not after a minute
  CHECK(queue.pop() == std::optional<std::string>("G1X2"));
}

#pragma once
// A queue between two threads of a pipeline with back-pressure: push() waits while the
// queue holds `capacity` items, pop() waits while it is empty; a consumer with other duties
// asks ready() first, which waits no longer than it is told. close() ends it from either
// side: a producer closes when it has no more, a consumer that gives up closes so that a
// producer blocked in push() wakes and learns nobody is listening. Memory is bounded by the
// capacity, however long the stream.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>

namespace subfeed {

template <class T> class BoundedQueue {
public:
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity == 0 ? 1 : capacity) {}

  // False when the queue was closed: the item was not taken.
  bool push(T item) {
    std::unique_lock lock(mutex_);
    not_full_.wait(lock, [this] { return closed_ || items_.size() < capacity_; });
    if (closed_) {
      return false;
    }
    items_.push_back(std::move(item));
    not_empty_.notify_one();
    return true;
  }

  // nullopt once the queue is closed and drained.
  std::optional<T> pop() {
    std::unique_lock lock(mutex_);
    not_empty_.wait(lock, [this] { return closed_ || !items_.empty(); });
    if (items_.empty()) {
      return std::nullopt;
    }
    T item = std::move(items_.front());
    items_.pop_front();
    not_full_.notify_one();
    return item;
  }

  // Whether pop() would return at once (an item is there, or the queue is closed), waiting
  // up to `wait` for that.
  [[nodiscard]] bool ready(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    return not_empty_.wait_for(lock, wait, [this] { return closed_ || !items_.empty(); });
  }

  void close() {
    const std::lock_guard lock(mutex_);
    closed_ = true;
    not_full_.notify_all();
    not_empty_.notify_all();
  }

  [[nodiscard]] std::size_t capacity() const { return capacity_; }

private:
  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable not_full_, not_empty_;
  std::deque<T> items_;
  bool closed_ = false;
};

} // namespace subfeed

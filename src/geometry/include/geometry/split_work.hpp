#pragma once
// Work over independent items split across the machine's cores: `work(begin, end)` is
// called once per contiguous share of [0, n), each share on its own thread, and all are
// joined before this returns. Items must not write anything another item reads. Small
// jobs run on the caller's thread alone, where a thread would cost more than it saves.

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace subfeed::geometry {

template <class Work> void split_work(std::size_t n, Work&& work, std::size_t min_share = 4096) {
  const std::size_t cores = std::max<std::size_t>(1, std::thread::hardware_concurrency());
  const std::size_t shares =
      std::clamp<std::size_t>(n / std::max<std::size_t>(min_share, 1), 1, cores);
  if (shares == 1) {
    work(std::size_t{0}, n);
    return;
  }
  std::vector<std::jthread> threads;
  const std::size_t each = (n + shares - 1) / shares;
  for (std::size_t s = 1; s < shares; ++s) {
    threads.emplace_back([&work, s, each, n] { work(s * each, std::min(n, (s + 1) * each)); });
  }
  work(std::size_t{0}, std::min(n, each));
}

} // namespace subfeed::geometry

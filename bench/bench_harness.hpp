#pragma once
// The shape every benchmark reports in: a figure measured next to its baseline in the same
// run, on the same machine, so that the ratio means something on a shared, noisy host.
// Times are the best of several repetitions.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

namespace subfeed::bench {

// Seconds for the fastest of `repetitions` calls of `work`.
template <class Work> double best_seconds(int repetitions, Work&& work) {
  double best = 1e300;
  for (int i = 0; i < repetitions; ++i) {
    const auto start = std::chrono::steady_clock::now();
    work();
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    best = std::min(best, took.count());
  }
  return best;
}

struct Figure {
  std::string name;
  double value = 0.0;
  std::string unit;
  std::string baseline_name;
  double baseline = 0.0;
  bool higher_is_better = true;
};

// One line per figure: name, value, baseline, and value/baseline.
inline void report(const Figure& f) {
  std::printf("%-34s %12.4g %-10s baseline %-28s %12.4g %-10s ratio %.3f (%s is better)\n",
              f.name.c_str(), f.value, f.unit.c_str(), f.baseline_name.c_str(), f.baseline,
              f.unit.c_str(), f.baseline != 0.0 ? f.value / f.baseline : 0.0,
              f.higher_is_better ? "higher" : "lower");
  std::fflush(stdout);
}

// Peak resident memory of this process so far (VmHWM), MiB.
inline double peak_rss_mib() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      double kib = 0.0;
      status >> kib;
      return kib / 1024.0;
    }
  }
  return 0.0;
}

// Keeps the optimiser from deleting work whose result is otherwise unused.
template <class T> void keep(const T& value) {
  asm volatile("" : : "g"(&value) : "memory");
}

} // namespace subfeed::bench

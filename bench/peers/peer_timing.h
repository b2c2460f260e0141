#pragma once
// Timing for the peers' benchmarks: the median of three runs, steps per second.

#include <algorithm>
#include <chrono>
#include <functional>

namespace peers {

/// The median of three calls of f.
inline double Median3(const std::function<double()>& f) {
  double r[3] = {f(), f(), f()};
  std::sort(r, r + 3);
  return r[1];
}

/// Steps per second of `steps` calls of step.
inline double StepsPerSecond(const std::function<void()>& step, int steps) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int s = 0; s < steps; ++s) step();
  return steps / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace peers

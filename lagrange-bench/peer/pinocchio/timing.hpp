// The peers' one timer: the mean wall time of `calls` calls of f, after a
// tenth as many to warm up (included by each peer beside it).
#pragma once

#include <chrono>

template <class F>
static double ns_per_call(F f, int calls) {
  for (int i = 0; i < calls / 10; ++i) f();  // warm up
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < calls; ++i) f();
  const auto end = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(end - start).count() / calls;
}

// Wall seconds on the steady clock since `start`: how every phase time is taken.
#pragma once

#include <chrono>

namespace radflux {

inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace radflux

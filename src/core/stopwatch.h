#pragma once
// Wall-clock time for the one-line summaries commands print ("... 5.88 s -> out.prt").
#include <chrono>

namespace prt {

/// Seconds of steady (monotonic) clock time elapsed since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace prt

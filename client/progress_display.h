// Progress for a person: a redrawn bar per phase on a terminal, plain lines (at most a
// few per second) when stderr is not a terminal, e.g. in CI logs or under a pipe.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

namespace radflux::cli {

class ProgressDisplay {
 public:
  explicit ProgressDisplay(bool quiet);
  // Phase progress: done of total units.
  void Phase(std::string_view phase, int64_t done, int64_t total);
  // Solver progress: iteration and convergence measure.
  void Iteration(int iteration, double residual, double unshot_fraction);
  // A status in words: on a terminal a bar redrawn in place ("solving [####    ] 52%
  // detail"; no bar when `fraction` < 0), else one plain line "label: detail". Shown at most
  // every 100 ms (terminal) or 500 ms (plain), unless `force` (a change worth a line).
  void Show(std::string_view label, double fraction, std::string_view detail, bool force);
  // True when stderr is a terminal (bars are redrawn in place).
  bool terminal() const { return terminal_; }
  // Ends the current bar line, if any.
  void Finish();
  // A message on its own line.
  void Line(const std::string& text);

 private:
  bool Due(bool force);
  bool quiet_, terminal_, bar_open_ = false;
  int64_t last_done_ = -1;  // the last phase count shown, so a repeat is not shown twice
  std::chrono::steady_clock::time_point last_;
};

}  // namespace radflux::cli

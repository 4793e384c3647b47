#include "client/progress_display.h"

#include <unistd.h>

#include <cstdio>

namespace radflux::cli {

ProgressDisplay::ProgressDisplay(bool quiet)
    : quiet_(quiet), terminal_(isatty(STDERR_FILENO) != 0), last_() {}

bool ProgressDisplay::Due(bool force) {
  const auto now = std::chrono::steady_clock::now();
  const auto gap = terminal_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(500);
  if (!force && now - last_ < gap) return false;
  last_ = now;
  return true;
}

void ProgressDisplay::Phase(std::string_view phase, int64_t done, int64_t total) {
  if (quiet_ || done == last_done_ || !Due(done == total)) return;
  last_done_ = done;
  const double fraction = total > 0 ? double(done) / total : 1.0;
  if (terminal_) {
    const int width = 30, filled = static_cast<int>(fraction * width);
    std::fprintf(stderr, "\r%-6.*s [%.*s%*s] %5.1f%% %lld/%lld", int(phase.size()), phase.data(),
                 filled, "##############################", width - filled, "", 100 * fraction,
                 static_cast<long long>(done), static_cast<long long>(total));
    bar_open_ = true;
    if (done == total) Finish();
  } else {
    std::fprintf(stderr, "%.*s: %lld/%lld (%.1f%%)\n", int(phase.size()), phase.data(),
                 static_cast<long long>(done), static_cast<long long>(total), 100 * fraction);
  }
}

void ProgressDisplay::Iteration(int iteration, double residual, double unshot_fraction) {
  if (quiet_ || !Due(false)) return;
  const char* format = terminal_ ? "\rsolve  iteration %d residual %.3e unshot %.3e   "
                                 : "solve: iteration %d residual %.3e unshot %.3e\n";
  std::fprintf(stderr, format, iteration, residual, unshot_fraction);
  bar_open_ = terminal_;
}

void ProgressDisplay::Finish() {
  if (bar_open_) std::fputc('\n', stderr);
  bar_open_ = false;
}

void ProgressDisplay::Line(const std::string& text) {
  if (quiet_) return;
  Finish();
  std::fprintf(stderr, "%s\n", text.c_str());
}

}  // namespace radflux::cli

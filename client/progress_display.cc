#include "client/progress_display.h"

#include <unistd.h>

#include <algorithm>
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
  if (quiet_ || done == last_done_) return;
  const double fraction = total > 0 ? double(done) / total : 1.0;
  char detail[64];
  std::snprintf(detail, sizeof detail, "%lld/%lld", static_cast<long long>(done),
                static_cast<long long>(total));
  last_done_ = done;
  Show(phase, fraction, detail, done == total);
  if (done == total) Finish();
}

void ProgressDisplay::Show(std::string_view label, double fraction, std::string_view detail,
                           bool force) {
  if (quiet_ || !Due(force)) return;
  if (!terminal_) {
    std::fprintf(stderr, "%.*s%s%.*s\n", int(label.size()), label.data(),
                 detail.empty() ? "" : ": ", int(detail.size()), detail.data());
    return;
  }
  std::fprintf(stderr, "\r%-22.*s", int(label.size()), label.data());
  if (fraction >= 0) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(std::min(1.0, fraction) * kWidth);
    std::fprintf(stderr, " [%.*s%*s] %5.1f%%", filled, "##############################",
                 kWidth - filled, "", 100 * fraction);
  }
  // \033[K clears what a longer previous line left on the right.
  std::fprintf(stderr, "  %.*s\033[K", int(detail.size()), detail.data());
  bar_open_ = true;
}

void ProgressDisplay::Iteration(int iteration, double residual, double unshot_fraction) {
  char detail[96];
  std::snprintf(detail, sizeof detail, "iteration %d residual %.3e unshot %.3e", iteration,
                residual, unshot_fraction);
  Show("solve", -1, detail, false);
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

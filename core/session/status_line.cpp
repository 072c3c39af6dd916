#include "core/session/status_line.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdio>
#include <system_error>
#include <utility>

namespace rtiow {

std::string fit_to_columns(const std::string& line, std::size_t columns) {
  if (line.size() <= columns) return line;
  // Whole fields ("  ETA 9.3s") while they fit, the share first; a field cut in two misleads.
  std::string fitted;
  for (std::size_t start = 0; start < line.size();) {
    std::size_t next = line.find("  ", start + 1);
    if (next == std::string::npos) next = line.size();
    if (next > columns) break;
    fitted = line.substr(0, next);
    start = next;
  }
  return fitted.empty() ? line.substr(0, columns) : fitted;
}

std::string duration_text(double seconds) {
  char text[32];
  if (seconds < 60.0) {
    std::snprintf(text, sizeof text, "%.1fs", seconds);
  } else {
    const long long total = (long long)(seconds + 0.5);
    std::snprintf(text, sizeof text, "%lldm%02llds", total / 60, total % 60);
  }
  return text;
}

bool stderr_is_terminal() {
  return ::isatty(STDERR_FILENO) == 1;
}

void draw_live_line(const std::string& line) {
  winsize size{};
  const bool sized = ::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1;
  std::fprintf(stderr, "\r\033[K%s",
               (sized ? fit_to_columns(line, size.ws_col - 1) : line).c_str());
  std::fflush(stderr);
}

void erase_live_line() {
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
}

PeriodicReport::PeriodicReport(std::chrono::milliseconds period, std::function<void()> report)
    : period_(period), report_(std::move(report)) {
  try {
    thread_ = std::thread([this] {
      std::unique_lock lock(mutex_);
      while (!wake_.wait_for(lock, period_, [this] { return stop_; })) report_();
    });
  } catch (const std::system_error&) {
  }
}

PeriodicReport::~PeriodicReport() {
  stop();
}

void PeriodicReport::stop() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

}  // namespace rtiow

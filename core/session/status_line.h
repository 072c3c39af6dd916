#pragma once
// What every progress display on stderr shares: a line redrawn in place on a terminal (never
// wider than it: a wrapped line is not erased by the next \r), durations in one form, and a
// thread that reports at a steady period until it is stopped.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace rtiow {

// A progress line in at most `columns` characters: its leading fields that fit whole (the
// share first), or its first `columns` characters where not even the first does.
std::string fit_to_columns(const std::string& line, std::size_t columns);

// "12.0s" under a minute, else "3m05s".
std::string duration_text(double seconds);

// Whether stderr is a terminal (a live line) or not (a log: plain lines).
bool stderr_is_terminal();

// Replaces the terminal's current line with `line`, cut to the terminal's width.
void draw_live_line(const std::string& line);

// Clears the terminal's current line.
void erase_live_line();

// Calls `report` every `period` on a thread of its own until stop() (or the destructor). Where
// no thread can start (a limit of processes) it reports nothing: what it watches goes on.
class PeriodicReport {
 public:
  PeriodicReport(std::chrono::milliseconds period, std::function<void()> report);
  ~PeriodicReport();
  PeriodicReport(const PeriodicReport&) = delete;
  PeriodicReport& operator=(const PeriodicReport&) = delete;

  // Returns once `report` has run for the last time.
  void stop();

 private:
  const std::chrono::milliseconds period_;
  const std::function<void()> report_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace rtiow

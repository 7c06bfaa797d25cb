// SPDX-License-Identifier: MIT
// A one-line progress bar on stderr for long work: redrawn in place with \r, with the count (or
// percentage), the rate and the time left. Disabled (prints nothing at all) unless the stream is a
// terminal and the user did not ask for --quiet, so scripts and logs never see it.
#pragma once

#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>

namespace odeskin {

// True when stderr is a terminal (isatty(2)).
bool stderrIsTerminal();

class ProgressBar {
 public:
  // `total`: the number of items, or 0 for work measured as a fraction (update(fraction)).
  ProgressBar(std::ostream& out, std::string label, std::size_t total, bool enabled);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // `done` items finished (count mode).
  void step(std::size_t done);
  // Overall fraction in [0, 1] (fraction mode); the stage name replaces the label.
  void fraction(std::string_view stage, double fraction);
  // Clears the line (the bar is transient; the summary that follows says what happened).
  void finish();

  bool enabled() const { return enabled_; }

 private:
  void draw(double fraction, const std::string& counter);

  std::ostream& out_;
  std::string label_;
  std::size_t total_ = 0;
  bool enabled_ = false;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  std::size_t last_width_ = 0;
};

// "1.5 s", "2 min 05 s", "1 h 02 min" for ETAs.
std::string formatDuration(double seconds);

}  // namespace odeskin

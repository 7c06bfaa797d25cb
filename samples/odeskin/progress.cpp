// SPDX-License-Identifier: MIT
#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace odeskin {
namespace {

using Clock = std::chrono::steady_clock;

// Redraws at most this often: a terminal flooded with \r lines slows the work it reports.
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
constexpr int kBarCells = 24;

}  // namespace

bool stderrIsTerminal() { return isatty(STDERR_FILENO) == 1; }

std::string formatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  char text[32];
  if (seconds < 60.0) {
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  } else if (seconds < 3600.0) {
    const long s = std::lround(seconds);
    std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
  } else {
    const long m = std::lround(seconds / 60.0);
    std::snprintf(text, sizeof text, "%ld h %02ld min", m / 60, m % 60);
  }
  return text;
}

ProgressBar::ProgressBar(std::ostream& out, std::string label, std::size_t total, bool enabled)
    : out_(out), label_(std::move(label)), total_(total), enabled_(enabled), start_(Clock::now()) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::step(std::size_t done) {
  if (!enabled_ || total_ == 0) return;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  char counter[96];
  std::snprintf(counter, sizeof counter, "%zu/%zu  %.1f/s  ETA %s", done, total_, rate,
                rate > 0.0 ? formatDuration(static_cast<double>(total_ - std::min(done, total_)) / rate).c_str() : "?");
  draw(static_cast<double>(done) / static_cast<double>(total_), counter);
}

void ProgressBar::fraction(std::string_view stage, double fraction) {
  if (!enabled_) return;
  if (stage != label_) {
    label_ = stage;
    drawn_ = false;  // a new stage draws at once
  }
  fraction = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  char counter[64];
  std::snprintf(counter, sizeof counter, "%3.0f%%  ETA %s", 100.0 * fraction,
                fraction > 0.0 ? formatDuration(elapsed * (1.0 - fraction) / fraction).c_str() : "?");
  draw(fraction, counter);
}

void ProgressBar::draw(double fraction, const std::string& counter) {
  const Clock::time_point now = Clock::now();
  if (drawn_ && fraction < 1.0 && now - last_draw_ < kRedrawInterval) return;
  last_draw_ = now;
  drawn_ = true;
  const int filled = static_cast<int>(std::lround(std::clamp(fraction, 0.0, 1.0) * kBarCells));
  std::string line = label_ + " [" + std::string(static_cast<std::size_t>(filled), '#') +
                     std::string(static_cast<std::size_t>(kBarCells - filled), '.') + "] " + counter;
  const std::size_t width = line.size();
  // Pad over a longer previous line so no stale characters remain.
  if (width < last_width_) line += std::string(last_width_ - width, ' ');
  last_width_ = width;
  out_ << '\r' << line << std::flush;
}

void ProgressBar::finish() {
  if (!enabled_ || last_width_ == 0) return;
  out_ << '\r' << std::string(last_width_, ' ') << '\r' << std::flush;
  last_width_ = 0;
}

}  // namespace odeskin

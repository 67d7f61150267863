#include "tools/cli/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace deepnav::cli {

ProgressLine::ProgressLine(std::string label, double total_signal_s)
    : label_(std::move(label)),
      total_s_(total_signal_s),
      enabled_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

ProgressLine::~ProgressLine() { finish(); }

void ProgressLine::update(double fraction) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < std::chrono::milliseconds(250) && fraction < 1.0) return;
  last_ = now;
  drawn_ = true;
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double done_s = fraction * total_s_;
  const double speed = wall > 0.0 ? done_s / wall : 0.0;
  const double eta = speed > 0.0 ? (total_s_ - done_s) / speed : 0.0;
  draw(fmt::format("\r{}: {:5.1f}%  {:.1f} of {:.1f} s  {:.1f}x real time  eta {:.0f} s   ", label_, 100.0 * fraction,
                   done_s, total_s_, speed, eta));
}

void ProgressLine::draw(const std::string& text) {
  // The line is cosmetic: a terminal gone (a hangup) ends the drawing, never the run.
  if (std::fputs(text.c_str(), stderr) < 0 || std::fflush(stderr) != 0) enabled_ = false;
}

void ProgressLine::finish() {
  if (enabled_ && drawn_) {
    draw(fmt::format("\r{:80}\r", ""));
    drawn_ = false;
  }
}

}  // namespace deepnav::cli

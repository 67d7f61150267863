#pragma once
// A one-line progress display for long runs: shown on stderr only when stderr is a
// terminal, so logs and pipes stay quiet.
#include <chrono>
#include <string>

namespace deepnav::cli {

class ProgressLine {
 public:
  /// `label` prefixes the line; `total_signal_s` is the signal length the run covers.
  ProgressLine(std::string label, double total_signal_s);
  ~ProgressLine();
  /// Redraws at most a few times per second.
  void update(double fraction);
  /// Clears the line.
  void finish();

 private:
  void draw(const std::string& text);
  std::string label_;
  double total_s_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace deepnav::cli

#pragma once
// A one-line progress indicator on stderr for long runs. Silent unless stderr is a terminal and the user did
// not pass --no-progress, so logs and pipes stay clean.
#include <chrono>
#include <string>

namespace ccdlab {

class Progress {
 public:
  /// Shows nothing unless `enabled` (no --no-progress) and stderr is a terminal: logs and pipes get no
  /// carriage returns or clear-line codes.
  Progress(std::string label, long total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void update(long done);
  /// Whether progress goes to stderr by default (stderr is a terminal).
  static bool stderr_is_terminal();

 private:
  std::string label_;
  long total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace ccdlab

#pragma once
// A long step's progress line on stderr for the CLI (the pipeline's ProgressReport, step_watch.hpp): shown only
// where stderr is a terminal and the user did not pass --no-progress, cleared when the guard goes.
#include <atomic>
#include <cstdio>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/util/progress.hpp"

namespace ccdlab::cli {

class StepProgressLine {
 public:
  StepProgressLine(CcdPipeline& pipeline, bool enabled) {
    if (!enabled || !Progress::stderr_is_terminal()) return;
    pipeline.set_progress([this](const StepProgress& p) {
      shown_.store(true, std::memory_order_relaxed);
      if (p.pairs_expected > 0)
        std::fprintf(stderr, "\r\033[Kstep: %llu of ~%.3g candidate pairs tested (%.0f%%), %.0f s",
                     static_cast<unsigned long long>(p.pairs_done), p.pairs_expected,
                     100.0 * double(p.pairs_done) / p.pairs_expected, p.seconds);
      else
        std::fprintf(stderr, "\r\033[Kstep: %llu candidate pairs tested, %.0f s",
                     static_cast<unsigned long long>(p.pairs_done), p.seconds);
      std::fflush(stderr);
    });
  }
  /// After each step: clears the line if one was shown.
  void clear() {
    if (shown_.exchange(false, std::memory_order_relaxed)) std::fprintf(stderr, "\r\033[K");
  }
  ~StepProgressLine() { clear(); }
  StepProgressLine(const StepProgressLine&) = delete;
  StepProgressLine& operator=(const StepProgressLine&) = delete;

 private:
  std::atomic<bool> shown_{false};
};

}  // namespace ccdlab::cli

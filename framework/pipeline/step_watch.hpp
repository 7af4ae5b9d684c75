#pragma once
// A step's clock, read by the narrow phase's workers between chunks: against the step's time limit (time_limit:
// past it, the workers take no more chunks and the pipeline throws once they are done), and for a progress
// report — candidate pairs tested of those expected — that an entry point may show while a long step runs.
// Chunks are ~512 candidates (tens of microseconds), so a limit is kept to within a chunk per thread, and the
// pipeline never stops a thread inside a chunk: the scratch, contacts and counters stay consistent.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>

namespace ccdlab {

/// Where a step is: seconds since it began, candidate pairs tested, and how many it is expected to test (the
/// work estimate in a first step, the last step's count after; 0 when unknown).
struct StepProgress {
  double seconds = 0;
  std::uint64_t pairs_done = 0;
  double pairs_expected = 0;
};

/// Called from a worker thread, one call at a time, at most every kReportEvery once a step has run kReportAfter.
using ProgressReport = std::function<void(const StepProgress&)>;

class StepWatch {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kReportAfter{2000}, kReportEvery{500};

  /// A step begins: `limit_s` seconds (0 = no limit), `expected` candidate pairs, `report` (null: none; must outlive
  /// the step), its first call after `report_after`.
  void start(double limit_s, double expected, const ProgressReport* report,
             std::chrono::milliseconds report_after = kReportAfter);
  /// A worker tested `pairs` candidate pairs: counted, and reported when due. Call between chunks.
  void advance(std::uint64_t pairs);
  /// Whether the step has run past its limit (checked by advance and by this call).
  [[nodiscard]] bool expired();
  [[nodiscard]] double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  [[nodiscard]] std::uint64_t pairs_done() const { return done_.load(std::memory_order_relaxed); }
  [[nodiscard]] double pairs_expected() const { return expected_; }

 private:
  Clock::time_point start_{}, deadline_{};
  bool limited_ = false;
  double expected_ = 0;
  const ProgressReport* report_ = nullptr;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<bool> expired_{false};
  std::atomic<std::int64_t> next_report_{0};  ///< Clock ticks of the next report; a thread claims it by exchange
};

}  // namespace ccdlab

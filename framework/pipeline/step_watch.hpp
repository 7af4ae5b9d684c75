#pragma once
// A step's clock and contact count, read by the narrow phase's workers between chunks: against the step's time
// limit (time_limit) and against the room memory_limit leaves for its contacts — past either, the workers take no
// more chunks and the pipeline throws once they are done — and for a progress report (candidate pairs tested of
// those expected) that an entry point may show while a long step runs. The candidates stream under memory_limit
// (memory_budget.hpp); the contacts are the step's answer and cannot: a step whose contacts would not fit is
// stopped while it still fits, instead of growing until the machine kills it. Chunks are ~512 candidates (tens
// of microseconds), so a limit is kept to within a chunk per thread, and the pipeline never stops a thread inside
// a chunk: the scratch, contacts and counters stay consistent.
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

  /// Bytes a contact holds until the step's end: 56 in its thread's list, 56 in the step's sorted list and two
  /// 16-byte sort keys (sort_contacts_into) — 144, with room for the lists' growth.
  static constexpr std::uint64_t kBytesPerContact = 200;

  /// A step begins: `limit_s` seconds (0 = no limit), `expected` candidate pairs, `report` (null: none; must
  /// outlive the step), its first call after `report_after`. No room limit until set_max_contacts.
  void start(double limit_s, double expected, const ProgressReport* report,
             std::chrono::milliseconds report_after = kReportAfter);
  /// A worker tested `pairs` candidate pairs and found `contacts`: counted, and reported when due. Call between
  /// chunks.
  void advance(std::uint64_t pairs, std::uint64_t contacts);
  /// The contacts the step may hold (0 = no limit), set once its memory plan is known, before its workers start.
  void set_max_contacts(std::uint64_t n) { max_contacts_ = n; }
  /// Whether the step has run past its time limit (checked by advance and by this call).
  [[nodiscard]] bool expired();
  /// Whether its contacts have passed max_contacts.
  [[nodiscard]] bool out_of_room() const { return out_of_room_.load(std::memory_order_relaxed); }
  /// Whether the workers are to stop: expired or out of room.
  [[nodiscard]] bool stopped() { return out_of_room() || expired(); }
  [[nodiscard]] double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  [[nodiscard]] std::uint64_t pairs_done() const { return done_.load(std::memory_order_relaxed); }
  [[nodiscard]] double pairs_expected() const { return expected_; }
  [[nodiscard]] std::uint64_t contacts() const { return contacts_.load(std::memory_order_relaxed); }
  [[nodiscard]] std::uint64_t max_contacts() const { return max_contacts_; }

 private:
  Clock::time_point start_{}, deadline_{};
  bool limited_ = false;
  double expected_ = 0;
  const ProgressReport* report_ = nullptr;
  std::uint64_t max_contacts_ = 0;
  std::atomic<std::uint64_t> done_{0}, contacts_{0};
  std::atomic<bool> expired_{false}, out_of_room_{false};
  std::atomic<std::int64_t> next_report_{0};  ///< Clock ticks of the next report; a thread claims it by exchange
};

}  // namespace ccdlab

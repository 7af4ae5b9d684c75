#include "framework/pipeline/step_watch.hpp"

namespace ccdlab {

void StepWatch::start(double limit_s, double expected, const ProgressReport* report, std::chrono::milliseconds report_after) {
  start_ = Clock::now();
  limited_ = limit_s > 0;
  if (limited_) deadline_ = start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit_s));
  expected_ = expected;
  max_contacts_ = 0;
  contacts_.store(0, std::memory_order_relaxed);
  out_of_room_.store(false, std::memory_order_relaxed);
  report_ = report && *report ? report : nullptr;
  done_.store(0, std::memory_order_relaxed);
  expired_.store(false, std::memory_order_relaxed);
  next_report_.store((start_ + report_after).time_since_epoch().count(), std::memory_order_relaxed);
}

bool StepWatch::expired() {
  if (expired_.load(std::memory_order_relaxed)) return true;
  if (!limited_ || Clock::now() < deadline_) return false;
  expired_.store(true, std::memory_order_relaxed);
  return true;
}

void StepWatch::advance(std::uint64_t pairs, std::uint64_t contacts) {
  const std::uint64_t done = done_.fetch_add(pairs, std::memory_order_relaxed) + pairs;
  const std::uint64_t found = contacts_.fetch_add(contacts, std::memory_order_relaxed) + contacts;
  if (max_contacts_ > 0 && found > max_contacts_) out_of_room_.store(true, std::memory_order_relaxed);
  (void)expired();
  if (!report_) return;
  const Clock::time_point now = Clock::now();
  std::int64_t due = next_report_.load(std::memory_order_relaxed);
  if (now.time_since_epoch().count() < due) return;
  // One thread wins the report; the others see the next due time and go on.
  if (!next_report_.compare_exchange_strong(due, (now + kReportEvery).time_since_epoch().count(), std::memory_order_relaxed))
    return;
  (*report_)(StepProgress{std::chrono::duration<double>(now - start_).count(), done, expected_});
}

}  // namespace ccdlab

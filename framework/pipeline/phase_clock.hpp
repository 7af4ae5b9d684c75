#pragma once
// One clock for the phases of a step: a phase's wall time goes into its StepTimings field and its task costs
// (PhaseTrace, what the schedule simulator replays) into the step's traces, from one reading, so the two
// never disagree on what a phase is.
#include <chrono>
#include <utility>

#include "framework/pipeline/step_result.hpp"

namespace ccdlab {

class PhaseClock {
 public:
  using Clock = std::chrono::steady_clock;
  explicit PhaseClock(StepResult& result) : result_(result) {}

  /// Runs `body(trace)` as the phase `name`: a parallel phase whose tasks `body` records in `trace`. Adds its wall
  /// ms to `*timing` (when given) and keeps its trace; returns its ms.
  template <class Body>
  double parallel(const char* name, double* timing, Body&& body) {
    PhaseTrace trace{name, Distribution::dynamic, 0, {}, {}};
    const auto t = Clock::now();
    std::forward<Body>(body)(trace);
    return keep(std::move(trace), timing, t);
  }
  /// Runs `body()` as the serial phase `name` (its whole time is serial_ms).
  template <class Body>
  double serial(const char* name, double* timing, Body&& body) {
    PhaseTrace trace{name, Distribution::dynamic, 0, {}, {}};
    const auto t = Clock::now();
    std::forward<Body>(body)();
    trace.serial_ms = ms_between(t, Clock::now());
    return keep(std::move(trace), timing, t);
  }

 private:
  double keep(PhaseTrace&& trace, double* timing, Clock::time_point start) {
    const double ms = ms_between(start, Clock::now());
    if (timing) *timing += ms;
    result_.traces.push_back(std::move(trace));
    return ms;
  }

  StepResult& result_;
};

}  // namespace ccdlab

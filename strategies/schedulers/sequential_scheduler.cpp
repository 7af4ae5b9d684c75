#include "strategies/schedulers/sequential_scheduler.hpp"


namespace ccdlab {

void SequentialScheduler::collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) {
  if (pass.side_a.bvh->nodes.empty() || pass.side_b.bvh->nodes.empty()) return;
  with_bvtt_view(pass, [&](const auto& view) {
    BvttStack stack;
    const auto t0 = std::chrono::steady_clock::now();
    traverse_bvtt(view, pass.root, stack, out.pairs.part(0), out.bv_tests);
    // One task on one thread: all of it is serial.
    const double ms = ms_between(t0, std::chrono::steady_clock::now());
    out.stats.serial_ms += ms;
    traces.push_back(PhaseTrace{"traverse", Distribution::dynamic, ms, {}, {}});
  });
}

}  // namespace ccdlab

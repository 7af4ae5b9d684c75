#include "strategies/schedulers/sequential_scheduler.hpp"

#include "framework/traversal/bvtt.hpp"

namespace ccdlab {

void SequentialScheduler::collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) {
  if (pass.bvh_a->nodes.empty() || pass.bvh_b->nodes.empty()) return;
  std::visit(
      [&](const auto& bvs_a) {
        using BV = typename std::decay_t<decltype(bvs_a)>::value_type;
        const auto& bvs_b = std::get<std::vector<BV>>(*pass.bvs_b);
        BvttView<BV> view{pass.bvh_a, &bvs_a, pass.bvh_b, &bvs_b, pass.mesh, pass.self};
        std::vector<BvttNode> stack;
        const auto t0 = std::chrono::steady_clock::now();
        traverse_bvtt(view, BvttNode{0, 0}, stack, out);
        // One task on one thread: all of it is serial.
        const double ms = ms_between(t0, std::chrono::steady_clock::now());
        out.stats.serial_ms += ms;
        traces.push_back(PhaseTrace{"traverse", Distribution::dynamic, ms, {}, {}});
      },
      *pass.bvs_a);
}

}  // namespace ccdlab

#include "strategies/schedulers/front_scheduler.hpp"

#include <chrono>

namespace ccdlab {
namespace {

/// A run of consecutive front pieces (piece index, node range) processed as one task.
struct Segment {
  std::size_t piece, begin, end;
};

}  // namespace

void FrontScheduler::collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) {
  if (pass.bvh_a->nodes.empty() || pass.bvh_b->nodes.empty()) return;
  using Clock = std::chrono::steady_clock;
  PassFront& front = fronts_[pass.id];
  PhaseTrace trace{"traverse", Distribution::dynamic, 0, {}, {}};
  const auto t_serial = Clock::now();
  const bool grown = params_.rebuild_growth > 0 && double(front.size) > params_.rebuild_growth * double(front.size_after_rebuild);
  const bool due = params_.rebuild_every > 0 && front.steps_since_rebuild >= params_.rebuild_every;
  // Adaptive restructuring changed which leaves a node covers: the front must restart (its rebuild policy).
  const std::uint64_t version = pass.bvh_a->version + (pass.self ? 0 : pass.bvh_b->version);
  if (front.pieces.empty() || grown || due || version != front.bvh_version) {
    front.bvh_version = version;
    front.pieces.assign(1, initial_front(*pass.bvh_a, *pass.bvh_b, pass.self, pass.root));
    front.steps_since_rebuild = 0;
    front.size_after_rebuild = 0;
    ++out.stats.rebuilds;
  }
  ++front.steps_since_rebuild;

  // Tasks: consecutive pieces cut into runs of at most `chunk` nodes.
  const std::size_t chunk = std::size_t(params_.chunk);
  std::vector<std::vector<Segment>> tasks;
  std::size_t filled = chunk;
  for (std::size_t p = 0; p < front.pieces.size(); ++p)
    for (std::size_t b = 0; b < front.pieces[p].size();) {
      if (filled == chunk) tasks.emplace_back(), filled = 0;
      const std::size_t e = std::min(front.pieces[p].size(), b + (chunk - filled));
      tasks.back().push_back({p, b, e});
      filled += e - b;
      b = e;
    }
  const int threads = pass.threads;
  std::vector<PerThread<std::vector<FrontNode>>> next(tasks.size());  // padded: neighbours written concurrently
  struct Local {
    std::vector<BvttNode> stack;
    FrontCounters counters;
  };
  std::vector<PerThread<Local>> local(threads);
  out.pairs.use_parts(threads);
  trace.serial_ms += ms_between(t_serial, Clock::now());

  with_bvtt_view(pass, [&](const auto& view) {
    parallel_chunks(tasks.size(), 1, threads, trace, [&](std::size_t t, std::size_t, int tid) {
      std::vector<FrontNode>& piece = next[t].value;
      piece.reserve(chunk + chunk / 4);
      Local& l = local[tid].value;
      for (const Segment& s : tasks[t]) {
        const FrontNode* nodes = front.pieces[s.piece].data();
        process_front(view, nodes + s.begin, nodes + s.end, params_.prune, piece, out.pairs.part(tid), l.stack,
                      l.counters);
      }
      out.hand_over(tid);
    });
  });

  const auto t_merge = Clock::now();
  front.pieces.resize(next.size());
  front.size = 0;
  for (std::size_t t = 0; t < next.size(); ++t) {
    front.pieces[t] = std::move(next[t].value);
    front.size += front.pieces[t].size();
  }
  if (front.size_after_rebuild == 0) front.size_after_rebuild = front.size;
  for (int t = 0; t < threads; ++t) {
    const Local& l = local[t].value;
    out.bv_tests += l.counters.bv_tests;
    out.stats.front_visited += l.counters.visited;
    out.stats.sprouted += l.counters.sprouted;
    out.stats.pruned += l.counters.pruned;
  }
  out.stats.tasks += tasks.size();
  out.stats.front_nodes += front.size;
  out.stats.front_bytes += front.size * sizeof(FrontNode) + front.pieces.size() * sizeof(std::vector<FrontNode>);
  trace.serial_ms += ms_between(t_merge, Clock::now());
  out.stats.serial_ms += trace.serial_ms;
  traces.push_back(std::move(trace));
}

void FrontScheduler::release(int pass_id) { fronts_.erase(pass_id); }

std::vector<FrontNode> FrontScheduler::front(int pass_id) const {
  std::vector<FrontNode> all;
  auto it = fronts_.find(pass_id);
  if (it != fronts_.end())
    for (const auto& piece : it->second.pieces) all.insert(all.end(), piece.begin(), piece.end());
  return all;
}

}  // namespace ccdlab

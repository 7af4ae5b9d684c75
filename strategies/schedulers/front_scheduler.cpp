#include "strategies/schedulers/front_scheduler.hpp"

#include <chrono>

namespace ccdlab {

void FrontScheduler::collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) {
  if (pass.bvh_a->nodes.empty() || pass.bvh_b->nodes.empty()) return;
  using Clock = std::chrono::steady_clock;
  PassFront& front = fronts_[pass.id];
  PhaseTrace trace{"traverse", Distribution::dynamic, 0, {}, {}};
  const auto t_serial = Clock::now();
  const bool grown = params_.rebuild_growth > 0 && front.nodes.size() > params_.rebuild_growth * front.size_after_rebuild;
  const bool due = params_.rebuild_every > 0 && front.steps_since_rebuild >= params_.rebuild_every;
  if (front.nodes.empty() || grown || due) {
    front.nodes = initial_front(*pass.bvh_a, *pass.bvh_b, pass.self);
    front.steps_since_rebuild = 0;
    front.size_after_rebuild = 0;
    ++out.stats.rebuilds;
  }
  ++front.steps_since_rebuild;
  const std::size_t n = front.nodes.size();
  const std::size_t chunk = std::size_t(params_.chunk);
  const std::size_t chunks = (n + chunk - 1) / chunk;
  const int threads = pass.threads;
  std::vector<PerThread<std::vector<FrontNode>>> pieces(chunks);  // padded: neighbours are written concurrently
  struct Local {
    std::vector<FacePair> pairs;
    std::vector<BvttNode> stack;
    FrontCounters counters;
  };
  std::vector<PerThread<Local>> local(threads);
  trace.serial_ms += ms_between(t_serial, Clock::now());

  with_bvtt_view(pass, [&](const auto& view) {
    parallel_chunks(n, chunk, threads, trace, [&](std::size_t b, std::size_t e, int tid) {
      std::vector<FrontNode>& piece = pieces[b / chunk].value;
      piece.reserve(e - b + 16);
      Local& l = local[tid].value;
      process_front(view, front.nodes.data() + b, front.nodes.data() + e, params_.prune, piece, l.pairs, l.stack,
                    l.counters);
    });
  });

  // Concatenate the pieces in chunk order (offsets serial, copies parallel) and merge thread-local results.
  const auto t_merge = Clock::now();
  std::vector<std::size_t> offset(chunks + 1, 0);
  for (std::size_t c = 0; c < chunks; ++c) offset[c + 1] = offset[c] + pieces[c].value.size();
  front.nodes.resize(offset[chunks]);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::ptrdiff_t c = 0; c < std::ptrdiff_t(chunks); ++c)
    std::copy(pieces[c].value.begin(), pieces[c].value.end(), front.nodes.begin() + std::ptrdiff_t(offset[c]));
  if (front.size_after_rebuild == 0) front.size_after_rebuild = front.nodes.size();
  for (int t = 0; t < threads; ++t) {
    const Local& l = local[t].value;
    out.pairs.insert(out.pairs.end(), l.pairs.begin(), l.pairs.end());
    out.bv_tests += l.counters.bv_tests;
    out.stats.front_visited += l.counters.visited;
    out.stats.sprouted += l.counters.sprouted;
    out.stats.pruned += l.counters.pruned;
  }
  out.stats.tasks += chunks;
  out.stats.front_nodes += front.nodes.size();
  out.stats.front_bytes += front.nodes.size() * sizeof(FrontNode);
  const double merge_ms = ms_between(t_merge, Clock::now());
  trace.serial_ms += merge_ms;
  out.stats.serial_ms += trace.serial_ms;
  traces.push_back(std::move(trace));
}

const std::vector<FrontNode>& FrontScheduler::front(int pass_id) const {
  static const std::vector<FrontNode> none;
  auto it = fronts_.find(pass_id);
  return it == fronts_.end() ? none : it->second.nodes;
}

}  // namespace ccdlab

#include "strategies/schedulers/front_scheduler.hpp"

#include <bit>
#include <chrono>

namespace ccdlab {
namespace {

using Clock = std::chrono::steady_clock;

/// A run of consecutive front pieces (piece index, entry range) processed as one task.
struct Segment {
  std::size_t piece, begin, end;
};

/// Node pairs on the cut held by a piece of the front.
std::size_t cut_nodes(const std::vector<FrontNode>& piece) { return piece.size(); }
std::size_t cut_nodes(const WideFrontPiece& piece) {
  std::size_t n = 0;
  for (const WideFrontGroup& g : piece) n += std::size_t(std::popcount(unsigned(g.cut)));
  return n;
}

/// One thread's scratch space and counts.
struct FrontLocal {
  BvttStack stack;
  FrontCounters counters;
};

}  // namespace

template <class Piece, class Process>
void FrontScheduler::run(const TraversalPass& pass, PassFront& front, std::vector<Piece>& pieces,
                         std::vector<Piece>& spare, std::size_t chunk, TraversalOutput& out, PhaseTrace& trace,
                         Process&& process) {
  using Entry = typename Piece::value_type;
  const auto t_serial = Clock::now();
  // Tasks: consecutive pieces cut into runs of at most `chunk` entries.
  std::vector<std::vector<Segment>> tasks;
  std::size_t filled = chunk;
  for (std::size_t p = 0; p < pieces.size(); ++p)
    for (std::size_t b = 0; b < pieces[p].size();) {
      if (filled == chunk) tasks.emplace_back(), filled = 0;
      const std::size_t e = std::min(pieces[p].size(), b + (chunk - filled));
      tasks.back().push_back({p, b, e});
      filled += e - b;
      b = e;
    }
  const int threads = pass.threads;
  std::vector<PerThread<Piece>> next(tasks.size());  // padded: neighbours written concurrently
  for (std::size_t t = 0; t < std::min(tasks.size(), spare.size()); ++t) {
    next[t].value = std::move(spare[t]);
    next[t].value.clear();
  }
  std::vector<std::size_t> nodes(tasks.size());
  std::vector<PerThread<FrontLocal>> local(threads);
  out.pairs.use_parts(threads);
  trace.serial_ms += ms_between(t_serial, Clock::now());

  parallel_chunks(tasks.size(), 1, threads, trace, [&](std::size_t t, std::size_t, int tid) {
    Piece& piece = next[t].value;
    piece.reserve(chunk + chunk / 4);
    for (const Segment& s : tasks[t]) {
      const Entry* entries = pieces[s.piece].data();
      process(entries + s.begin, entries + s.end, piece, out.pairs.part(tid), local[tid].value);
    }
    nodes[t] = cut_nodes(piece);
    out.hand_over(tid);
  });

  const auto t_merge = Clock::now();
  spare = std::move(pieces);
  pieces.resize(next.size());
  front.size = 0;
  for (std::size_t t = 0; t < next.size(); ++t) {
    pieces[t] = std::move(next[t].value);
    front.size += nodes[t];
  }
  if (front.size_after_rebuild == 0) front.size_after_rebuild = front.size;
  for (int t = 0; t < threads; ++t) {
    const FrontCounters& c = local[t].value.counters;
    out.bv_tests += c.bv_tests;
    out.stats.front_visited += c.visited;
    out.stats.sprouted += c.sprouted;
    out.stats.pruned += c.pruned;
  }
  std::size_t entries = 0;
  for (const auto& piece : pieces) entries += piece.size();
  out.stats.tasks += tasks.size();
  out.stats.front_nodes += front.size;
  out.stats.front_bytes += entries * sizeof(Entry) + pieces.size() * sizeof(Piece);
  trace.serial_ms += ms_between(t_merge, Clock::now());
}

void FrontScheduler::collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) {
  if (pass.bvh_a->nodes.empty() || pass.bvh_b->nodes.empty()) return;
  PassFront& front = fronts_[pass.id];
  PhaseTrace trace{"traverse", Distribution::dynamic, 0, {}, {}};
  with_bvtt_view(pass, [&](const auto& view) {
    const auto t_serial = Clock::now();
#if defined(CCDLAB_HAS_AVX512_WALK)
    const bool wide = view.wide() && view.lane_pairs;
#else
    const bool wide = false;
#endif
    const bool grown = params_.rebuild_growth > 0 && double(front.size) > params_.rebuild_growth * double(front.size_after_rebuild);
    const bool due = params_.rebuild_every > 0 && front.steps_since_rebuild >= params_.rebuild_every;
    // Adaptive restructuring changed which leaves a node covers: the front must restart (its rebuild policy).
    const std::uint64_t version = pass.bvh_a->version + (pass.self ? 0 : pass.bvh_b->version);
    const bool none = wide ? front.wide_pieces.empty() : front.pieces.empty();
    const bool rebuild = none || grown || due || version != front.bvh_version;
    if (rebuild) {
      front.bvh_version = version;
      front.pieces.clear();
      front.wide_pieces.clear();
      front.spare.clear();
      front.wide_spare.clear();
      if (wide) {
        front.layout_a = view.wide_layout_a, front.layout_b = view.wide_layout_b;
        front.wide_pieces.assign(1, wide_front_seeds(*pass.bvh_a, *view.wide_layout_a, *pass.bvh_b,
                                                     *view.wide_layout_b, pass.self, pass.root));
      } else {
        front.pieces.assign(1, initial_front(*pass.bvh_a, *pass.bvh_b, pass.self, pass.root));
      }
      front.steps_since_rebuild = 0;
      front.size_after_rebuild = 0;
      ++out.stats.rebuilds;
    }
    ++front.steps_since_rebuild;
    trace.serial_ms += ms_between(t_serial, Clock::now());
    const std::size_t chunk = std::size_t(params_.chunk);
#if defined(CCDLAB_HAS_AVX512_WALK)
    if (wide) {
      // Seeds are split for balance: not merged back in the step that made them.
      const bool prune = params_.prune && !rebuild;
      run(pass, front, front.wide_pieces, front.wide_spare, chunk, out, trace,
          [&](const WideFrontGroup* b, const WideFrontGroup* e, WideFrontPiece& next, FacePairs& pairs,
              FrontLocal& l) { process_wide_front(view, b, e, prune, next, pairs, l.stack.lane_pairs, l.counters); });
      return;
    }
#endif
    run(pass, front, front.pieces, front.spare, chunk, out, trace,
        [&](const FrontNode* b, const FrontNode* e, std::vector<FrontNode>& next, FacePairs& pairs, FrontLocal& l) {
          process_front(view, b, e, params_.prune, next, pairs, l.stack.binary, l.counters);
        });
  });
  out.stats.serial_ms += trace.serial_ms;
  traces.push_back(std::move(trace));
}

void FrontScheduler::release(int pass_id) { fronts_.erase(pass_id); }

std::vector<FrontNode> FrontScheduler::front(int pass_id) const {
  std::vector<FrontNode> all;
  auto it = fronts_.find(pass_id);
  if (it == fronts_.end()) return all;
  for (const auto& piece : it->second.pieces) all.insert(all.end(), piece.begin(), piece.end());
  for (const auto& piece : it->second.wide_pieces)
    append_wide_front_nodes(*it->second.layout_a, *it->second.layout_b, piece, all);
  return all;
}

}  // namespace ccdlab

#include "strategies/schedulers/front_scheduler.hpp"

#include <algorithm>
#include <bit>
#include <chrono>

#include "framework/util/memory.hpp"

namespace ccdlab {
namespace {

using Clock = std::chrono::steady_clock;

/// A rebuild's front, for the room its buffers get: entries per node pair seed and per leaf, above what real
/// steps reach (docs/results-scheduling.md); a self seed grows into far more.
constexpr std::size_t kSeedGrowth = 8;
constexpr std::size_t kRebuildEntriesPerLeaf = 8;
/// Tasks of a rebuild step (see collect).
constexpr std::size_t kRebuildTasks = 256;

/// A run of consecutive entries of one front piece; a task processes a few of them.
struct Segment {
  std::size_t piece, begin, end;
};

/// Node pairs on the cut held by entries [begin, end).
std::size_t cut_nodes(const FrontNode* begin, const FrontNode* end) { return std::size_t(end - begin); }
std::size_t cut_nodes(const WideFrontGroup* begin, const WideFrontGroup* end) {
  std::size_t n = 0;
  for (const WideFrontGroup* g = begin; g != end; ++g) n += std::size_t(std::popcount(unsigned(g->cut)));
  return n;
}

/// One thread's scratch space and counts.
struct FrontLocal {
  BvttStack stack;
  FrontCounters counters;
};

/// Empties `buffers` and makes `n` of them, each with room for `entries` entries at least. A buffer that must
/// grow gets half as much again, and kLargeAllocation bytes at least (see Store), so that a front growing by a
/// little every step does not move to new memory every step; room that is not written costs no memory.
template <class Buffer>
void prepare_buffers(std::vector<PerThread<Buffer>>& buffers, std::size_t n, std::size_t entries) {
  if (buffers.size() < n) buffers.resize(n);
  for (auto& b : buffers) {
    b.value.clear();
    if (b.value.capacity() < entries)
      b.value.reserve(std::max(entries + entries / 2, kLargeAllocation / sizeof(typename Buffer::value_type)));
  }
}

}  // namespace

template <class Entry>
template <class Seeds>
void FrontScheduler::Store<Entry>::seed(const Seeds& seeds) {
  prepare_buffers(buffers, 1, seeds.size());
  buffers[0].value.assign(seeds.begin(), seeds.end());
  pieces.assign(1, Piece{0, 0, seeds.size()});
}

template <class Entry, class Process>
void FrontScheduler::run(const TraversalPass& pass, PassFront& front, Store<Entry>& store, bool rebuild,
                         std::size_t chunk, TraversalOutput& out, PhaseTrace& trace, Process&& process) {
  const auto t_serial = Clock::now();
  // Tasks: consecutive pieces cut into runs of at most `chunk` entries.
  std::vector<std::vector<Segment>> tasks;
  std::size_t filled = chunk, entries_in = 0;
  for (std::size_t p = 0; p < store.pieces.size(); ++p) {
    const std::size_t size = store.pieces[p].end - store.pieces[p].begin;
    entries_in += size;
    for (std::size_t b = 0; b < size;) {
      if (filled == chunk) tasks.emplace_back(), filled = 0;
      const std::size_t e = std::min(size, b + (chunk - filled));
      tasks.back().push_back({p, b, e});
      filled += e - b;
      b = e;
    }
  }
  const int threads = pass.threads;
  // Room in every buffer for the whole next front (any thread may write most of it), so that no buffer grows by
  // copying into fresh memory: about this front's size, or, from seeds, the larger of kSeedGrowth times theirs
  // and kRebuildEntriesPerLeaf per leaf.
  const std::size_t leaves = std::size_t(pass.side_a.bvh->num_leaves() + (pass.self ? 0 : pass.side_b.bvh->num_leaves()));
  prepare_buffers(store.spare, std::size_t(threads),
                  rebuild ? std::max(kSeedGrowth * entries_in, kRebuildEntriesPerLeaf * leaves) : entries_in + entries_in / 4);
  std::vector<typename Store<Entry>::Piece> made(tasks.size());
  std::vector<std::size_t> nodes(tasks.size());
  std::vector<PerThread<FrontLocal>> local(threads);
  out.pairs.use_parts(threads);
  trace.serial_ms += ms_between(t_serial, Clock::now());

  parallel_chunks(tasks.size(), 1, threads, trace, [&](std::size_t t, std::size_t, int tid) {
    auto& buffer = store.spare[std::size_t(tid)].value;
    const std::size_t begin = buffer.size();
    for (const Segment& s : tasks[t]) {
      const Entry* entries = store.data(store.pieces[s.piece]);
      process(entries + s.begin, entries + s.end, buffer, begin, out.pairs.part(tid), local[tid].value);
    }
    made[t] = {std::size_t(tid), begin, buffer.size()};
    nodes[t] = cut_nodes(buffer.data() + begin, buffer.data() + buffer.size());
    out.hand_over(tid);
  });

  const auto t_merge = Clock::now();
  std::swap(store.buffers, store.spare);
  store.pieces = std::move(made);
  front.size = 0;
  std::size_t entries = 0;
  for (std::size_t t = 0; t < tasks.size(); ++t) {
    front.size += nodes[t];
    entries += store.pieces[t].end - store.pieces[t].begin;
  }
  if (front.size_after_rebuild == 0) front.size_after_rebuild = front.size;
  FrontCounters c;
  for (int t = 0; t < threads; ++t) c += local[t].value.counters;
  out.bv_tests += c.bv_tests;
  out.stats.front_visited += c.visited;
  out.stats.sprouted += c.sprouted;
  out.stats.pruned += c.pruned;
  out.stats.tasks += tasks.size();
  out.stats.front_nodes += front.size;
  out.stats.front_bytes += entries * sizeof(Entry) + store.pieces.size() * sizeof(typename Store<Entry>::Piece);
  trace.serial_ms += ms_between(t_merge, Clock::now());
}

void FrontScheduler::collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) {
  if (pass.side_a.bvh->nodes.empty() || pass.side_b.bvh->nodes.empty()) return;
  PassFront& front = fronts_[pass.id];
  PhaseTrace trace{"traverse", Distribution::dynamic, 0, {}, {}};
  with_bvtt_view(pass, [&](const auto& view) {
    const auto t_serial = Clock::now();
#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
    const bool wide = view.wide() && view.lane_pairs != LanePairWalk::none;
#else
    const bool wide = false;
#endif
    const bool grown = params_.rebuild_growth > 0 && double(front.size) > params_.rebuild_growth * double(front.size_after_rebuild);
    const bool due = params_.rebuild_every > 0 && front.steps_since_rebuild >= params_.rebuild_every;
    // Adaptive restructuring changed which leaves a node covers: the front must restart (its rebuild policy).
    const std::uint64_t version = pass.side_a.bvh->version + (pass.self ? 0 : pass.side_b.bvh->version);
    const bool none = wide ? front.wide.empty() : front.binary.empty();
    // End boxes turned on (bv.end_boxes: auto, CcdPipeline::end_boxes_pay): the front stops where the k-DOPs alone
    // stopped, far below where end boxes stop a walk, and pruning climbs one level a step, so start again from the
    // seeds (docs/appendix-wide-bvh.md has the measurement). Turned off, the front only sprouts.
    const bool ends_on = pass.test_ends && !front.test_ends;
    front.test_ends = pass.test_ends;
    const bool rebuild = none || grown || due || version != front.bvh_version || ends_on;
    if (rebuild) {
      front.bvh_version = version;
      front.binary.clear();
      front.wide.clear();
      if (wide) {
        front.layout_a = view.side_a.wide_layout, front.layout_b = view.side_b.wide_layout;
        // Self nodes as seeds unless this step skips patches (REBUILD in front/wide_front.hpp).
        front.wide.seed(wide_front_seeds(*pass.side_a.bvh, *view.side_a.wide_layout, *pass.side_b.bvh, *view.side_b.wide_layout,
                                         pass.self, pass.root, view.skip_root == nullptr));
      } else {
        front.binary.seed(initial_front(*pass.side_a.bvh, *pass.side_b.bvh, pass.self, pass.root));
      }
      front.steps_since_rebuild = 0;
      front.size_after_rebuild = 0;
      ++out.stats.rebuilds;
    }
    ++front.steps_since_rebuild;
    trace.serial_ms += ms_between(t_serial, Clock::now());
    // A rebuild's tasks: about kRebuildTasks of them, as its seeds are fewer than the front (self seeds: a few
    // hundred) and each sprouts much more.
    std::size_t chunk = std::size_t(params_.chunk);
    if (rebuild) {
      const std::size_t seeds = wide ? front.wide.pieces[0].end : front.binary.pieces[0].end;
      chunk = std::clamp<std::size_t>(seeds / kRebuildTasks, 1, chunk);
    }
#if defined(CCDLAB_HAS_LANE_PAIR_WALKS)
    if (wide) {
      // Seeds are split for balance: not merged back in the step that made them.
      const bool prune = params_.prune && !rebuild;
      run(pass, front, front.wide, rebuild, chunk, out, trace,
          [&](const WideFrontGroup* b, const WideFrontGroup* e, WideFrontPiece& next, std::size_t piece_begin,
              FacePairs& pairs, FrontLocal& l) {
            process_wide_front(view.lane_pairs, view, b, e, prune, next, piece_begin, pairs, l.stack.lane_pairs,
                               l.counters);
          });
      return;
    }
#endif
    run(pass, front, front.binary, rebuild, chunk, out, trace,
        [&](const FrontNode* b, const FrontNode* e, FrontPiece& next, std::size_t piece_begin, FacePairs& pairs,
            FrontLocal& l) {
          process_front(view, b, e, params_.prune, next, piece_begin, pairs, l.stack.binary, l.counters);
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
  const PassFront& f = it->second;
  for (const auto& piece : f.binary.pieces) all.insert(all.end(), f.binary.data(piece), f.binary.data(piece) + (piece.end - piece.begin));
  for (const auto& piece : f.wide.pieces)
    append_wide_front_nodes(*f.layout_a, *f.layout_b, f.wide.data(piece), f.wide.data(piece) + (piece.end - piece.begin), all);
  return all;
}

}  // namespace ccdlab

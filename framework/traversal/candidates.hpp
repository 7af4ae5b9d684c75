#pragma once
// What the broad phase hands to the narrow phase: candidate face pairs whose swept bounding volumes overlap.
#include <algorithm>
#include <compare>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "framework/mesh/tri_mesh.hpp"
#include "framework/util/parallel.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

struct FacePair {
  Index a;
  Index b;
  auto operator<=>(const FacePair&) const = default;
};

/// A list of candidates. Growing it leaves the new entries uninitialized (they are written right after).
using FacePairs = UninitializedVector<FacePair>;

/// The candidates of a step, in parts: one per thread that found them (part 0 also takes what a serial
/// traversal or the serial top of a split BVTT finds). The candidate list is their concatenation in part
/// order; which part a pair lands in depends on the schedule, so nothing may depend on the order (the
/// contacts are sorted at the end of the step). Why parts, and room reserved ahead (docs/appendix-narrow-phase.md,
/// "Memory touched once"):
///   - merging the threads' lists into one copies every pair into fresh pages;
///   - a list that grows by doubling copies itself and first-touches about twice its final size.
/// clear() keeps the parts' memory for the next step. The pipeline does that while a step fits the memory
/// limit with them resident (MemoryBudget::fits), and releases them otherwise, before planning the step.
class CandidateList {
 public:
  /// At least n parts; existing parts keep their pairs and memory. Not thread-safe: call it before the
  /// threads write into part(0..n-1).
  void use_parts(int n);
  [[nodiscard]] int num_parts() const { return int(parts_.size()); }
  [[nodiscard]] FacePairs& part(int i) { return parts_[std::size_t(i)].value; }
  [[nodiscard]] const FacePairs& part(int i) const { return parts_[std::size_t(i)].value; }
  /// Room for `pairs` more in each of the first n parts (created if missing), reserved as address space:
  /// pages are touched only when written. A part can receive every candidate of the step, so each gets the
  /// whole expectation; at most kMaxReservedPairs each (beyond that, the parts grow as they need).
  void reserve(int n, std::size_t pairs);
  static constexpr std::size_t kMaxReservedPairs = std::size_t(1) << 27;  // 1 GiB of address space

  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] bool empty() const { return size() == 0; }
  /// Every part emptied, memory kept for the next step.
  void clear();
  /// Every part emptied and its memory returned.
  void release();
  /// The concatenation, as one list (tests, analysis; the pipeline reads the parts in place).
  [[nodiscard]] FacePairs flatten() const;
  /// Calls f(std::span<const FacePair>) with the pairs of the concatenation in [begin, end), one call per
  /// part it overlaps.
  template <class F>
  void for_each_span(std::size_t begin, std::size_t end, F&& f) const {
    std::size_t offset = 0;
    for (const auto& p : parts_) {
      const std::size_t n = p.value.size(), lo = std::max(begin, offset), hi = std::min(end, offset + n);
      if (lo < hi) f(std::span<const FacePair>(p.value.data() + (lo - offset), hi - lo));
      offset += n;
      if (offset >= end) break;
    }
  }

 private:
  // Padded: each thread writes its own part's size and pointers. Part 0 always exists.
  std::vector<PerThread<FacePairs>> parts_ = std::vector<PerThread<FacePairs>>(1);
};

/// Work counters of a scheduler for one step (summed over passes).
struct TraversalStats {
  std::uint64_t bv_tests = 0;         ///< BV overlap tests performed
  std::uint64_t tasks = 0;            ///< parallel tasks (sub-trees, front chunks) handed out
  double serial_ms = 0;               ///< time in the scheduler's serial part (top of the BVTT, merging)
  // BVTT front (scheduler `front`)
  std::uint64_t front_nodes = 0;      ///< front size after the step
  std::uint64_t front_bytes = 0;      ///< memory of the front
  std::uint64_t front_visited = 0;    ///< front nodes processed this step
  std::uint64_t sprouted = 0;         ///< front nodes that overlapped and descended
  std::uint64_t pruned = 0;           ///< sibling pairs collapsed back into their parent
  std::uint64_t rebuilds = 0;         ///< fronts rebuilt from the root this step
  std::uint64_t cone_culled = 0;      ///< self tests skipped by normal-cone culling (topmost nodes)
  std::uint64_t contour_edges = 0;    ///< boundary edges tested by the contour test

  void add(const TraversalStats& o);
};

/// Takes the candidates that thread `tid` found, on that thread, while the traversal runs.
using CandidateConsumer = std::function<void(int tid, std::span<const FacePair> pairs)>;

struct TraversalOutput {
  CandidateList pairs;
  std::uint64_t bv_tests = 0;  ///< BV overlap tests performed (kept beside stats for the sequential kernels)
  TraversalStats stats;
  /// Optional; CcdPipeline sets it unless told to keep the candidates. A scheduler calls hand_over(tid)
  /// between two of its tasks: a part that holds hand_over_pairs or more goes to the consumer (the narrow
  /// phase, on the thread that found the pairs) and is emptied. The pairs are tested while still in cache,
  /// and the list reuses a few hundred KiB instead of holding a whole step in fresh pages (docs/appendix-narrow-phase.md,
  /// "Page faults, again"). What is left in the parts after collect() is the caller's.
  CandidateConsumer consumer;
  static constexpr std::size_t kHandOverPairs = std::size_t(1) << 14;  // 128 KiB: stays in L2
  std::size_t hand_over_pairs = kHandOverPairs;  ///< tests lower it, so that small scenes take this path

  void hand_over(int tid) {
    FacePairs& part = pairs.part(tid);
    if (!consumer || part.size() < hand_over_pairs) return;
    consumer(tid, std::span<const FacePair>(part.data(), part.size()));
    part.clear();
  }
  /// Empties the lists and counters (the consumer stays).
  void clear() {
    pairs.clear();
    bv_tests = 0;
    stats = {};
  }
};

}  // namespace ccdlab

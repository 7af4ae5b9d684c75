#pragma once
// `front`: BVTT-front decomposition (the seed paper's method). This is the policy; the front's data, rules and
// walks are one room, framework/traversal/front/ (its README gives the reading order of a step). The front of each pass is kept across steps; each step its nodes are processed in parallel,
// in fixed-size chunks handed out dynamically, so the first traversal from the root (the serial top of `phc`)
// disappears after the first step and the BV tests above the front are not repeated (the paper's λ).
// The front is stored as a list of pieces in traversal order; each task takes a run of consecutive pieces
// holding at most `chunk` entries and writes one new piece, so nothing is copied between steps and the front —
// and the work — does not depend on the thread count.
// At bv.width 4, where the CPU has the lane-pair walk, the front is one of record pairs with their cut lane pairs
// (front/wide_front.hpp), visited by the kernel every other scheduler's walk uses; elsewhere, and at bv.width 2
// (the paper's original), it is the binary front of node pairs (front/binary_front.hpp).
#include <map>

#include "framework/traversal/front/binary_front.hpp"
#include "framework/traversal/front/wide_front.hpp"
#include "framework/traversal/scheduler.hpp"
#include "framework/util/parallel.hpp"
#include "framework/util/uninitialized_vector.hpp"

namespace ccdlab {

class FrontScheduler final : public TraversalScheduler {
 public:
  struct Params {
    int chunk = 512;               ///< front entries per task: node pairs (binary), or record pairs (wide: ~7 node pairs each)
    bool prune = true;             ///< collapse non-overlapping siblings back into their parent
    double rebuild_growth = 2.0;   ///< rebuild when the front exceeds this × its size after the last rebuild (0 = never)
    int rebuild_every = 0;         ///< also rebuild every N steps (0 = never)
  };
  FrontScheduler() = default;
  explicit FrontScheduler(Params p) : params_(p) {}
  [[nodiscard]] std::string_view name() const override { return "front"; }
  void collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) override;
  void release(int pass_id) override;
  /// The current front of a pass, concatenated (empty before its first step) — for tests and reports.
  [[nodiscard]] std::vector<FrontNode> front(int pass_id) const;

 private:
  /// A front's entries, kept across steps. Each task of a step writes the piece it makes at the end of its
  /// thread's buffer, so the front is a list of pieces, in BVTT order, each a range of one buffer; the next step
  /// reads them and writes into the other set of buffers (`spare`), whose capacity it keeps. A buffer starts at
  /// kLargeAllocation bytes, so it lies in huge pages (framework/util/memory.hpp): a rebuild writes the whole
  /// front at once, and a separate allocation per piece took a fault per fresh 4 KiB page
  /// (docs/results-scheduling.md, "The front's pieces in thread buffers").
  template <class Entry>
  struct Store {
    using Buffer = UninitializedVector<Entry>;
    struct Piece {
      std::size_t buffer, begin, end;
    };
    std::vector<Piece> pieces;
    std::vector<PerThread<Buffer>> buffers;  ///< the pieces' buffers, by the thread that wrote them
    std::vector<PerThread<Buffer>> spare;    ///< emptied at the next step, which writes into them
    [[nodiscard]] bool empty() const { return pieces.empty(); }
    [[nodiscard]] const Entry* data(const Piece& p) const { return buffers[p.buffer].value.data() + p.begin; }
    /// Replaces the front by `seeds`, as one piece.
    template <class Seeds>
    void seed(const Seeds& seeds);
    void clear() { pieces.clear(); }
  };
  struct PassFront {
    Store<FrontNode> binary;     ///< the binary front
    Store<WideFrontGroup> wide;  ///< or the wide one
    const WideLayout* layout_a = nullptr;  ///< the wide front's layouts (its record ids mean nothing without them)
    const WideLayout* layout_b = nullptr;
    std::size_t size = 0;  ///< node pairs on the cut
    std::size_t size_after_rebuild = 0;
    std::uint64_t bvh_version = 0;  ///< of the BVHs it was built on: a restructured BVH invalidates the front
    bool test_ends = false;         ///< whether its last step tested end boxes (TraversalPass::test_ends)
    int steps_since_rebuild = 0;
  };
  /// One step of a front: its pieces cut into tasks of at most `chunk` entries, `process` on threads, the new
  /// pieces kept and counted.
  template <class Entry, class Process>
  void run(const TraversalPass& pass, PassFront& front, Store<Entry>& store, bool rebuild, std::size_t chunk,
           TraversalOutput& out, PhaseTrace& trace, Process&& process);
  Params params_{};
  std::map<int, PassFront> fronts_;  ///< by TraversalPass::id
};

}  // namespace ccdlab

#pragma once
// The walk over the 4-wide view for any x86-64 (SSE2): a pair node opens its larger side's record and tests its
// four lanes against the other side; the walk for CPUs without AVX2 (the lane-pair walks: bvtt_wide.hpp).
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "framework/traversal/bvtt_view.hpp"
#include "framework/traversal/wide_overlap.hpp"

namespace ccdlab {

/// A node on the wide traversal's stack, carrying what its visit needs so that it reads no binary node. A pair
/// node (known to overlap): each side's home (WideLayout::home: the lane that holds its k-DOP, record · 4 + lane),
/// wide slot (a wide node, or ~face for a leaf) and size measure. A self node (self passes only): ha == hb ==
/// the node's id (a pair node's sides are different lanes, so its homes differ).
struct WideBvttEntry {
  Index ha, hb;
  Index wa, wb;
  float sa, sb;
  [[nodiscard]] bool both_leaves() const { return (wa & wb) < 0; }  // slots ~face
  /// The descent rule (bvtt_rule::descend_a) on the entry: open a's record (true) or b's.
  [[nodiscard]] bool descends_a() const { return bvtt_rule::descend_a(wa < 0, wb < 0, sa, sb); }
};

/// The 16-bit lane-pair mask (bit 4i + j: a's lane i, b's lane j) of the rows in `lanes` (bit i: a's lane i).
constexpr unsigned lane_rows_mask(unsigned lanes) {
  return (lanes & 1u) * 0xFu | (lanes >> 1 & 1u) * 0xF0u | (lanes >> 2 & 1u) * 0xF00u | (lanes >> 3 & 1u) * 0xF000u;
}

/// Lanes of a record that hold a node (BV tests when it is opened): 2, 3 or 4, the empty ones last.
template <class BV>
int used_lanes(const WideBounds<BV>& r) {
  constexpr int W = WideLayout::kWidth;
  return W - (r.lanes.slot[W - 1] == WideLayout::kNoSlot) - (r.lanes.slot[W - 2] == WideLayout::kNoSlot);
}

/// Depth-first traversal over the 4-wide view: a pair node's larger side opens all its lanes at once and only
/// the lanes that overlap the other side are pushed (test before push). Self nodes still open into (L, L),
/// (R, R), (L, R) as in the binary BVTT, so normal-cone skips apply unchanged. The descent rule is the binary
/// one (the larger side by size_measure, never a leaf); the candidates are the same (see wide_bvh.hpp).
/// Written like the binary walk (raw pointers, candidates written in place). A pair visit reads the record it
/// opens and the other side's k-DOP from the lane that holds it, in a record opened a moment ago: reading it
/// from the binary array instead misses the cache. A hit lane whose own
/// visit would open the other side's record (the usual case: a lane is two levels smaller) is not pushed: that
/// test is made at once, while both records are in cache. Same BV tests as pushing it, in another order.
template <class BV>
void traverse_bvtt_wide(const BvttView<BV>& v, BvttNode start, std::vector<WideBvttEntry>& stack, FacePairs& pairs,
                        std::uint64_t& bv_tests_out) {
  constexpr int W = WideLayout::kWidth;
  const BvhNode* const na = v.side_a.bvh->nodes.data();
  const BV* const bva = v.side_a.bv->data();
  const BV* const bvb = v.side_b.bv->data();
  const WideSideArrays<BV> side_a(v.side_a), side_b(v.side_b);  // end boxes on: both sides' ends, else neither
  const bool self = v.self;
  std::uint64_t bv_tests = 0;
  const auto pair_entry = [&](Index a, Index b) {
    return WideBvttEntry{side_a.home[a], side_b.home[b], side_a.slot[a], side_b.slot[b], bva[a].size_measure(), bvb[b].size_measure()};
  };
  // A visit pushes at most W · W pair nodes, or 2 entries for a self node; room is checked before each visit.
  if (stack.size() < 64) stack.resize(64);
  WideBvttEntry* base = stack.data();
  WideBvttEntry* top = base;
  WideBvttEntry* room = base + stack.size() - W * W;
  std::size_t emitted = pairs.size();
  pairs.resize(std::max<std::size_t>(pairs.capacity(), emitted + 1024));
  FacePair* pout = pairs.data() + emitted;
  FacePair* pend = pairs.data() + pairs.size();
  WideBvttEntry n{start.a, start.b, -1, -1, 0, 0};
  bool visit = true;
  if (!(self && start.a == start.b)) {
    ++bv_tests;
    visit = v.nodes_overlap(start.a, start.b);
    if (visit) n = pair_entry(start.a, start.b);
  }
  const auto emit = [&](const WideBvttEntry& leaves) {  // the candidate of two overlapping leaves
    if (pout == pend) [[unlikely]] {
      emitted = std::size_t(pout - pairs.data());
      pairs.resize(2 * pairs.size());
      pout = pairs.data() + emitted;
      pend = pairs.data() + pairs.size();
    }
    pout = v.write_face_pair(pout, ~leaves.wa, ~leaves.wb);
  };
  alignas(16) float size[W];
  for (;;) {
    if (visit) {
      if (top > room) [[unlikely]] {
        const std::size_t used = std::size_t(top - base);
        stack.resize(2 * stack.size());
        base = stack.data();
        top = base + used;
        room = base + stack.size() - W * W;
      }
      if (self && n.ha == n.hb) {
        if (const BvhNode& A = na[n.ha]; v.self_opens(A, n.ha)) {
          const auto c = BvttView<BV>::self_children(A);  // (L, L) next, (R, R) stacked, (L, R) tested first
          ++bv_tests;
          if (v.nodes_overlap(c.node[2].a, c.node[2].b)) *top++ = pair_entry(c.node[2].a, c.node[2].b);
          *top++ = {c.node[1].a, c.node[1].b, -1, -1, 0, 0};
          n = {c.node[0].a, c.node[0].b, -1, -1, 0, 0};
          continue;
        }
      } else if (n.both_leaves()) {
        emit(n);
      } else {
        const bool down_a = n.descends_a();
        const auto side_of = [&](bool a_side) { return a_side ? side_a.records : side_b.records; };
        const auto ends_of = [&](bool a_side) { return a_side ? side_a.ends : side_b.ends; };
        const Index rx = down_a ? n.wa : n.wb;  // the record opened
        const WideBounds<BV>& bx = side_of(down_a)[rx];
        const Index h = down_a ? n.hb : n.ha;  // the other side's home
        unsigned hit = overlapping_lanes(bx, WideLane<BV>{side_of(!down_a) + h / W, h % W});
        if (side_a.ends) hit &= ~lanes_apart_at_both_ends(ends_of(down_a)[rx], ends_of(!down_a)[h / W], h % W);
        bv_tests += used_lanes(bx);
        if (hit) {
          lane_sizes(bx, size);
          const Index ry = down_a ? n.wb : n.wa;  // the other side's record, if it is inner
          alignas(16) float size_y[W];
          bool sized_y = false;
          const auto lane_child = [](WideBvttEntry c, bool a_side, Index record, const WideBounds<BV>& b,
                                     const float* sz, int j) {
            if (a_side) {
              c.ha = record * W + j, c.wa = b.lanes.slot[j], c.sa = sz[j];
            } else {
              c.hb = record * W + j, c.wb = b.lanes.slot[j], c.sb = sz[j];
            }
            return c;
          };
          // A pair node found to overlap: emitted if both are leaves, else pushed, its next record asked for.
          const auto settle = [&](const WideBvttEntry& c) {
            if (c.both_leaves()) {
              emit(c);
              return;
            }
            const char* r = reinterpret_cast<const char*>(c.descends_a() ? side_a.records + c.wa : side_b.records + c.wb);
            for (std::size_t line = 0; line < sizeof(WideBounds<BV>); line += 64) __builtin_prefetch(r + line);
            *top++ = c;
          };
          for (; hit; hit &= hit - 1) {
            const int j = std::countr_zero(hit);
            const WideBvttEntry c = lane_child(n, down_a, rx, bx, size, j);
            // The visit of c would open the other side's record with lane j as its query (the binary rule):
            // make that test now, while both records are in cache, instead of pushing c.
            if (c.both_leaves() || c.descends_a() == down_a) {
              settle(c);
              continue;
            }
            const WideBounds<BV>& by = side_of(!down_a)[ry];
            unsigned hit_y = overlapping_lanes(by, WideLane<BV>{&bx, j});
            if (side_a.ends) hit_y &= ~lanes_apart_at_both_ends(ends_of(!down_a)[ry], ends_of(down_a)[rx], j);
            bv_tests += used_lanes(by);
            if (hit_y && !sized_y) lane_sizes(by, size_y), sized_y = true;
            for (; hit_y; hit_y &= hit_y - 1) settle(lane_child(c, !down_a, ry, by, size_y, std::countr_zero(hit_y)));
          }
        }
      }
    }
    if (top == base) break;
    n = *--top;
    visit = true;
  }
  pairs.resize(std::size_t(pout - pairs.data()));
  bv_tests_out += bv_tests;
}

}  // namespace ccdlab

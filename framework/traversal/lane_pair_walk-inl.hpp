// The lane-pair walk's body, included by lane_pair_walk_avx512.hpp and lane_pair_walk_avx2.hpp inside its namespace
// (lane_pair_avx512, lane_pair_avx2), with CCDLAB_WALK_TARGET the set's function attribute and that namespace's
// visit_lane_pairs in scope. No include guard: one walk per inclusion.
/// Depth-first traversal over the 4-wide view (call only where lane_pair_walk() allows this instruction set). A pair
/// node opens both sides at once: an inner side's record, or, for a leaf, the record that holds it (its home)
/// restricted to that lane. One overlapping_lane_pairs gives the 16 lane pairs' answers; the pairs of two leaves
/// are written as candidates (adjacency tested in SIMD on the lanes' vertex ids, WideLayout::LaneIds::vert) and the
/// others pushed, each with one compress per 16 lanes — no branch on any answer, the branches that cost the other
/// walks most per BV test (docs/wide-bvh.md). Self nodes open into (L, L), (R, R), (L, R) as in the binary
/// BVTT, so normal-cone skips apply unchanged; (L, R) is pushed untested, since its visit tests L's lanes against
/// R's anyway (a leaf pair under L × R overlaps only if L and R do). Same candidates as the binary walk
/// (wide_bvh.hpp), in another order; a BV test is one lane pair of the restricted records.
template <class BV>
CCDLAB_WALK_TARGET void traverse_bvtt_lane_pairs(const BvttView<BV>& v, BvttNode start, LanePairStack& stack,
                                                   FacePairs& pairs, std::uint64_t& bv_tests_out) {
  constexpr int W = WideLayout::kWidth;
  const BvhNode* const na = v.side_a.bvh->nodes.data();
  const WideSideArrays<BV> side_a(v.side_a), side_b(v.side_b);
  const bool self = v.self;
  std::uint64_t bv_tests = 0;
  // A visit pushes at most 16 pair nodes, or 2 for a self node; room is checked before each visit.
  LanePairCursor cur{nullptr, nullptr, nullptr, nullptr, 0, nullptr, v.side_a.wide_ends, v.side_b.wide_ends};
  const auto make_room = [&](std::size_t n) {
    stack.reserve(n, cur.top);
    cur.col_ha = stack.column(0), cur.col_hb = stack.column(1), cur.col_wa = stack.column(2), cur.col_wb = stack.column(3);
  };
  make_room(64);
  const auto push = [&](Index ha, Index hb, Index wa, Index wb) {
    cur.col_ha[cur.top] = ha, cur.col_hb[cur.top] = hb, cur.col_wa[cur.top] = wa, cur.col_wb[cur.top] = wb;
    ++cur.top;
  };
  // Candidates: written in place, 16 at a time (full-width stores), into room made ahead, trimmed at the end.
  std::size_t emitted = pairs.size();
  pairs.resize(std::max<std::size_t>(pairs.capacity(), emitted + 1024));
  cur.pout = pairs.data() + emitted;
  FacePair* pend = pairs.data() + pairs.size();
  // The visited node: each side's home and slot (as on the stack).
  Index ha = start.a, hb = start.b, wa = -1, wb = -1;
  bool visit = true;
  if (!(self && start.a == start.b)) {
    ++bv_tests;
    visit = v.nodes_overlap(start.a, start.b);
    ha = side_a.home[start.a], hb = side_b.home[start.b], wa = side_a.slot[start.a], wb = side_b.slot[start.b];
  }
  for (;;) {
    if (visit) {
      if (cur.top + 2 * W * W > stack.cap()) [[unlikely]] make_room(cur.top + 2 * W * W);
      if (self && ha == hb) {  // a self node (a pair node's homes differ)
        if (const BvhNode& A = na[ha]; v.self_opens(A, ha)) {
          // (L, R) is pushed untested: testing it here culls few and reads the binary array, away from the
          // records; its visit tests the lanes anyway (docs/wide-bvh.md).
          const auto c = BvttView<BV>::self_children(A);
          push(side_a.home[c.node[2].a], side_a.home[c.node[2].b], side_a.slot[c.node[2].a], side_a.slot[c.node[2].b]);
          push(c.node[1].a, c.node[1].b, -1, -1);
          ha = hb = c.node[0].a;
          continue;
        }
      } else {
        Index ra, rb;
        const unsigned allowed = entry_lane_pairs(side_a.records, side_b.records, ha, hb, wa, wb, ra, rb);
        bv_tests += unsigned(std::popcount(allowed));
        if (cur.pout + W * W > pend) [[unlikely]] {
          emitted = std::size_t(cur.pout - pairs.data());
          pairs.resize(2 * pairs.size() + W * W);
          cur.pout = pairs.data() + emitted;
          pend = pairs.data() + pairs.size();
        }
        visit_lane_pairs(side_a.records[ra], side_b.records[rb], ra, rb, allowed, self, cur);
      }
    }
    if (cur.top == 0) break;
    --cur.top;
    ha = cur.col_ha[cur.top], hb = cur.col_hb[cur.top], wa = cur.col_wa[cur.top], wb = cur.col_wb[cur.top];
    // Ask for the records of the node two below the top: visited next but one when this visit pushes nothing
    // (the usual case near the leaves), or after this visit's pushes, still soon. The first read of a record is
    // a miss; one below the top comes too late to hide it (docs/appendix-wide-bvh.md has the figures). A self
    // node's entry holds its node id, not a home: id / W is then some record (ids < 2 · records), a useless but
    // harmless prefetch.
    if (cur.top >= 2) prefetch_entry_records(side_a.records, side_b.records, cur, cur.top - 2);
    visit = true;
  }
  pairs.resize(std::size_t(cur.pout - pairs.data()));
  bv_tests_out += bv_tests;
}

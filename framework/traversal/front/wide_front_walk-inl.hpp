// The wide front's step, included by front/wide_front.hpp once per instruction set inside its lane-pair
// namespace (lane_pair_avx512, lane_pair_avx2: bvtt_wide.hpp), with CCDLAB_WALK_TARGET the set's function
// attribute and that namespace's visit_lane_pairs in scope. No include guard: one step per inclusion.
/// Processes groups [begin, end) (call only where the view's lane_pairs allows this instruction set): appends the next
/// front's groups to `next` and the candidates to `pairs`. `prune`: false at a rebuild (seeds are split for
/// balance, not to be merged back at once) or when the scheduler says so. The groups of `next` before
/// `piece_begin` are other pieces': nothing is merged into them.
template <class BV>
CCDLAB_WALK_TARGET void process_wide_front(const BvttView<BV>& v, const WideFrontGroup* begin,
                                             const WideFrontGroup* end, bool prune, WideFrontPiece& next,
                                             std::size_t piece_begin, FacePairs& pairs, LanePairStack& stack,
                                             FrontCounters& counters) {
  constexpr int W = WideLayout::kWidth;
  const WideBounds<BV>* const wide_a = v.side_a.wide->data();
  const WideBounds<BV>* const wide_b = v.side_b.wide->data();
  const WideLayout& la = *v.side_a.wide_layout;
  const WideLayout& lb = *v.side_b.wide_layout;
  const BvhNode* const na = v.side_a.bvh->nodes.data();
  const bool self = v.self;
  FrontCounters c;  // local: the caller's are written once, at the end
  LanePairCursor cur{nullptr, nullptr, nullptr, nullptr, 0, nullptr, v.side_a.wide_ends, v.side_b.wide_ends};
  const auto make_room = [&](std::size_t n) {
    stack.reserve(n, cur.top);
    cur.col_ha = stack.column(0), cur.col_hb = stack.column(1), cur.col_wa = stack.column(2), cur.col_wb = stack.column(3);
  };
  make_room(64);
  std::size_t emitted = pairs.size();
  pairs.resize(std::max<std::size_t>(pairs.capacity(), emitted + 1024));
  cur.pout = pairs.data() + emitted;
  FacePair* pend = pairs.data() + pairs.size();
  // Room for one visit: 16 more children on the stack, 16 more candidates.
  const auto room_for_visit = [&] {
    if (cur.top + W * W > stack.cap()) [[unlikely]] make_room(cur.top + W * W);
    if (cur.pout + W * W > pend) [[unlikely]] {
      emitted = std::size_t(cur.pout - pairs.data());
      pairs.resize(2 * pairs.size() + W * W);
      cur.pout = pairs.data() + emitted;
      pend = pairs.data() + pairs.size();
    }
  };
  // The homes of the node pair whose visit tests exactly g's lane pairs (see PRUNE above), or false. No
  // sub-tree test is needed in self passes: a cut holds pair nodes only, and if x held y (or x == y) some lane
  // pair of x's record and y's would hold one side inside the other.
  const auto whole_visit_of = [&](const WideFrontGroup& g, Index& hx, Index& hy) {
    const unsigned cut = g.cut;
    unsigned rows = 0;
    for (int i = 0; i < W; ++i) rows |= unsigned((cut >> (W * i) & 0xFu) != 0) << i;
    const unsigned cols = (cut | cut >> 4 | cut >> 8 | cut >> 12) & 0xFu;
    if (cut != (lane_rows_mask(rows) & (cols * 0x1111u))) return false;
    const auto side = [&](const WideLayout& l, const WideBounds<BV>& rec, Index r, unsigned lanes, Index& h) {
      if (lanes == (1u << used_lanes(rec)) - 1) {  // every lane: the record's owner (the top record is nobody's)
        h = l.owner_home[std::size_t(r)];
        return h >= 0 ? 1 : -1;
      }
      const int j = std::countr_zero(lanes);
      if (std::popcount(lanes) != 1 || rec.lanes.slot[std::size_t(j)] >= 0) return -1;
      h = r * W + j;  // a leaf side stays itself
      return 0;
    };
    const int inner_a = side(la, wide_a[g.ra], g.ra, rows, hx);
    const int inner_b = side(lb, wide_b[g.rb], g.rb, cols, hy);
    return inner_a >= 0 && inner_b >= 0 && inner_a + inner_b > 0;
  };
  // The next front's groups: written in place like the candidates (at most one more per visit).
  std::size_t written = next.size();
  next.resize(std::max<std::size_t>(next.capacity(), written + 256));
  WideFrontGroup* gbase = next.data();
  WideFrontGroup* gout = gbase + written;
  WideFrontGroup* gfloor = gbase + piece_begin;  // the first group of this piece: merges stop there
  WideFrontGroup* gend = gbase + next.size();
  const auto room_for_group = [&] {
    if (gout == gend) [[unlikely]] {
      written = std::size_t(gout - gbase);
      next.resize(2 * next.size());
      gbase = next.data(), gout = gbase + written, gend = gbase + next.size(), gfloor = gbase + piece_begin;
    }
  };
  // This step's recent visits: their records and all 16 answers, direct-mapped (the answers cannot change within
  // a step). A quiet group's parent visit is usually among them.
  struct Seen {
    Index ra = -1, rb = -1;
    unsigned all = 0;
  };
  constexpr unsigned kSeen = 256;
  Seen seen[kSeen];
  const auto seen_slot = [](Index ra, Index rb) { return (unsigned(ra) * 2654435761u + unsigned(rb)) >> 24 & (kSeen - 1); };
  const auto remember = [&](Index ra, Index rb, unsigned all) { seen[seen_slot(ra, rb)] = Seen{ra, rb, all}; };
  // Does the lane pair at homes hx, hy overlap? From the cache, else one BV test.
  const auto lane_pair_overlaps = [&](Index hx, Index hy) {
    const Seen& s = seen[seen_slot(hx / W, hy / W)];
    if (s.ra == hx / W && s.rb == hy / W) return (s.all >> (W * (hx % W) + hy % W) & 1u) != 0;
    ++c.bv_tests;
    unsigned hit = overlapping_lanes(wide_b[hy / W], WideLane<BV>{wide_a + hx / W, hx % W});
    if (cur.ends_a) hit &= ~lanes_apart_at_both_ends(cur.ends_b[hy / W], cur.ends_a[hx / W], hx % W);
    return (hit >> (hy % W) & 1u) != 0;
  };
  // Appends a group, merged into the last one when it holds the same two records; then, while the last group is
  // quiet and is one node pair's whole visit, and that node pair does not overlap, prunes it into that node pair.
  const auto push_group = [&](Index ra, Index rb, unsigned cut, bool quiet, std::uint8_t wait) {
    if (!cut) return;
    if (gout != gfloor && gout[-1].ra == ra && gout[-1].rb == rb) {
      gout[-1].cut = std::uint16_t(gout[-1].cut | cut);
      gout[-1].quiet &= std::uint8_t(quiet);
      gout[-1].prune_wait = std::min(gout[-1].prune_wait, wait);
    } else {
      room_for_group();
      *gout++ = WideFrontGroup{ra, rb, std::uint16_t(cut), std::uint8_t(quiet), wait};
    }
    while (prune && gout[-1].quiet && gout[-1].prune_wait == 0) {
      Index hx = 0, hy = 0;  // set by whole_visit_of when it answers true
      if (!whole_visit_of(gout[-1], hx, hy)) {  // not one node pair's visit until its mask changes
        gout[-1].prune_wait = kNoPruneWhileSame;
        break;
      }
      if (lane_pair_overlaps(hx, hy)) {
        gout[-1].prune_wait = kPruneWait;
        break;
      }
      --gout;
      ++c.pruned;
      const unsigned bit = 1u << (W * (hx % W) + hy % W);
      if (gout != gfloor && gout[-1].ra == hx / W && gout[-1].rb == hy / W) {
        gout[-1].cut = std::uint16_t(gout[-1].cut | bit);  // its quiet flag stands: (x, y) is quiet
        gout[-1].prune_wait = 0;  // a new mask: its own node pair may be whole now
      } else {
        *gout++ = WideFrontGroup{hx / W, hy / W, std::uint16_t(bit), 1, 0};
      }
    }
  };
  for (const WideFrontGroup* g = begin; g != end; ++g) {
    // Lane pairs inside a patch that cannot touch itself this step: kept, untested.
    unsigned held = 0;
    if (v.skip_root)
      for (unsigned m = g->cut; m; m &= m - 1) {
        const int bit = std::countr_zero(m);
        if (v.in_skipped_patch(la.lanes[std::size_t(g->ra)].node[std::size_t(bit / W)],
                               lb.lanes[std::size_t(g->rb)].node[std::size_t(bit % W)]))
          held |= 1u << bit;
      }
    // Self seeds (a rebuild's only: see REBUILD), pushed for the walk below; the rest is visited.
    const unsigned self_seeds = self && g->ra == g->rb ? g->cut & kDiagonalLanePairs : 0;
    const unsigned allowed = g->cut & ~held & ~self_seeds;
    ++c.visited;
    c.bv_tests += unsigned(std::popcount(allowed));
    for (unsigned m = self_seeds; m; m &= m - 1) {
      const Index x = la.lanes[std::size_t(g->ra)].node[std::size_t(std::countr_zero(m) / W)];
      room_for_visit();
      cur.col_ha[cur.top] = cur.col_hb[cur.top] = x, cur.col_wa[cur.top] = cur.col_wb[cur.top] = -1;
      ++cur.top;
    }
    room_for_visit();
    const LanePairAnswer kept = visit_lane_pairs(wide_a[g->ra], wide_b[g->rb], g->ra, g->rb, allowed, self, cur);
    remember(g->ra, g->rb, kept.all);
    c.sprouted += unsigned(std::popcount(kept.down | self_seeds));
    const unsigned cut = g->cut & ~kept.down & ~kept.adjacent & ~self_seeds;
    const std::uint8_t wait = cut != g->cut || g->prune_wait == 0 ? 0 : std::uint8_t(g->prune_wait - 1);
    push_group(g->ra, g->rb, cut, kept.hit == 0 && held == 0 && wait == 0, wait);
    // Sprouts: the walk below every lane pair pushed, each visit leaving the group of what it did not descend.
    while (cur.top > 0) {
      --cur.top;
      const Index ha = cur.col_ha[cur.top], hb = cur.col_hb[cur.top], wa = cur.col_wa[cur.top], wb = cur.col_wb[cur.top];
      if (cur.top >= 2) prefetch_entry_records(wide_a, wide_b, cur, cur.top - 2);
      if (self && ha == hb) {  // a self node (by node id, as the walk pushes it; a pair node's homes differ)
        // Self seeds exist only where no patch is skipped, so self_opens is "not a leaf" here (else a skipped
        // node would leave the cut).
        if (const BvhNode& x = na[ha]; v.self_opens(x, ha)) {
          // As traverse_bvtt_lane_pairs: (L, R) untested, (R, R), then (L, L) on top.
          const auto push = [&](Index h_a, Index h_b, Index w_a, Index w_b) {
            cur.col_ha[cur.top] = h_a, cur.col_hb[cur.top] = h_b, cur.col_wa[cur.top] = w_a, cur.col_wb[cur.top] = w_b;
            ++cur.top;
          };
          room_for_visit();
          const auto ch = BvttView<BV>::self_children(x);
          const BvttNode lr = ch.node[2];
          push(la.home[std::size_t(lr.a)], la.home[std::size_t(lr.b)], la.slot[std::size_t(lr.a)], la.slot[std::size_t(lr.b)]);
          push(ch.node[1].a, ch.node[1].b, -1, -1);
          push(ch.node[0].a, ch.node[0].b, -1, -1);
        }
        continue;
      }
      Index ra, rb;
      const unsigned lanes = entry_lane_pairs(wide_a, wide_b, ha, hb, wa, wb, ra, rb);
      c.bv_tests += unsigned(std::popcount(lanes));
      room_for_visit();
      const LanePairAnswer a = visit_lane_pairs(wide_a[ra], wide_b[rb], ra, rb, lanes, self, cur);
      remember(ra, rb, a.all);
      // Born waiting: its node pair overlapped this step (it was descended), so an attempt next step would fail
      // and cost a BV test on a record no visit has in cache (the binary front's kFresh rule).
      push_group(ra, rb, lanes & ~a.down & ~a.adjacent, false, kPruneWait);
    }
    // The next group's records, asked for early (the front is read in order; its records are scattered).
    if (g + 5 < end) {
      const char* ra = reinterpret_cast<const char*>(wide_a + g[5].ra);
      const char* rb = reinterpret_cast<const char*>(wide_b + g[5].rb);
      for (std::size_t line = 0; line < sizeof(WideBounds<BV>); line += 64) __builtin_prefetch(ra + line), __builtin_prefetch(rb + line);
    }
  }
  pairs.resize(std::size_t(cur.pout - pairs.data()));
  next.resize(std::size_t(gout - gbase));
  counters += c;
}

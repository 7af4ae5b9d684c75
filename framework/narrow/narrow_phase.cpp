#include "framework/narrow/narrow_phase.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>

#include "framework/narrow/kdop_filter.hpp"
#include "framework/narrow/window_distance_filter.hpp"
#include "framework/narrow/split_filter.hpp"
#include "framework/narrow/triangle_filter.hpp"

#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

using Clock = std::chrono::steady_clock;

std::uint64_t ns_since(Clock::time_point t) {
  return std::uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t).count());
}

/// Counts one elementary test, its route and its hit (`tests`, `contacts`: the VF or EE counters); returns the hit.
bool counted(const CcdHit& hit, std::uint64_t& tests, std::uint64_t& contacts, NarrowCounters& c) {
  ++tests;
  c.tests_filtered += hit.route == TestRoute::filter;
  c.tests_fallback += hit.route == TestRoute::fallback;
  contacts += hit.hit;
  return hit.hit;
}

/// Keeps the pairs whose keep flag is set, in order. Branch-free: the flags are close to random, and a
/// mispredicted branch per pair costs more than the stage that set them.
template <class Pairs>
void compact(Pairs& pairs, const std::uint8_t* keep) {
  std::size_t j = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    pairs[j] = pairs[i];
    j += keep[i];
  }
  pairs.resize(j);
}

/// Appends the pairs whose keep flag is set to `out`, in order (branch-free, as compact above).
template <class Pair>
void append_kept(std::span<const Pair> pairs, const std::uint8_t* keep, UninitializedVector<Pair>& out) {
  std::size_t j = out.size();
  out.resize(j + pairs.size());
  Pair* dst = out.data();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    dst[j] = pairs[i];
    j += keep[i];
  }
  out.resize(j);
}

/// VF flags first, then EE (and `from`, laid out the same, in one pass).
void compact(FeatureBatch& batch, const std::vector<std::uint8_t>& keep) {
  const std::size_t nvf = batch.vf.size();
  compact(batch.vf, keep.data());
  compact(batch.ee, keep.data() + nvf);
  if (!batch.from.empty()) compact(batch.from, keep.data());
}

}  // namespace

StepPossible NarrowPhase::possible() const {
  const bool batched = options_.mode == NarrowMode::batched, reach = tester_.cull_reach().has_value();
  // Forced on, the candidates carry the orphans in scalar mode too (the tests compare the two).
  const bool carry = reps_.carries_orphans() && (batched || options_.rules.orphan_carry == PassChoice::on);
  return {.triangles = batched && reach, .culling = batched && reach, .carry = carry, .certificates = batched};
}

void NarrowPhase::begin_step(const Positions& x_t0, const Positions& x_t1, const FeatureBounds& bounds, const StepPlan& plan) {
  x_t0_ = &x_t0;
  x_t1_ = &x_t1;
  motionless_ = &x_t0 == &x_t1;
  bounds_ = &bounds;
  const StepPossible can = possible();
  triangle_stage_ = can.triangles && plan.triangles;
  triangle_box_pass_ = !plan.end_boxes;
  sixteenths_stage_ = plan.sixteenths;
  proximity_stage_ = plan.proximity || motionless_;  // without motion stage 4 is the only window test there is
  carry_orphans_ = can.carry && plan.carry;
  certificates_in_step_ = can.certificates && plan.certificates && !carry_orphans_;
  if (triangle_stage_) float_frames_.update(x_t0.data(), x_t1.data(), x_t0.size(), mesh_.faces(), triangle_box_pass_);
}

void NarrowPhase::gather(std::span<const FacePair> candidates, NarrowScratch& scratch, NarrowCounters& c,
                         bool cull) const {
  FeatureBatch& batch = scratch.batch;
  const auto reach = tester_.cull_reach();
  if (!cull || !triangle_stage_ || !reach || candidates.empty()) {
    c.candidates_gathered += candidates.size();
    c.orphans_carried += reps_.append_pairs(candidates, batch.vf, batch.ee, true, carry_orphans_);
    return;
  }
  const auto t = Clock::now();
  scratch.keep.resize(candidates.size());
  const std::size_t fine = triangle_filter(candidates, mesh_.faces().data(), float_frames_, *reach, scratch.keep.data(),
                                           triangle_box_pass_);
  scratch.candidates.clear();
  append_kept(candidates, scratch.keep.data(), scratch.candidates);
  c.triangle_tested += candidates.size();
  c.triangle_fine += fine;
  c.triangle_culled += candidates.size() - scratch.candidates.size();
  c.triangle_ns += ns_since(t);
  c.candidates_gathered += scratch.candidates.size();
  c.orphans_carried += reps_.append_pairs(scratch.candidates, batch.vf, batch.ee, true, carry_orphans_);
}

std::uint64_t NarrowPhase::begin_orphans(const Positions& x_t0, const Positions& x_t1) {
  // Only steps whose orphan loop tests the whole set can use them (gather_orphans), as the plan says.
  const auto t = Clock::now();
  certify_orphans_ = certificates_in_step_;
  if (certify_orphans_) certificates_.begin_step(x_t0, x_t1, tester_.thickness());
  else certificates_.forget();
  return ns_since(t);
}

void NarrowPhase::gather_orphans(std::size_t b, std::size_t e, FeatureBatch& batch, NarrowCounters& c,
                                 bool cull) const {
  const OrphanSet& orphans = orphans_to_test();
  const std::size_t nvf = orphans.vf.size(), n = nvf + orphans.ee.size();
  e = std::min(e, n);
  const auto vf = [&](std::size_t lo, std::size_t hi) {
    return std::span(orphans.vf).subspan(std::min(lo, nvf), std::min(hi, nvf) - std::min(lo, nvf));
  };
  const auto ee = [&](std::size_t lo, std::size_t hi) {
    return std::span(orphans.ee).subspan(std::max(lo, nvf) - nvf, std::max(hi, nvf) - std::max(lo, nvf));
  };
  if (options_.mode == NarrowMode::scalar || !cull) {  // stage 1 runs pair by pair in run(), or not at all
    batch.vf.insert(batch.vf.end(), vf(b, e).begin(), vf(b, e).end());
    batch.ee.insert(batch.ee.end(), ee(b, e).begin(), ee(b, e).end());
    return;
  }
  const auto t = Clock::now();
  if (!certify_orphans_) {  // stage 1's coarse test, in pieces whose flags stay in L1
    constexpr std::size_t kPiece = 1024;
    std::uint8_t keep[kPiece];
    for (std::size_t s = b; s < e; s += kPiece) {
      const auto pv = vf(s, std::min(e, s + kPiece));
      const auto pe = ee(s, std::min(e, s + kPiece));
      vf_keep_coarse(*bounds_, mesh_, pv, keep);
      append_kept(pv, keep, batch.vf);
      ee_keep_coarse(*bounds_, mesh_, pe, keep);
      append_kept(pe, keep, batch.ee);
    }
    c.vf_pairs += vf(b, e).size();
    c.ee_pairs += ee(b, e).size();
    c.kdop_culled += e - b - batch.vf.size() - batch.ee.size();
    c.kdop_ns += ns_since(t);
    batch.coarse_done = true;
    return;
  }
  constexpr std::size_t kBlock = OrphanCertificates::kBlock;
  std::uint8_t keep[kBlock];  // flags on the stack, in L1
  std::uint64_t gathered = 0;
  for (std::size_t s = b; s < e;) {
    const std::size_t k = OrphanCertificates::block_of(s), block_end = std::min((k + 1) * kBlock, n),
                      piece_end = std::min(e, block_end);
    const bool whole = s == k * kBlock && piece_end == block_end;
    if (whole && certificates_.holds(k)) {
      c.orphans_unmoved += piece_end - s;
      s = piece_end;
      continue;
    }
    const auto pv = vf(s, piece_end);
    const auto pe = ee(s, piece_end);
    int steps = vf_keep_coarse_gap(*bounds_, mesh_, pv, keep);
    append_kept(pv, keep, batch.vf);
    steps = std::min(steps, ee_keep_coarse_gap(*bounds_, mesh_, pe, keep));
    append_kept(pe, keep, batch.ee);
    if (whole) certificates_.certify(k, double(steps - 2) * bounds_->coarse_step());
    c.vf_pairs += pv.size();
    c.ee_pairs += pe.size();
    gathered += pv.size() + pe.size();
    s = piece_end;
  }
  c.kdop_culled += gathered - batch.vf.size() - batch.ee.size();
  c.kdop_ns += ns_since(t);
  batch.coarse_done = true;
}

VertexFaceQuery NarrowPhase::vf_query(Index v, Index f) const {
  const Face& t = mesh_.face(f);
  const Positions &x0 = *x_t0_, &x1 = *x_t1_;
  return {x0[v], x0[t[0]], x0[t[1]], x0[t[2]], x1[v], x1[t[0]], x1[t[1]], x1[t[2]]};
}

EdgeEdgeQuery NarrowPhase::ee_query(Index a, Index b) const {
  const Edge &ea = mesh_.edge(a), &eb = mesh_.edge(b);
  const Positions &x0 = *x_t0_, &x1 = *x_t1_;
  return {x0[ea[0]], x0[ea[1]], x0[eb[0]], x0[eb[1]], x1[ea[0]], x1[ea[1]], x1[eb[0]], x1[eb[1]]};
}

void NarrowPhase::run(NarrowScratch& scratch, Contacts& out, NarrowCounters& c, bool cull) const {
  FeatureBatch& batch = scratch.batch;
  if (!batch.coarse_done) {
    c.vf_pairs += batch.vf.size();
    c.ee_pairs += batch.ee.size();
  }
  if (options_.mode == NarrowMode::scalar) {
    // One pair at a time: the 26-DOP test, then the tester.
    const auto t = Clock::now();
    for (const VertexFacePair& p : batch.vf) {
      if (cull && !vf_may_touch(*bounds_, p.v, mesh_.face(p.f))) {
        ++c.kdop_culled;
        continue;
      }
      test_vf(p.v, p.f, out, c);
    }
    for (const EdgeEdgePair& p : batch.ee) {
      if (cull && !ee_may_touch(*bounds_, mesh_.edge(p.a), mesh_.edge(p.b))) {
        ++c.kdop_culled;
        continue;
      }
      test_ee(p.a, p.b, out, c);
    }
    c.test_ns += ns_since(t);
    return;
  }
  if (cull) {
    if (!batch.coarse_done) cull_kdop(scratch, c, /*coarse=*/true);  // stage 1 on the 16-bit grid, every pair
    if (const auto reach = tester_.cull_reach()) {
      cull_plane(scratch, *reach, c);  // stages 2, 3 and 4
    }
    cull_kdop(scratch, c, /*coarse=*/false);  // stage 1's float test, the definition, on what is left
  }
  test(batch, out, c);
}

void NarrowPhase::cull_kdop(NarrowScratch& scratch, NarrowCounters& c, bool coarse) const {
  const auto t = Clock::now();
  FeatureBatch& batch = scratch.batch;
  const std::size_t nvf = batch.vf.size(), n = nvf + batch.ee.size();
  scratch.keep.resize(n);
  if (coarse) {
    vf_keep_coarse(*bounds_, mesh_, batch.vf, scratch.keep.data());
    ee_keep_coarse(*bounds_, mesh_, batch.ee, scratch.keep.data() + nvf);
  } else {
    vf_keep(*bounds_, mesh_, batch.vf, scratch.keep.data());
    ee_keep(*bounds_, mesh_, batch.ee, scratch.keep.data() + nvf);
  }
  compact(batch, scratch.keep);
  c.kdop_culled += n - batch.vf.size() - batch.ee.size();
  c.kdop_ns += ns_since(t);
}

void NarrowPhase::cull_plane(NarrowScratch& scratch, CullReach reach, NarrowCounters& c) const {
  const auto t = Clock::now();
  FeatureBatch& batch = scratch.batch;
  const std::size_t nvf = batch.vf.size(), n = nvf + batch.ee.size();
  if (n == 0) return;
  PlaneBatch& plane = scratch.plane;
  plane.resize(n);
  stage_vf_rows(plane, 0, batch.vf, mesh_.faces().data(), bounds_->frame_points());
  stage_ee_rows(plane, nvf, batch.ee, mesh_.edges().data(), bounds_->frame_points());
  scratch.keep.resize(n);
  plane_filter(plane, reach, scratch.keep.data());
  std::size_t plane_kept = 0;
  for (std::size_t i = 0; i < n; ++i) plane_kept += scratch.keep[i];
  c.plane_culled += n - plane_kept;
  // Moving a kept row (27 doubles) costs about what stage 3's halves cost on a row: when stage 2
  // keeps most rows, the halves run on all of them, the culled ones too (their flags stay 0), and one compaction
  // follows instead of two.
  const bool compact_now = 2 * plane_kept < n;
  if (compact_now) {
    plane.compact(scratch.keep.data());
    compact(batch, scratch.keep);
  }
  const auto t_split = Clock::now();
  c.plane_ns += ns_since(t);
  // Stage 3 on stage 2's survivors, from the coefficients, threshold and reach stage 2 left in the rows: halves,
  // then, in the steps the rules choose (rules/stage_rules.hpp), sixteenths on what the halves keep, within the halves they
  // left open (split_filter.hpp); the last pass leaves each row's open windows for stage 4.
  std::size_t kept_vf = 0, rows = 0;
  // Without motion (the proximity query) every window of the step is the same instant, which stage 2 has already
  // tested: stage 3 is skipped and stage 4 takes the whole step as one window.
  const int levels = motionless_ ? 0 : sixteenths_stage_ ? kSplitLevels : kSplitCoarseLevels;
  if (motionless_) {
    kept_vf = batch.vf.size(), rows = kept_vf + batch.ee.size();
    if (compact_now) scratch.keep.assign(rows, 1);  // else: stage 2's flags
    scratch.open.assign(rows, 1);
  }
  auto t_sixteenths = t_split;  // where the sixteenths' own time starts: their compaction after the halves
  for (const int pass : {kSplitCoarseLevels, kSplitLevels}) {
    if (motionless_) break;
    const bool sixteenths = pass == kSplitLevels;
    kept_vf = batch.vf.size(), rows = kept_vf + batch.ee.size();
    if (sixteenths || compact_now) scratch.keep.assign(rows, 1);  // else: stage 2's flags, which the halves only clear
    scratch.open.resize(rows);
    std::uint16_t* open = scratch.open.data();
    const std::uint16_t* halves = sixteenths ? open : nullptr;  // read and overwritten row by row
    split_filter(plane, 0, kept_vf, true, scratch.keep.data(), pass, open, halves);
    split_filter(plane, kept_vf, rows, false, scratch.keep.data(), pass, open, halves);
    if (pass == levels) break;  // stage 4 reads these rows in place, and compacts once
    t_sixteenths = Clock::now();
    plane.compact(scratch.keep.data());  // the rows the next pass reads
    compact(batch, scratch.keep);
    compact(scratch.open, scratch.keep.data());
  }
  std::size_t split_kept = 0;
  for (std::size_t i = 0; i < rows; ++i) split_kept += scratch.keep[i];
  c.split_culled += plane_kept - split_kept;
  const auto t_proximity = Clock::now();
  if (levels == kSplitLevels) {
    c.sixteenths_tested += rows, c.sixteenths_culled += rows - split_kept;
    c.sixteenths_ns += ns_since(t_sixteenths);
    c.split_ns += std::uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(t_sixteenths - t_split).count());
  } else {
    c.split_ns += ns_since(t_split);
  }
  // Stage 4 on the rows stage 3 kept, in place (same row numbers): the distance on their open windows, in the
  // steps the rules choose (rules/stage_rules.hpp).
  if (proximity_stage_) {
    window_distance_filter(plane, kept_vf, rows, scratch.open.data(), levels, scratch.keep.data(), scratch.proximity);
    c.proximity_tested += split_kept;
    c.proximity_ns += ns_since(t_proximity);
  }
  // Each pair's earliest possible time: the start of its first open window; then the one compaction, which
  // runs whether stage 4 does or not (stage 3's).
  const auto t_compact = Clock::now();
  batch.from.resize(rows);
  for (std::size_t i = 0; i < rows; ++i)
    batch.from[i] = scratch.open[i] ? float(std::countr_zero(scratch.open[i])) / float(1 << levels) : 1.0f;
  compact(batch, scratch.keep);
  c.proximity_culled += split_kept - batch.vf.size() - batch.ee.size();
  c.split_ns += ns_since(t_compact);
}

void NarrowPhase::test(const FeatureBatch& batch, Contacts& out, NarrowCounters& c) const {
  if (earliest_) return test_earliest(batch, out, c);
  const auto t = Clock::now();
  // In blocks, for testers with a batched kernel (PrimitiveTester::vertex_faces); a block's queries stay in L1.
  const auto from = [&](std::size_t i) { return batch.from.empty() ? 0.0 : double(batch.from[i]); };
  const auto in_blocks = [&](const auto& pairs, auto query_of, auto run, auto record) {
    if (pairs.empty()) return;  // most chunks of a sparse step: not even the arrays below (64 hits to initialise)
    constexpr std::size_t kBlock = 64;
    std::array<decltype(query_of(pairs[0])), kBlock> queries;
    std::array<CcdHit, kBlock> hits;
    for (std::size_t b = 0; b < pairs.size(); b += kBlock) {
      const std::size_t n = std::min(kBlock, pairs.size() - b);
      for (std::size_t i = 0; i < n; ++i) queries[i] = query_of(pairs[b + i]);
      run(std::span(queries.data(), n), hits.data());
      for (std::size_t i = 0; i < n; ++i) record(b + i, hits[i]);
    }
  };
  const std::size_t nvf = batch.vf.size();
  in_blocks(
      batch.vf, [&](const VertexFacePair& p) { return vf_query(p.v, p.f); },
      [&](std::span<const VertexFaceQuery> q, CcdHit* h) { tester_.vertex_faces(q, h); },
      [&](std::size_t i, const CcdHit& h) { record_vf(batch.vf[i], h, from(i), out, c); });
  in_blocks(
      batch.ee, [&](const EdgeEdgePair& p) { return ee_query(p.a, p.b); },
      [&](std::span<const EdgeEdgeQuery> q, CcdHit* h) { tester_.edge_edges(q, h); },
      [&](std::size_t i, const CcdHit& h) { record_ee(batch.ee[i], h, from(nvf + i), out, c); });
  c.test_ns += ns_since(t);
}

void NarrowPhase::test_earliest(const FeatureBatch& batch, Contacts& out, NarrowCounters& c) const {
  const auto t = Clock::now();
  const std::size_t nvf = batch.vf.size(), n = nvf + batch.ee.size();
  const auto from = [&](std::size_t i) { return batch.from.empty() ? 0.0f : batch.from[i]; };
  // Pair i < nvf is VF pair i, else EE pair i − nvf; in order of earliest possible time.
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = std::uint32_t(i);
  if (!batch.from.empty())
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return from(a) < from(b); });
  constexpr std::size_t kBlock = 64;
  std::array<VertexFaceQuery, kBlock> vq;
  std::array<EdgeEdgeQuery, kBlock> eq;
  std::array<std::uint32_t, kBlock> vi, ei;
  std::array<CcdHit, kBlock> hits;
  for (std::size_t k = 0; k < n;) {
    // The next block: pairs that may still beat the best time, up to kBlock.
    const double best = earliest_->best();
    std::size_t nv = 0, ne = 0;
    for (; k < n && nv + ne < kBlock && double(from(order[k])) <= best; ++k) {
      const std::uint32_t i = order[k];
      if (i < nvf) vi[nv] = i, vq[nv++] = vf_query(batch.vf[i].v, batch.vf[i].f);
      else ei[ne] = i, eq[ne++] = ee_query(batch.ee[i - nvf].a, batch.ee[i - nvf].b);
    }
    if (nv + ne == 0) break;  // every later pair starts after the best time
    tester_.vertex_faces({vq.data(), nv}, hits.data());
    for (std::size_t j = 0; j < nv; ++j) record_vf(batch.vf[vi[j]], hits[j], from(vi[j]), out, c);  // each hit lowers the best
    tester_.edge_edges({eq.data(), ne}, hits.data());
    for (std::size_t j = 0; j < ne; ++j) record_ee(batch.ee[ei[j] - nvf], hits[j], from(ei[j]), out, c);
  }
  c.test_ns += ns_since(t);
}

void NarrowPhase::test_vf(Index v, Index f, Contacts& out, NarrowCounters& c) const {
  record_vf({v, f}, tester_.vertex_face(vf_query(v, f)), 0.0, out, c);
}

void NarrowPhase::test_ee(Index a, Index b, Contacts& out, NarrowCounters& c) const {
  record_ee({a, b}, tester_.edge_edge(ee_query(a, b)), 0.0, out, c);
}

template <class Query>
void NarrowPhase::offer_earliest(const Query& q, CcdHit& hit) const {
  // Only a hit that can still be the earliest is worth the tester's narrowing (earliest_cut.hpp).
  if (hit.toi < earliest_->best()) {
    const double t = tester_.tighten_toi(q, hit.toi);
    if (t > hit.toi) hit.toi = t, hit.coords = contact_coords(q, t);
  }
  earliest_->offer(hit.toi);
}

void NarrowPhase::record_vf(const VertexFacePair& p, CcdHit hit, double from, Contacts& out, NarrowCounters& c) const {
  if (!counted(hit, c.vf_tests, c.contacts_vf, c)) return;
  if (hit.toi < from) hit.toi = from, hit.coords = contact_coords(vf_query(p.v, p.f), from);
  if (earliest_) offer_earliest(vf_query(p.v, p.f), hit);
  const Face& t = mesh_.face(p.f);
  out.push_back(Contact{ContactKind::vf, p.v, p.f, {p.v, t[0], t[1], t[2]}, hit.toi, hit.coords});
}

void NarrowPhase::record_ee(const EdgeEdgePair& p, CcdHit hit, double from, Contacts& out, NarrowCounters& c) const {
  if (!counted(hit, c.ee_tests, c.contacts_ee, c)) return;
  if (hit.toi < from) hit.toi = from, hit.coords = contact_coords(ee_query(p.a, p.b), from);
  if (earliest_) offer_earliest(ee_query(p.a, p.b), hit);
  const Edge &ea = mesh_.edge(p.a), &eb = mesh_.edge(p.b);
  out.push_back(Contact{ContactKind::ee, p.a, p.b, {ea[0], ea[1], eb[0], eb[1]}, hit.toi, hit.coords});
}

}  // namespace ccdlab

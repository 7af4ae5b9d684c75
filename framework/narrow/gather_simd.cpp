// The fixed rule's gather (Representatives::append_pairs) with 512-bit vectors: per candidate, both faces'
// 32-byte records in one vector, one lane permutation to the six VF pairs and one to eight of the nine EE
// pairs (min and max by swapping neighbouring lanes), the owned ones first (the lanes each combination of owner
// bits picks are tabled), each vector stored whole.
// Far fewer instructions a candidate than the plain loop, which is bound by them.
// AVX2 does the same with two 256-bit output vectors per kind, each lane permuted from either record and
// blended. The same pairs in the same order as the plain loop (a test compares them on every target). Other
// targets return false and the caller runs the plain loop.
#include "framework/narrow/representatives.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/narrow/gather_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <array>
#include <utility>

#ifndef CCDLAB_GATHER_TABLES
#define CCDLAB_GATHER_TABLES
namespace ccdlab::detail {
// Per combination of the two faces' owner bits (3 of a, 3 of b: 64), the int32 lanes of the pair of records
// (lanes 0–7: a's corners 0–2, edges 3–5, owner bits 6, id 7; lanes 8–15: b's) that make the owned pairs, two
// lanes a pair, packed to the front in the plain loop's order; and how many pairs that is.
//   VF: for j = 0..2, (corner j of a, id of b) if a owns it, then (corner j of b, id of a) if b owns it.
//   EE: for i, j = 0..2, (edge i of a, edge j of b) if both own them; only the first eight (i, j) here, the
//       ninth, (2, 2), goes apart (nine pairs would not fit one vector).
struct LanePicks {
  std::array<std::array<std::int32_t, 16>, 64> lanes{};
  std::array<std::uint8_t, 64> count{};
};
constexpr LanePicks pick_vf() {
  LanePicks t{};
  for (unsigned m = 0; m < 64; ++m) {
    unsigned k = 0;
    for (unsigned j = 0; j < 3; ++j) {
      if ((m >> j) & 1u) t.lanes[m][2 * k] = std::int32_t(j), t.lanes[m][2 * k + 1] = 15, ++k;
      if ((m >> (3 + j)) & 1u) t.lanes[m][2 * k] = std::int32_t(8 + j), t.lanes[m][2 * k + 1] = 7, ++k;
    }
    t.count[m] = std::uint8_t(k);
  }
  return t;
}
constexpr LanePicks pick_ee() {
  LanePicks t{};
  for (unsigned m = 0; m < 64; ++m) {
    unsigned k = 0;
    for (unsigned i = 0; i < 3; ++i)
      for (unsigned j = 0; j < 3; ++j)
        if (3 * i + j < 8 && ((m >> i) & (m >> (3 + j)) & 1u))
          t.lanes[m][2 * k] = std::int32_t(3 + i), t.lanes[m][2 * k + 1] = std::int32_t(11 + j), ++k;
    t.count[m] = std::uint8_t(k);
  }
  return t;
}
alignas(64) inline constexpr LanePicks kVfPicks = pick_vf();
alignas(64) inline constexpr LanePicks kEePicks = pick_ee();
}  // namespace ccdlab::detail
#endif

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL || HWY_TARGET == HWY_AVX2
// (x, y) lane pairs to (min, max): each lane beside its neighbour, the min kept in the even lane, the max in the odd.
template <class V>
HWY_INLINE V OrderPairs(V x) {
  const V y = hn::Shuffle2301(x);
  return hn::OddEven(hn::Max(x, y), hn::Min(x, y));
}
#endif

bool GatherOwned(const GatherRecord* rec, const FacePair* candidates, std::size_t n, VertexFacePair* out_vf,
                 EdgeEdgePair* out_ee, std::size_t* n_vf, std::size_t* n_ee) {
#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL || HWY_TARGET == HWY_AVX2
  static_assert(sizeof(GatherRecord) == 32 && sizeof(VertexFacePair) == 8 && sizeof(EdgeEdgePair) == 8);
  const hn::Full256<std::int32_t> d8;
#if HWY_TARGET == HWY_AVX2
  // Each 256-bit output vector holds four pairs, each lane taken from a's record (table entry < 8) or b's (≥ 8):
  // one permutation of each and a blend; two vectors per table row.
  const auto seven = hn::Set(d8, 7);
  const auto load = [&](const GatherRecord& ra, const GatherRecord& rb) {
    return std::pair(hn::Load(d8, &ra.corner[0]), hn::Load(d8, &rb.corner[0]));
  };
  const auto store = [&](const auto& both, const std::int32_t* lanes, bool order, void* out) {
    for (int half = 0; half < 2; ++half) {
      const auto from = hn::Load(d8, lanes + 8 * half);
      const auto lane = hn::IndicesFromVec(d8, hn::And(from, seven));
      const auto v = hn::IfThenElse(hn::Gt(from, seven), hn::TableLookupLanes(both.second, lane),
                                    hn::TableLookupLanes(both.first, lane));
      hn::StoreU(order ? OrderPairs(v) : v, d8, static_cast<std::int32_t*>(out) + 8 * half);
    }
  };
#else
  // Both records in one 512-bit vector; a table row is one permutation of it.
  const hn::Full512<std::int32_t> d16;
  const auto load = [&](const GatherRecord& ra, const GatherRecord& rb) {
    return hn::Combine(d16, hn::Load(d8, &rb.corner[0]), hn::Load(d8, &ra.corner[0]));
  };
  const auto store = [&](const auto& both, const std::int32_t* lanes, bool order, void* out) {
    const auto v = hn::TableLookupLanes(both, hn::SetTableIndices(d16, lanes));
    hn::StoreU(order ? OrderPairs(v) : v, d16, static_cast<std::int32_t*>(out));
  };
#endif
  VertexFacePair* vf = out_vf;
  EdgeEdgePair* ee = out_ee;
  for (std::size_t k = 0; k < n; ++k) {
    const GatherRecord &ra = rec[candidates[k].a], &rb = rec[candidates[k].b];
    if (k + 12 < n) {  // the records of a later candidate, as the plain loop does
      __builtin_prefetch(&rec[candidates[k + 12].a]);
      __builtin_prefetch(&rec[candidates[k + 12].b]);
    }
    const auto both = load(ra, rb);
    const unsigned ma = unsigned(ra.owned_mask), mb = unsigned(rb.owned_mask);
    const unsigned owners = (ma & 7u) | ((mb & 7u) << 3), edge_owners = ((ma >> 3) & 7u) | (((mb >> 3) & 7u) << 3);
    store(both, detail::kVfPicks.lanes[owners].data(), false, vf);
    vf += detail::kVfPicks.count[owners];
    store(both, detail::kEePicks.lanes[edge_owners].data(), true, ee);
    ee += detail::kEePicks.count[edge_owners];
    *ee = ordered_edge_pair(ra.edge[2], rb.edge[2]);  // the ninth EE pair, (edge 2 of a, edge 2 of b)
    ee += (ma >> 5) & (mb >> 5) & 1u;
  }
  *n_vf = std::size_t(vf - out_vf);
  *n_ee = std::size_t(ee - out_ee);
  return true;
#else
  (void)rec, (void)candidates, (void)n, (void)out_vf, (void)out_ee, (void)n_vf, (void)n_ee;
  return false;
#endif
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ccdlab {
HWY_EXPORT(GatherOwned);
namespace detail {
bool gather_owned_simd(const GatherRecord* rec, std::span<const FacePair> candidates, VertexFacePair* out_vf,
                       EdgeEdgePair* out_ee, std::size_t* n_vf, std::size_t* n_ee) {
  return HWY_DYNAMIC_DISPATCH(GatherOwned)(rec, candidates.data(), candidates.size(), out_vf, out_ee, n_vf, n_ee);
}
}  // namespace detail
}  // namespace ccdlab
#endif  // HWY_ONCE

// Stage 1 over a batch in SIMD (kdop_filter.hpp). The coarse test, run on every pair: a vertex's 16-bit
// 26-DOP is 16 + 16 int16, one 256-bit load per half (two 128-bit ones on SSE4). The float test, run on what
// stages 2–4 leave: 16 + 16 floats, 2 (AVX-512) to 8 (128-bit) loads per vertex. Highway compiles this file
// once per target and picks one at run time.
#include "framework/narrow/kdop_filter.hpp"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "framework/narrow/kdop_filter.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace ccdlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void KdopKeepVf(const PaddedDop* dops, const Face* faces, const VertexFacePair* pairs, std::size_t n,
                std::uint8_t* keep) {
  const hn::ScalableTag<float> d;
  const std::size_t N = hn::Lanes(d);
  for (std::size_t i = 0; i < n; ++i) {
    const Face& f = faces[pairs[i].f];
    const PaddedDop &p = dops[pairs[i].v], &a = dops[f[0]], &b = dops[f[1]], &c = dops[f[2]];
    auto apart = hn::Lt(hn::Zero(d), hn::Zero(d));  // all false
    for (std::size_t k = 0; k < std::size_t(PaddedDop::kLanes); k += N) {
      const auto lo = hn::Min(hn::Min(hn::Load(d, a.min + k), hn::Load(d, b.min + k)), hn::Load(d, c.min + k));
      const auto hi = hn::Max(hn::Max(hn::Load(d, a.max + k), hn::Load(d, b.max + k)), hn::Load(d, c.max + k));
      apart = hn::Or(apart, hn::Or(hn::Gt(hn::Load(d, p.min + k), hi), hn::Gt(lo, hn::Load(d, p.max + k))));
    }
    keep[i] = hn::AllFalse(d, apart);
  }
}

void KdopKeepEe(const PaddedDop* dops, const Edge* edges, const EdgeEdgePair* pairs, std::size_t n,
                std::uint8_t* keep) {
  const hn::ScalableTag<float> d;
  const std::size_t N = hn::Lanes(d);
  for (std::size_t i = 0; i < n; ++i) {
    const Edge &ea = edges[pairs[i].a], &eb = edges[pairs[i].b];
    const PaddedDop &a0 = dops[ea[0]], &a1 = dops[ea[1]], &b0 = dops[eb[0]], &b1 = dops[eb[1]];
    auto apart = hn::Lt(hn::Zero(d), hn::Zero(d));
    for (std::size_t k = 0; k < std::size_t(PaddedDop::kLanes); k += N) {
      const auto alo = hn::Min(hn::Load(d, a0.min + k), hn::Load(d, a1.min + k));
      const auto ahi = hn::Max(hn::Load(d, a0.max + k), hn::Load(d, a1.max + k));
      const auto blo = hn::Min(hn::Load(d, b0.min + k), hn::Load(d, b1.min + k));
      const auto bhi = hn::Max(hn::Load(d, b0.max + k), hn::Load(d, b1.max + k));
      apart = hn::Or(apart, hn::Or(hn::Gt(alo, bhi), hn::Gt(blo, ahi)));
    }
    keep[i] = hn::AllFalse(d, apart);
  }
}

// Coarse: unions are lane-wise minima (of minima, and of negated maxima); separated where a saturating
// min + neg_max of the other side is > 0 (CoarseDop).
// With 512-bit vectors a whole CoarseDop is one vector [min | neg_max]: the union is one Min per vertex, and
// both separation sums come from one saturating add of one side and the other's halves swapped.
#if HWY_TARGET != HWY_SCALAR
template <class D>
hn::Vec<D> SwapHalves(D d, hn::Vec<D> v) {
  return hn::ConcatLowerUpper(d, v, v);  // [neg_max | min]
}
constexpr bool kWholeDop = hn::MaxLanes(hn::CappedTag<std::int16_t, 2 * CoarseDop::kLanes>()) == 2 * CoarseDop::kLanes;
#else
template <class D>
hn::Vec<D> SwapHalves(D, hn::Vec<D> v) {
  return v;  // never called: one lane
}
constexpr bool kWholeDop = false;
#endif

// With kGap, also the smallest over the pairs of each pair's largest separation sum (in grid steps, saturated;
// ≤ 0 when some pair overlaps; +32767 for no pairs): the lanes are the separation sums themselves.
template <bool kGap>
int CoarseKeepVfT(const CoarseDop* dops, const Face* faces, const VertexFacePair* pairs, std::size_t n,
                  std::uint8_t* keep) {
  int smallest = CoarseDop::kClamp;
  if constexpr (kWholeDop) {
    const hn::CappedTag<std::int16_t, 2 * CoarseDop::kLanes> d;
    const auto zero = hn::Zero(d);
    const auto whole = [&](Index v) { return hn::Load(d, dops[v].min); };
    for (std::size_t i = 0; i < n; ++i) {
      const Face& f = faces[pairs[i].f];
      const auto face = hn::Min(hn::Min(whole(f[0]), whole(f[1])), whole(f[2]));
      const auto sum = hn::SaturatedAdd(whole(pairs[i].v), SwapHalves(d, face));
      keep[i] = hn::AllFalse(d, hn::Gt(sum, zero));
      if constexpr (kGap) smallest = std::min(smallest, int(hn::GetLane(hn::MaxOfLanes(d, sum))));
    }
    return smallest;
  }
  const hn::CappedTag<std::int16_t, CoarseDop::kLanes> d;
  const std::size_t N = hn::Lanes(d);
  const auto zero = hn::Zero(d);
  for (std::size_t i = 0; i < n; ++i) {
    const Face& f = faces[pairs[i].f];
    const CoarseDop &p = dops[pairs[i].v], &a = dops[f[0]], &b = dops[f[1]], &c = dops[f[2]];
    auto largest = hn::Set(d, std::int16_t(-CoarseDop::kClamp));
    for (std::size_t k = 0; k < std::size_t(CoarseDop::kLanes); k += N) {
      const auto lo = hn::Min(hn::Min(hn::Load(d, a.min + k), hn::Load(d, b.min + k)), hn::Load(d, c.min + k));
      const auto neg_hi =
          hn::Min(hn::Min(hn::Load(d, a.neg_max + k), hn::Load(d, b.neg_max + k)), hn::Load(d, c.neg_max + k));
      largest = hn::Max(largest, hn::Max(hn::SaturatedAdd(hn::Load(d, p.min + k), neg_hi),
                                         hn::SaturatedAdd(lo, hn::Load(d, p.neg_max + k))));
    }
    keep[i] = hn::AllFalse(d, hn::Gt(largest, zero));
    if constexpr (kGap) smallest = std::min(smallest, int(hn::GetLane(hn::MaxOfLanes(d, largest))));
  }
  return smallest;
}

template <bool kGap>
int CoarseKeepEeT(const CoarseDop* dops, const Edge* edges, const EdgeEdgePair* pairs, std::size_t n,
                  std::uint8_t* keep) {
  int smallest = CoarseDop::kClamp;
  if constexpr (kWholeDop) {
    const hn::CappedTag<std::int16_t, 2 * CoarseDop::kLanes> d;
    const auto zero = hn::Zero(d);
    const auto whole = [&](Index v) { return hn::Load(d, dops[v].min); };
    for (std::size_t i = 0; i < n; ++i) {
      const Edge &ea = edges[pairs[i].a], &eb = edges[pairs[i].b];
      const auto a = hn::Min(whole(ea[0]), whole(ea[1])), b = hn::Min(whole(eb[0]), whole(eb[1]));
      const auto sum = hn::SaturatedAdd(a, SwapHalves(d, b));
      keep[i] = hn::AllFalse(d, hn::Gt(sum, zero));
      if constexpr (kGap) smallest = std::min(smallest, int(hn::GetLane(hn::MaxOfLanes(d, sum))));
    }
    return smallest;
  }
  const hn::CappedTag<std::int16_t, CoarseDop::kLanes> d;
  const std::size_t N = hn::Lanes(d);
  const auto zero = hn::Zero(d);
  for (std::size_t i = 0; i < n; ++i) {
    const Edge &ea = edges[pairs[i].a], &eb = edges[pairs[i].b];
    const CoarseDop &a0 = dops[ea[0]], &a1 = dops[ea[1]], &b0 = dops[eb[0]], &b1 = dops[eb[1]];
    auto largest = hn::Set(d, std::int16_t(-CoarseDop::kClamp));
    for (std::size_t k = 0; k < std::size_t(CoarseDop::kLanes); k += N) {
      const auto alo = hn::Min(hn::Load(d, a0.min + k), hn::Load(d, a1.min + k));
      const auto aneg_hi = hn::Min(hn::Load(d, a0.neg_max + k), hn::Load(d, a1.neg_max + k));
      const auto blo = hn::Min(hn::Load(d, b0.min + k), hn::Load(d, b1.min + k));
      const auto bneg_hi = hn::Min(hn::Load(d, b0.neg_max + k), hn::Load(d, b1.neg_max + k));
      largest = hn::Max(largest, hn::Max(hn::SaturatedAdd(alo, bneg_hi), hn::SaturatedAdd(blo, aneg_hi)));
    }
    keep[i] = hn::AllFalse(d, hn::Gt(largest, zero));
    if constexpr (kGap) smallest = std::min(smallest, int(hn::GetLane(hn::MaxOfLanes(d, largest))));
  }
  return smallest;
}

void CoarseKeepVf(const CoarseDop* dops, const Face* faces, const VertexFacePair* pairs, std::size_t n,
                  std::uint8_t* keep) {
  CoarseKeepVfT<false>(dops, faces, pairs, n, keep);
}
void CoarseKeepEe(const CoarseDop* dops, const Edge* edges, const EdgeEdgePair* pairs, std::size_t n,
                  std::uint8_t* keep) {
  CoarseKeepEeT<false>(dops, edges, pairs, n, keep);
}
int CoarseKeepGapVf(const CoarseDop* dops, const Face* faces, const VertexFacePair* pairs, std::size_t n,
                    std::uint8_t* keep) {
  return CoarseKeepVfT<true>(dops, faces, pairs, n, keep);
}
int CoarseKeepGapEe(const CoarseDop* dops, const Edge* edges, const EdgeEdgePair* pairs, std::size_t n,
                    std::uint8_t* keep) {
  return CoarseKeepEeT<true>(dops, edges, pairs, n, keep);
}

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ccdlab {

HWY_EXPORT(KdopKeepVf);
HWY_EXPORT(KdopKeepEe);
HWY_EXPORT(CoarseKeepVf);
HWY_EXPORT(CoarseKeepEe);
HWY_EXPORT(CoarseKeepGapVf);
HWY_EXPORT(CoarseKeepGapEe);

void vf_keep(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const VertexFacePair> pairs, std::uint8_t* keep) {
  HWY_DYNAMIC_DISPATCH(KdopKeepVf)(bounds.dops(), mesh.faces().data(), pairs.data(), pairs.size(), keep);
}

void ee_keep(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const EdgeEdgePair> pairs, std::uint8_t* keep) {
  HWY_DYNAMIC_DISPATCH(KdopKeepEe)(bounds.dops(), mesh.edges().data(), pairs.data(), pairs.size(), keep);
}
void vf_keep_coarse(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const VertexFacePair> pairs,
                    std::uint8_t* keep) {
  HWY_DYNAMIC_DISPATCH(CoarseKeepVf)(bounds.coarse_dops(), mesh.faces().data(), pairs.data(), pairs.size(), keep);
}

void ee_keep_coarse(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const EdgeEdgePair> pairs,
                    std::uint8_t* keep) {
  HWY_DYNAMIC_DISPATCH(CoarseKeepEe)(bounds.coarse_dops(), mesh.edges().data(), pairs.data(), pairs.size(), keep);
}

int vf_keep_coarse_gap(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const VertexFacePair> pairs,
                       std::uint8_t* keep) {
  return HWY_DYNAMIC_DISPATCH(CoarseKeepGapVf)(bounds.coarse_dops(), mesh.faces().data(), pairs.data(), pairs.size(), keep);
}

int ee_keep_coarse_gap(const FeatureBounds& bounds, const TriMesh& mesh, std::span<const EdgeEdgePair> pairs,
                       std::uint8_t* keep) {
  return HWY_DYNAMIC_DISPATCH(CoarseKeepGapEe)(bounds.coarse_dops(), mesh.edges().data(), pairs.data(), pairs.size(), keep);
}

}  // namespace ccdlab
#endif  // HWY_ONCE

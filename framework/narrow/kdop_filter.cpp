// Stage 1 over a batch in SIMD: one vertex 26-DOP is 16 + 16 floats, so a pair is 2 (AVX-512) to 8 (128-bit)
// loads per vertex. Highway compiles this file once per target and picks one at run time.
#include "framework/narrow/feature_bounds.hpp"

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

}  // namespace HWY_NAMESPACE
}  // namespace ccdlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ccdlab {

HWY_EXPORT(KdopKeepVf);
HWY_EXPORT(KdopKeepEe);

void FeatureBounds::vf_keep(const TriMesh& mesh, std::span<const VertexFacePair> pairs, std::uint8_t* keep) const {
  HWY_DYNAMIC_DISPATCH(KdopKeepVf)(vertex_.data(), mesh.faces().data(), pairs.data(), pairs.size(), keep);
}

void FeatureBounds::ee_keep(const TriMesh& mesh, std::span<const EdgeEdgePair> pairs, std::uint8_t* keep) const {
  HWY_DYNAMIC_DISPATCH(KdopKeepEe)(vertex_.data(), mesh.edges().data(), pairs.data(), pairs.size(), keep);
}

}  // namespace ccdlab
#endif  // HWY_ONCE

#include "framework/narrow/feature_bounds.hpp"

namespace ccdlab {

void FeatureBounds::update(const Positions& x_t0, const Positions& x_t1, double thickness, int threads,
                           PhaseTrace& trace) {
  vertex_.resize(x_t0.size());
  parallel_chunks(x_t0.size(), 4096, threads, trace, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t v = b; v < e; ++v) {
      KDop<26> dop;
      dop.grow(std::array<const Vec3*, 2>{&x_t0[v], &x_t1[v]});
      dop.inflate(0.5 * thickness);
      PaddedDop& out = vertex_[v];
      for (int i = 0; i < PaddedDop::kLanes; ++i) {
        out.min[i] = i < PaddedDop::kAxes ? dop.min(i) : 0.0f;
        out.max[i] = i < PaddedDop::kAxes ? dop.max(i) : 0.0f;
      }
    }
  });
}

}  // namespace ccdlab

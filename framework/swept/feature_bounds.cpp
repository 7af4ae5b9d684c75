#include "framework/swept/feature_bounds.hpp"

#include <cmath>

namespace ccdlab {
namespace {

constexpr std::size_t kChunk = 4096;

}  // namespace

void FeatureBounds::update(const Positions& x_t0, const Positions& x_t1, double thickness, int threads,
                           PhaseTrace& trace) {
  const std::size_t n = x_t0.size();
  vertex_.resize(n);
  points_.resize(n);
  // The float 26-DOPs, and the range of every axis per chunk for the coarse grid; the frames interleaved.
  std::vector<AxisRange> chunk_range((n + kChunk - 1) / kChunk);
  parallel_chunks(n, kChunk, threads, trace, [&](std::size_t b, std::size_t e, int) {
    detail::swept_vertex_dops(x_t0.data() + b, x_t1.data() + b, e - b, 0.5 * thickness, vertex_.data() + b);
    interleave_frames(x_t0.data() + b, x_t1.data() + b, e - b, points_.data() + b);
    AxisRange r;
    for (std::size_t v = b; v < e; ++v) r.include(vertex_[v].min, vertex_[v].max);
    chunk_range[b / kChunk] = r;
  });
  AxisRange all;
  for (const AxisRange& r : chunk_range) all.include(r.lo, r.hi);
  // x, y, z are the 26-DOP's first three axes: their ranges hold every vertex of both frames. (NaN or Inf make it
  // non-finite, and whoever reads it then culls nothing by it.)
  extent_ = 0;
  for (int i = 0; i < 3; ++i) extent_ += n ? double(all.hi[i]) - double(all.lo[i]) : 0.0;
  if (n && !std::isfinite(extent_)) extent_ = std::numeric_limits<double>::infinity();
  update_coarse(all, threads, trace);
}

void FeatureBounds::update_coarse(const AxisRange& range, int threads, PhaseTrace& trace) {
  // Per lane: the grid's origin, scale and offset. Padding lanes map their zeros to 0. An empty, flat or
  // non-finite range has scale 0: every finite bound maps to one grid value (±∞ to a clamp, through NaN), so
  // that axis separates nothing.
  alignas(64) float lo[CoarseDop::kLanes] = {}, scale[CoarseDop::kLanes] = {}, offset[CoarseDop::kLanes] = {};
  for (int i = 0; i < PaddedDop::kAxes; ++i) {
    const double extent = double(range.hi[i]) - double(range.lo[i]);
    const bool usable = std::isfinite(extent) && extent > 0;
    lo[i] = usable ? range.lo[i] : 0.0f;
    scale[i] = usable ? float(CoarseDop::kSteps / extent) : 0.0f;
    offset[i] = float(CoarseDop::kOffset);
  }
  coarse_step_ = HUGE_VAL;
  for (int i = 0; i < PaddedDop::kAxes; ++i) {
    const auto& d = KDop<26>::axes[std::size_t(i)];
    if (scale[i] > 0) coarse_step_ = std::min(coarse_step_, 1 / (double(scale[i]) * std::sqrt(double(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]))));
  }
  if (coarse_step_ == HUGE_VAL) coarse_step_ = 0;
  coarse_.resize(vertex_.size());
  parallel_chunks(vertex_.size(), kChunk, threads, trace, [&](std::size_t b, std::size_t e, int) {
    detail::quantize_dops(vertex_.data() + b, coarse_.data() + b, e - b, lo, scale, offset);
  });
}

}  // namespace ccdlab

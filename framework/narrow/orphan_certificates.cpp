#include "framework/narrow/orphan_certificates.hpp"

#include <algorithm>
#include <bit>
#include <limits>

namespace ccdlab {

OrphanCertificates::OrphanCertificates(const OrphanSet& orphans, const TriMesh& mesh) {
  const std::size_t nvf = orphans.vf.size(), n = nvf + orphans.ee.size();
  range_.assign((n + kBlock - 1) / kBlock, Range{std::numeric_limits<Index>::max(), 0});
  const auto read = [&](std::size_t pair, Index v) {
    Range& r = range_[block_of(pair)];
    r.lo = std::min(r.lo, v), r.hi = std::max(r.hi, v);
  };
  for (std::size_t i = 0; i < nvf; ++i) {
    const VertexFacePair& p = orphans.vf[i];
    read(i, p.v);
    for (Index v : mesh.face(p.f)) read(i, v);
  }
  for (std::size_t i = nvf; i < n; ++i) {
    const EdgeEdgePair& p = orphans.ee[i - nvf];
    for (Index v : mesh.edge(p.a)) read(i, v);
    for (Index v : mesh.edge(p.b)) read(i, v);
  }
  budget_.assign(range_.size(), -HUGE_VAL);
}

void OrphanCertificates::begin_step(const Positions& x_t0, const Positions& x_t1, double thickness) {
  if (range_.empty()) return;
  const std::size_t n = x_t0.size();
  could_skip_ = last_t0_.size() == n && last_t1_.size() == n && x_t1.size() == n;
  if (!could_skip_) {  // the first step: nothing measured
    std::fill(budget_.begin(), budget_.end(), -HUGE_VAL);
  } else {
    // Each vertex's swept 26-DOP bounds the set of its two positions, in either order: δ pairs this step's ends
    // with the last step's in the order that moves them least overall (a step replayed backwards: not at all).
    double straight = 0, crossed = 0;
    for (std::size_t v = 0; v < n; ++v) {
      straight += (x_t0[v] - last_t0_[v]).squaredNorm() + (x_t1[v] - last_t1_[v]).squaredNorm();
      crossed += (x_t0[v] - last_t1_[v]).squaredNorm() + (x_t1[v] - last_t0_[v]).squaredNorm();
    }
    const Positions& from_t0 = crossed < straight ? last_t1_ : last_t0_;
    const Positions& from_t1 = crossed < straight ? last_t0_ : last_t1_;
    // Per bucket, the box of δ (both ends of the step); then runs of 2, 4, … buckets.
    const std::size_t buckets = (n + kBucket - 1) / kBucket;
    runs_.resize(std::size_t(std::bit_width(buckets)));
    runs_[0].resize(buckets);
    double largest = 0;
    bool finite = true;
    for (std::size_t b = 0; b < buckets; ++b) {
      Box box{Vec3::Constant(HUGE_VAL), Vec3::Constant(-HUGE_VAL)};
      for (std::size_t v = b * kBucket; v < std::min(n, (b + 1) * kBucket); ++v) {
        for (const Vec3& d : {Vec3(x_t0[v] - from_t0[v]), Vec3(x_t1[v] - from_t1[v])}) {
          box.lo = box.lo.cwiseMin(d), box.hi = box.hi.cwiseMax(d);
          finite &= d.allFinite();
        }
        largest = std::max({largest, x_t0[v].cwiseAbs().maxCoeff(), x_t1[v].cwiseAbs().maxCoeff()});
      }
      runs_[0][b] = box;
    }
    for (std::size_t j = 1; j < runs_.size(); ++j) {
      const std::size_t half = std::size_t(1) << (j - 1);
      runs_[j].resize(buckets - 2 * half + 1);
      for (std::size_t b = 0; b < runs_[j].size(); ++b) {
        const Box &p = runs_[j - 1][b], &q = runs_[j - 1][b + half];
        runs_[j][b] = {p.lo.cwiseMin(q.lo), p.hi.cwiseMax(q.hi)};
      }
    }
    margin_ = kMargin * (largest + thickness);
    for (std::size_t k = 0; k < range_.size(); ++k) budget_[k] = finite ? budget_[k] - motion(range_[k]) : -HUGE_VAL;
  }
  last_t0_ = x_t0, last_t1_ = x_t1;
}

double OrphanCertificates::motion(const Range& r) const {
  const std::size_t first = std::size_t(r.lo) / kBucket, last = std::size_t(r.hi) / kBucket;
  const std::size_t j = std::size_t(std::bit_width(last - first + 1)) - 1;  // 2^j ≤ buckets < 2^(j+1)
  const Box &p = runs_[j][first], &q = runs_[j][last + 1 - (std::size_t(1) << j)];
  return (p.hi.cwiseMax(q.hi) - p.lo.cwiseMin(q.lo)).norm();
}

}  // namespace ccdlab

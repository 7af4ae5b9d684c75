#pragma once
// The orphan set priced by what moves. The orphans (representatives.hpp) are fixed by the topology and tested
// every step, yet nearly all of them are pairs of features a few edges apart on a surface that bends little
// from one step to the next: stage 1 culls them step after step. A certificate lets a step skip them until the
// surface around them has moved enough to matter.
//
// The orphan set (VF pairs, then EE pairs) is cut into blocks of kBlock pairs. When a block is tested, stage 1's
// coarse test also measures each pair's largest separation on an axis of the 26-DOP, k grid steps, which the
// features keep at least as (k − 2)·coarse_step() along its unit direction (kdop_filter.hpp, feature_bounds.hpp);
// the smallest over the block is its budget (≤ 0 when some pair overlaps). Every later step takes
// off the budget how far the block's vertices can have moved relative to one another since the step before:
// with δ_v = the change of vertex v's position at the step's start and at its end (two vectors per vertex), a
// support of a feature's swept 26-DOP along a unit direction u moves by at most max u·δ over its vertices, so a
// gap shrinks by at most (max − min of u·δ over the block's vertices) ≤ the diagonal of the box of their δ.
// While the budget stays above a rounding margin, every pair of the block is still apart on its axis, stage 1
// would cull it, and the block is skipped: the contacts are the same, and a step pays for the blocks that moved.
// A translation spends no budget (δ is the same for every vertex); bending and turning do. The two positions of a
// vertex may be paired with the last step's in either order (its swept 26-DOP bounds them as a set): begin_step
// takes the order that moves the mesh least, so a step replayed backwards spends nothing.
//
// The box of a block's δ is taken over the range of vertex ids its pairs read, from per-bucket boxes (kBucket
// consecutive ids) through a table of power-of-two runs of buckets: O(1) per block. Meshes numbered in a
// spatially coherent order (grids, scans, most generators) give tight ranges; a scattered numbering only
// makes the boxes larger and the skips rarer, never wrong.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "framework/geometry/vec.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/primitive/feature_pairs.hpp"

namespace ccdlab {

class OrphanCertificates {
 public:
  static constexpr std::size_t kBlock = 64;    ///< pairs per block (the orphan loop's chunks hold whole blocks)
  static constexpr std::size_t kBucket = 64;   ///< vertex ids per bucket of the motion boxes
  static constexpr double kMargin = 1e-4;      ///< relative to the largest coordinate plus the thickness: the float
                                               ///< 26-DOPs' own rounding, with room to spare

  // Which steps use them is the rules' choice (rules/stage_rules.hpp): they cost a motion pass and the gaps'
  // measuring, and save only where the mesh bends little (a twisting rod spends every budget at once).

  /// Blocks of `orphans` (VF first, then EE) with the vertex ids each reads; every budget starts spent.
  OrphanCertificates(const OrphanSet& orphans, const TriMesh& mesh);

  [[nodiscard]] std::size_t blocks() const { return budget_.size(); }
  /// Block k holds the pairs [k·kBlock, (k + 1)·kBlock) of the set (clipped to its size).
  [[nodiscard]] static std::size_t block_of(std::size_t pair) { return pair / kBlock; }

  /// Once per step, before the orphan loop: takes the motion since the last step's frames off every budget, then
  /// keeps these frames. `thickness`: the tester's (the 26-DOPs are inflated by half of it).
  void begin_step(const Positions& x_t0, const Positions& x_t1, double thickness);
  /// A step whose orphan loop does not use the certificates: they lapse, and the step after measures afresh.
  void forget() {
    could_skip_ = false;
    last_t0_.clear(), last_t1_.clear();
    std::fill(budget_.begin(), budget_.end(), -HUGE_VAL);
  }
  /// Whether every pair of block k is still apart (stage 1 would cull each one): the block may be skipped.
  [[nodiscard]] bool holds(std::size_t k) const { return budget_[k] > margin_; }
  /// Block k was tested in this step and every pair of it keeps a distance of at least `gap` along some unit
  /// axis (≤ 0: not every pair). Written only by the one chunk of the orphan loop that holds the block.
  void certify(std::size_t k, double gap) const { budget_[k] = gap; }

 private:
  struct Range {
    Index lo, hi;  ///< the smallest and largest vertex id the block's pairs read
  };
  struct Box {
    Vec3 lo, hi;
  };
  [[nodiscard]] double motion(const Range& r) const;  ///< diagonal of the δ box over ids [lo, hi]

  std::vector<Range> range_;
  mutable std::vector<double> budget_;  // see certify()
  double margin_ = 0;
  bool could_skip_ = false;     ///< this step has budgets from the last one (begin_step)
  Positions last_t0_, last_t1_;         ///< the last step's frames (empty before the first)
  std::vector<std::vector<Box>> runs_;  ///< runs_[j][b]: the δ box of buckets [b, b + 2^j)
};

}  // namespace ccdlab

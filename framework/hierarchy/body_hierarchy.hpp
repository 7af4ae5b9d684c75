#pragma once
// Stage 2 of a step (design.md): one body's bounding volume hierarchy across the steps of a run.
//   build            first step: top-down over the faces' swept boxes (the HierarchyBuilder), then the
//                    restructuring units (disjoint sub-trees, independent of the thread count)
//   refit            every step: the leaves' k-DOPs cut from the swept volumes (framework/swept/), then
//                    bottom-up along the refit plan
//   restructure      when on: rebuilds the sub-trees whose quality degraded (each one a new topology version)
//   follow_topology  whenever the topology version changed (first step, restructuring): the 4-wide view and
//                    the normal-cone patches are cut again. The one check every per-topology structure hangs on.
//   refit_wide       width 4: every wide record's bounds, from the binary volumes
//   update_cones     normal cones on: which self tests of this step may be skipped
// The traversal reads bvh(), node_bvs(), wide_layout(), node_wide() and skip_root() through pointers that stay
// valid for the hierarchy's lifetime.
#include <memory>
#include <optional>
#include <vector>

#include "framework/hierarchy/bvh.hpp"
#include "framework/hierarchy/normal_cones.hpp"
#include "framework/hierarchy/pass_side.hpp"
#include "framework/swept/feature_bounds.hpp"

namespace ccdlab {

class BodyHierarchy {
 public:
  /// What the hierarchy takes of the pipeline's settings (pipeline_settings.hpp, where their defaults are).
  struct Settings {
    int k;
    int width;
    int threads;
    double restructure_threshold;  ///< 0 = off
    bool normal_cones;             ///< cut cone patches (self-colliding bodies only)
    bool end_boxes;                ///< keep every node's EndBoxes (and, width 4, the records' WideEnds)
  };
  /// `faces`: the body's faces; `self_collides`: whether its self pass runs (normal cones serve only that pass).
  BodyHierarchy(const TriMesh& mesh, std::vector<Index> faces, bool self_collides, const Settings& settings);

  /// Top-down build over the faces' boxes swept over the step; a new topology.
  void build(const Positions& x_t0, const Positions& x_t1, const HierarchyBuilder& builder, PhaseTrace& trace);
  /// Every leaf's swept k-DOP (from `swept`), then every inner node's, bottom-up (refit plan); with an end reach
  /// (end boxes kept and tested this step), their EndBoxes too, inflated by end_reach / 2 (CcdPipeline::end_reach).
  void refit(const FeatureBounds& swept, std::optional<double> end_reach, PhaseTrace& trace);
  /// Rebuilds the degraded sub-trees (and, with an end reach, their end boxes); returns how many were rebuilt.
  std::uint64_t restructure(const Positions& x_t0, const Positions& x_t1, const FeatureBounds& swept,
                            std::optional<double> end_reach, const HierarchyBuilder& builder, PhaseTrace& trace);
  /// Whether the topology changed since follow_topology last ran (then call it before refit_wide and update_cones).
  [[nodiscard]] bool topology_changed() const { return followed_version_ != bvh_.version; }
  /// Cuts the 4-wide layout (width 4) and the normal-cone patches (when on) from the current topology.
  void follow_topology();
  /// Every wide record's bounds from the binary volumes (and their lanes, after follow_topology cut them again).
  /// `ends`: also the records' WideEnds, from the nodes' end boxes (refit with an end reach this step).
  void refit_wide(bool ends, PhaseTrace& trace);
  /// This step's normal-cone culling (skip_root); returns the number of topmost skipped nodes.
  std::uint64_t update_cones(const Positions& x_t0, const Positions& x_t1, PhaseTrace& trace);
  /// Writes, for each of the body's faces, the skipped patch (BVH node) holding it this step, or −1.
  void mark_skipped_patches(std::vector<Index>& face_patch) const;

  [[nodiscard]] const std::vector<Index>& faces() const { return faces_; }
  [[nodiscard]] const BvhTopology& bvh() const { return bvh_; }
  [[nodiscard]] const AnyBvs& node_bvs() const { return node_bvs_; }
  [[nodiscard]] const WideLayout& wide_layout() const { return wide_layout_; }
  [[nodiscard]] const AnyWideBvs& node_wide() const { return node_wide_; }
  /// With end boxes on: every node's EndBoxes, and (width 4) every record's lanes' (WideEnds); empty otherwise.
  [[nodiscard]] const BvArray<EndBoxes>& node_ends() const { return node_ends_; }
  [[nodiscard]] const WideEndsArray& wide_ends() const { return wide_ends_; }
  /// The hierarchy as a traversal pass reads it: the binary volumes, with the wide view (`wide`) and the end
  /// boxes (`ends`) where the pipeline uses them. Its pointers stay valid for the hierarchy's lifetime.
  [[nodiscard]] PassSide side(bool wide, bool ends) const {
    PassSide s{&bvh_, &node_bvs_};
    if (wide) s.wide_layout = &wide_layout_, s.wide = &node_wide_;
    if (ends) s.ends = &node_ends_, s.wide_ends = wide ? &wide_ends_ : nullptr;
    return s;
  }
  [[nodiscard]] const std::vector<Index>& skip_root() const { return skip_root_; }
  [[nodiscard]] bool has_cones() const { return cones_ != nullptr; }
  [[nodiscard]] std::uint64_t contour_edge_tests() const { return cones_ ? cones_->contour_edge_tests() : 0; }
  [[nodiscard]] std::size_t memory_bytes() const;

 private:
  const TriMesh& mesh_;
  std::vector<Index> faces_;
  bool self_collides_;
  Settings settings_;
  BvhTopology bvh_;
  AnyBvs node_bvs_;         ///< index = node; a leaf holds its face's swept volume
  WideLayout wide_layout_;  ///< width 4
  AnyWideBvs node_wide_;    ///< width 4: refit from node_bvs_ after the binary refit (and restructuring)
  BvArray<EndBoxes> node_ends_;  ///< per node: its box at each end of the step
  WideEndsArray wide_ends_;      ///< width 4: per record, its lanes' node_ends_
  bool wide_lanes_stale_ = false;  ///< follow_topology cut the layout: refit_wide copies the records' lanes again
  std::uint64_t followed_version_ = ~0ull;
  // Adaptive restructuring units: disjoint sub-trees of ≤ max(64, n/64) leaves, and their reference quality.
  std::vector<Index> restructure_roots_;
  std::vector<double> quality_ref_;
  std::unique_ptr<NormalConeCuller> cones_;  ///< normal cones on and self-colliding
  std::vector<Index> skip_root_;             ///< this step's culling, read by the self pass
};

}  // namespace ccdlab

#pragma once
// CcdPipeline: one CCD step, frame i → i+1, wired from the strategies chosen in the config (design.md). Its
// stages, each in its own home, in data-flow order:
//   1 swept volumes      every vertex's 26-DOP over the step (framework/swept/), read by stages 2 and 4
//   2 body hierarchies   built once, refit, restructured, wide view, normal cones (body_hierarchy.hpp)
//   3 traversal          the scheduler over every BVTT pass → candidate face pairs (traversal_driver.hpp)
//   4 narrow phase       candidates and orphans → feature pairs → culling → tests, per thread (narrow_driver.hpp)
//   5 sorted contacts
// Only the passes the bodies ask for run: no self pass without self-collision, no pair pass without a
// second body. Every phase is timed once (phase_clock.hpp).
#include <memory>
#include <string_view>
#include <vector>

#include "framework/narrow/narrow_phase.hpp"
#include "framework/pipeline/bodies.hpp"
#include "framework/pipeline/body_hierarchy.hpp"
#include "framework/pipeline/memory_budget.hpp"
#include "framework/pipeline/narrow_driver.hpp"
#include "framework/pipeline/step_result.hpp"
#include "framework/swept/feature_bounds.hpp"
#include "framework/pipeline/traversal_driver.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

/// bv.end_boxes (framework/swept/end_boxes.hpp): test the nodes' boxes at both ends of the step in every
/// step (`on`), never (`off`), or in the steps where they pay (`automatic`, YAML `auto`: CcdPipeline's rule).
enum class EndBoxMode { off, on, automatic };
[[nodiscard]] std::string_view to_string(EndBoxMode m);
/// true / on, false / off, or auto; throws Error naming the field otherwise.
[[nodiscard]] EndBoxMode parse_end_box_mode(std::string_view name);

struct PipelineStrategies {
  int k = 18;  ///< k-DOP: 6, 14, 18 or 26
  int width = kDefaultBvhWidth;  ///< BVH width the traversal reads: 2 (binary) or 4 (framework/hierarchy/wide_bvh.hpp)
  int threads = 1;  ///< OpenMP threads for every stage
  /// The thread count the BVTT is split for (phc and static cut c·N tasks); 0 = `threads`. `ccdlab bench` runs
  /// 1 thread with split_threads = N to record the tasks N cores would get, so the simulator replays them.
  int split_threads = 0;
  /// Adaptive restructuring: rebuild a sub-tree when its quality (Σ sizes of inner nodes ÷ size of its root)
  /// exceeds this × its value at the last (re)build. 0 = off.
  double restructure_threshold = 0;
  /// Continuous normal-cone culling of self tests (framework/traversal/normal_cones.hpp); thickness 0 only.
  bool normal_cones = false;
  /// End boxes (framework/swept/end_boxes.hpp): the traversal also drops node pairs apart on x, y or z at both
  /// ends of the step. Needs the tester's reach (PrimitiveTester::cull_reach); off for a tester without one.
  EndBoxMode end_boxes = EndBoxMode::automatic;
  /// Bytes the process may hold resident during a step (0 = no limit): above the predicted need, a step streams
  /// its candidates to the narrow phase slice by slice (framework/pipeline/memory_budget.hpp).
  std::uint64_t memory_limit = 0;
  /// Stream every step in (about) this many slices per pass, whatever the memory: to test streaming and to
  /// measure its cost. 0 = only when the memory limit asks for it.
  std::size_t stream_slices = 0;
  /// How the narrow phase runs: scalar or batched, and its representative rule (framework/narrow/).
  NarrowOptions narrow;
  std::unique_ptr<HierarchyBuilder> builder;
  std::unique_ptr<TraversalScheduler> scheduler;
  std::unique_ptr<PrimitiveTester> tester;

  /// The one check of a pipeline's configuration, whoever made it (YAML, the CLI, the Python module, a scene's
  /// ccd_contact effect): throws Error naming the field (YAML checks the same earlier, with its line).
  void validate() const;
};

class CcdPipeline {
 public:
  /// `mesh` must outlive the pipeline. Builds the representative rule's orphan set (once per topology).
  CcdPipeline(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies);
  ~CcdPipeline();

  /// Runs one step between two frames of the mesh (same vertex count as the topology).
  StepResult step(const Positions& x_t0, const Positions& x_t1);
  /// The earliest time of contact of the step, 1.0 when there is none: the minimum over step()'s contacts,
  /// found without testing the pairs that cannot beat the best time found so far (earliest_cut.hpp). `result`,
  /// when given, receives the step's counters and timings; its contacts are those tested before the cut.
  double earliest_toi(const Positions& x_t0, const Positions& x_t1, StepResult* result = nullptr);

  /// Tests of the ownership rule: record every feature pair considered into StepResult::tested_*.
  void set_record_tested_pairs(bool on) { narrow_driver_.record_tested(on); }

  [[nodiscard]] const TriMesh& mesh() const { return mesh_; }
  [[nodiscard]] const CollisionRules& rules() const { return rules_; }
  [[nodiscard]] const Representatives& representatives() const { return narrow_.representatives(); }
  [[nodiscard]] const OrphanSet& orphans() const { return narrow_.representatives().orphans(); }
  [[nodiscard]] const PipelineStrategies& strategies() const { return strategies_; }
  /// Keep every candidate of a step for last_candidates() (tests, the quality meter). Off by default: the
  /// narrow phase takes the candidates while the traversal finds them, and no list holds them all.
  void keep_candidates(bool on) { traversal_.keep_candidates(on); }
  /// How many candidates a thread gathers before the narrow phase takes them (TraversalOutput::hand_over).
  void set_hand_over_pairs(std::size_t pairs) { traversal_.set_hand_over_pairs(pairs); }
  /// Candidate face pairs of the last step (unsorted) and their BV test count; throws Error unless
  /// keep_candidates(true) was called before the step.
  [[nodiscard]] const TraversalOutput& last_candidates() const;
  /// BVH of body b (empty before the first step).
  [[nodiscard]] const BvhTopology& bvh(int body) const { return bodies_[body].bvh(); }
  /// The volumes of body b's BVH nodes, refit in the last step (index = node; a leaf holds its face's swept
  /// volume, which the pipeline stores nowhere else).
  [[nodiscard]] const AnyBvs& node_bvs(int body) const { return bodies_[body].node_bvs(); }
  /// The traversal passes (self passes first, then body pairs), whose ids a stateful scheduler keys on.
  [[nodiscard]] const std::vector<TraversalPass>& passes() const { return traversal_.passes(); }
  /// Bytes of the pipeline's persistent data (topology, ownership, orphans, BVHs).
  [[nodiscard]] std::size_t memory_bytes() const;

  /// Whether the hierarchies keep end boxes (framework/swept/end_boxes.hpp): bv.end_boxes is not off, and
  /// the tester has a reach.
  [[nodiscard]] bool end_boxes_kept() const;
  /// Whether the last step's traversal tested them (always when `on` and kept; by the rule when `automatic`).
  [[nodiscard]] bool end_boxes_in_last_step() const { return ends_in_step_; }

 private:
  /// Whether this step tests end boxes: bv.end_boxes, and for `automatic` the rule from the last steps' counts.
  [[nodiscard]] bool end_boxes_pay() const;
  /// The distance beyond which the tester reports no pair, for every pair of this step (its reach at the scene's
  /// size): end boxes are inflated by half of it.
  [[nodiscard]] double end_reach() const;

  const TriMesh& mesh_;
  CollisionRules rules_;
  PipelineStrategies strategies_;
  FeatureBounds swept_;  ///< stage 1, read by the hierarchies and the narrow phase
  NarrowPhase narrow_;
  std::vector<BodyHierarchy> bodies_;
  std::vector<Index> face_patch_;  ///< normal cones: the skipped patch (BVH node) holding each face this step, or −1
  TraversalDriver traversal_;
  NarrowDriver narrow_driver_;
  ContactSortScratch sort_scratch_;  ///< sort_contacts' buffers, kept across steps
  bool built_ = false;
  // The end boxes' rule (end_boxes_pay): steps run, the candidates of the last step run without them and of the
  // last run with them, and whether this (or the last) step tests them.
  std::uint64_t steps_ = 0;
  std::uint64_t candidates_without_ends_ = 0;
  std::uint64_t candidates_with_ends_ = 0;
  bool ends_in_step_ = false;
};

/// Bytes a pipeline over `mesh` will add before its first traversal: the BVHs and their volumes (the leaves' are
/// the faces' swept volumes; and their 4-wide view for width 4), the feature bounds, the ownership, the orphan set
/// and the two frames of a step. Checked against memory_limit when a pipeline is made, so that a run too large for
/// the machine is refused before it starts.
std::uint64_t estimate_pipeline_bytes(const TriMesh& mesh, int k, int width, std::size_t orphan_pairs,
                                      bool end_boxes = false);

}  // namespace ccdlab

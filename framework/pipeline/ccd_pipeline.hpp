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
#include "framework/hierarchy/body_hierarchy.hpp"
#include "framework/pipeline/memory_budget.hpp"
#include "framework/pipeline/narrow_driver.hpp"
#include "framework/pipeline/pipeline_settings.hpp"
#include "framework/pipeline/step_result.hpp"
#include "framework/pipeline/step_watch.hpp"
#include "framework/swept/feature_bounds.hpp"
#include "framework/pipeline/traversal_driver.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

/// The settings (pipeline_settings.hpp) and the strategies made from the names a configuration chose.
struct PipelineStrategies : PipelineSettings {
  std::unique_ptr<HierarchyBuilder> builder;
  std::unique_ptr<TraversalScheduler> scheduler;
  std::unique_ptr<PrimitiveTester> tester;

  /// The one check of a pipeline's configuration, whoever made it: the settings (PipelineSettings::validate,
  /// spelled by `name`), then the strategies and what depends on them. Throws Error naming the field.
  void validate(const SettingName& name = {}) const;
};

class CcdPipeline {
 public:
  /// `mesh` must outlive the pipeline. Builds the representative rule's orphan set (once per topology).
  CcdPipeline(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies);
  ~CcdPipeline();

  /// Runs one step between two frames of the mesh (same vertex count as the topology).
  StepResult step(const Positions& x_t0, const Positions& x_t1);
  /// The same into `result`, replacing what it held but keeping its contact list's memory: a loop that passes
  /// one StepResult to every step writes a dense step's contacts into pages already touched, where a fresh list
  /// costs page faults (and the kernel's clearing of them) on every step.
  void step(const Positions& x_t0, const Positions& x_t1, StepResult& result);
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
  /// Reports a long step's progress (candidate pairs tested of those expected) from its workers, at most every
  /// half second once it has run two seconds (framework/pipeline/step_watch.hpp). Empty: none.
  void set_progress(ProgressReport report) { progress_ = std::move(report); }
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
  /// The distance beyond which the tester reports no pair, for every pair of this step (its reach at the scene's
  /// size): end boxes are inflated by half of it.
  [[nodiscard]] double end_reach() const;
  /// Throws Error, before the traversal, when the frames lie beyond the coordinates the pipeline computes reliably
  /// or the step is estimated to find more candidates per triangle than candidate_limit
  /// (framework/pipeline/work_estimate.hpp); hands the estimate to the memory plan. Checked in the first step, and
  /// again in a step where the scene has grown to more than twice its extent at the last check.
  void refuse_exploding_work(const Positions& x_t0, const Positions& x_t1);
  /// Throws Error when the step ran past time_limit or out of the room memory_limit leaves for its contacts (its
  /// workers stopped taking work): `where` the step was.
  void refuse_late_step(const char* where);

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
  StageRules stage_rules_;     ///< which passes that only save work a step runs (framework/narrow/rules/)
  StepPlan plan_;              ///< … this (or the last) step's
  std::uint64_t steps_ = 0;    ///< steps run
  bool ends_in_step_ = false;  ///< whether this (or the last) step tests end boxes
  double estimated_extent_ = -1;  ///< the scene's extent at the last work estimate (−1: none yet)
  double expected_candidates_ = 0;  ///< for the progress report: the estimate, then the last step's count
  StepWatch watch_;
  ProgressReport progress_;
};

}  // namespace ccdlab

#pragma once
// CcdPipeline: one CCD step, frame i → i+1, wired from the strategies chosen in the config (design.md):
//   swept face BVs → BVH refit (built once, on the first step) → BVTT traversal (scheduler) → candidate face
//   pairs → narrow phase (framework/narrow/: feature pairs of candidates and orphans → culling → elementary
//   tests) → sorted contacts.
// Only the passes the bodies ask for run: no self pass without self-collision, no pair pass without a
// second body.
#include <memory>
#include <vector>

#include "framework/hierarchy/bvh.hpp"
#include "framework/pipeline/bodies.hpp"
#include "framework/pipeline/memory_budget.hpp"
#include "framework/pipeline/step_result.hpp"
#include "framework/narrow/narrow_phase.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/traversal/normal_cones.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

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
};

class CcdPipeline {
 public:
  /// `mesh` must outlive the pipeline. Builds the representative rule's orphan set (once per topology).
  CcdPipeline(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies);
  ~CcdPipeline();

  /// Runs one step between two frames of the mesh (same vertex count as the topology).
  StepResult step(const Positions& x_t0, const Positions& x_t1);

  /// Tests of the ownership rule: record every feature pair considered into StepResult::tested_*.
  void set_record_tested_pairs(bool on) { record_tested_ = on; }

  [[nodiscard]] const TriMesh& mesh() const { return mesh_; }
  [[nodiscard]] const CollisionRules& rules() const { return rules_; }
  [[nodiscard]] const Representatives& representatives() const { return narrow_.representatives(); }
  [[nodiscard]] const OrphanSet& orphans() const { return narrow_.representatives().orphans(); }
  [[nodiscard]] const PipelineStrategies& strategies() const { return strategies_; }
  /// Keep every candidate of a step for last_candidates() (tests, the quality meter). Off by default: the
  /// narrow phase takes the candidates while the traversal finds them, and no list holds them all.
  void keep_candidates(bool on) { keep_candidates_ = on; }
  /// How many candidates a thread gathers before the narrow phase takes them (TraversalOutput::hand_over).
  void set_hand_over_pairs(std::size_t pairs) { candidates_.hand_over_pairs = std::max<std::size_t>(1, pairs); }
  /// Candidate face pairs of the last step (unsorted) and their BV test count; throws Error unless
  /// keep_candidates(true) was called before the step.
  [[nodiscard]] const TraversalOutput& last_candidates() const;
  /// BVH of body b (empty before the first step).
  [[nodiscard]] const BvhTopology& bvh(int body) const { return bodies_[body].bvh; }
  /// The volumes of body b's BVH nodes, refit in the last step (index = node; a leaf holds its face's swept
  /// volume, which the pipeline stores nowhere else).
  [[nodiscard]] const AnyBvs& node_bvs(int body) const { return bodies_[body].node_bvs; }
  /// The traversal passes (self passes first, then body pairs), whose ids a stateful scheduler keys on.
  [[nodiscard]] const std::vector<TraversalPass>& passes() const { return passes_; }
  /// Bytes of the pipeline's persistent data (topology, ownership, orphans, BVHs).
  [[nodiscard]] std::size_t memory_bytes() const;

 private:
  struct BodyState {
    std::vector<Index> faces;
    BvhTopology bvh;
    AnyBvs node_bvs;
    WideLayout wide_layout;  ///< width 4: cut again whenever the topology version changes
    AnyWideBvs node_wide;    ///< width 4: refit from node_bvs after the binary refit (and restructuring)
    // Adaptive restructuring units: disjoint sub-trees of ≤ max(64, n/64) leaves, and their reference quality.
    std::vector<Index> restructure_roots;
    std::vector<double> quality_ref;
    std::unique_ptr<NormalConeCuller> cones;  ///< when normal_cones is on (rebuilt with the topology)
    std::vector<Index> skip_root;             ///< this step's culling, read by the self pass
    std::uint64_t cones_version = ~0ull;
  };
  /// Rebuilds the degraded sub-trees of every body; returns how many were rebuilt.
  std::uint64_t restructure(const Positions& x_t0, const Positions& x_t1, PhaseTrace& trace);
  void build_hierarchies(const Positions& x_t0, const Positions& x_t1, PhaseTrace& trace);
  /// Every leaf's swept k-DOP (from its vertices' 26-DOPs), then every inner node's, bottom-up (refit plan).
  void refit_body(BodyState& body, PhaseTrace& trace);
  /// Every wide record's bounds, from the binary volumes; cuts the layout again (and copies the records' lanes)
  /// when the topology changed.
  void refit_wide(BodyState& body, PhaseTrace& trace);
  /// BVTT traversal of every pass and the narrow phase of its candidates: at once, or slice by slice when the
  /// memory plan streams.
  void traverse_and_test(const MemoryPlan& plan, StepResult& result);
  void test_candidates(StepResult& result);
  void test_orphans(StepResult& result);
  /// The narrow phase over `n` items in chunks on every thread: `gather(begin, end, batch)` puts a chunk's
  /// feature pairs into the batch, which is then culled and tested; contacts and counters merged in thread order.
  struct NarrowLocal;
  /// One chunk on one thread: `gather(batch, counters)` fills the batch, which is then culled and tested.
  template <class Gather>
  void narrow_chunk(NarrowLocal& local, Gather&& gather);
  void merge_narrow(const std::vector<PerThread<NarrowLocal>>& local, StepResult& result, PhaseTrace& trace);
  template <class Gather>
  void narrow_in_parallel(std::size_t n, std::size_t chunk, const char* phase, StepResult& result, Gather&& gather);

  const TriMesh& mesh_;
  CollisionRules rules_;
  PipelineStrategies strategies_;
  NarrowPhase narrow_;
  std::vector<BodyState> bodies_;
  std::vector<TraversalPass> passes_;
  std::vector<Index> face_patch_;  ///< normal cones: the skipped patch (BVH node) holding each face this step, or −1
  TraversalOutput candidates_;
  MemoryBudget budget_;
  ContactSortScratch sort_scratch_;  ///< sort_contacts' buffers, kept across steps
  bool built_ = false;
  bool record_tested_ = false;
  bool keep_candidates_ = false;
};

/// Bytes a pipeline over `mesh` will add before its first traversal: the BVHs and their volumes (the leaves' are
/// the faces' swept volumes; and their 4-wide view for width 4), the feature bounds, the ownership, the orphan set
/// and the two frames of a step. Checked against memory_limit when a pipeline is made, so that a run too large for
/// the machine is refused before it starts.
std::uint64_t estimate_pipeline_bytes(const TriMesh& mesh, int k, int width, std::size_t orphan_pairs);

/// An AnyBvs holding an empty vector of KDop<k>; throws Error unless is_kdop_k(k).
AnyBvs make_bvs(int k);
AnyWideBvs make_wide_bvs(int k);

/// Swept k-DOP of every face of the mesh over the step (inflated by thickness / 2), on `threads` threads; the
/// task costs go to `trace` when given. The pipeline writes these volumes into its BVH leaves instead; this
/// face-indexed array is for references (brute force) and benchmarks.
void compute_face_bvs(const TriMesh& mesh, const Positions& x_t0, const Positions& x_t1, double thickness, AnyBvs& out,
                      int threads = 1, PhaseTrace* trace = nullptr);

}  // namespace ccdlab

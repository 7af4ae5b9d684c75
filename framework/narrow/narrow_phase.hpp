#pragma once
// The narrow phase of one step, one stage of its own (design.md): candidate face pairs → feature pairs →
// culling → elementary tests → contacts. Nothing below the pipeline depends on it.
//
//   stage 0  candidate face pairs proven apart as whole triangles (triangle_filter.hpp)  batched mode, testers with a reach
//   gather   the feature pairs each candidate represents (representatives.hpp), or a chunk of orphans
//   stage 1  swept feature 26-DOPs overlap (feature_bounds.hpp, SIMD)     every mode; defines the contact set
//            (batched: a coarse 16-bit copy first, the float test itself after stage 4)
//   stage 2  certified plane test, SIMD over the batch (plane_filter.hpp)   batched mode, testers with a reach
//   stage 3  the plane test and the boxes on halves, then sixteenths of the step (split_filter.hpp)  〃 (the
//            sixteenths where they pay)
//   stage 4  the features' distance on the windows stage 3 left open (proximity_filter.hpp)  〃, where it pays
//   test     the PrimitiveTester on the survivors; hits become contacts
//
// `scalar` mode runs stage 1 and the test pair by pair, as a student would write it; `batched` runs each
// stage over the whole batch. Both report the same contacts (the stages are exact; tests/framework/narrow/).
#include <span>
#include <string_view>
#include <vector>

#include "framework/narrow/earliest_cut.hpp"
#include "framework/narrow/feature_batch.hpp"
#include "framework/swept/feature_bounds.hpp"
#include "framework/narrow/narrow_counters.hpp"
#include "framework/narrow/orphan_certificates.hpp"
#include "framework/narrow/representatives.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/traversal/candidates.hpp"
#include "framework/util/named_values.hpp"

namespace ccdlab {

enum class NarrowMode { scalar, batched };
/// narrow.mode's names: the one list every reader, message and choice list takes.
inline constexpr NamedValues<NarrowMode, 2> kNarrowModes{{{{"scalar", NarrowMode::scalar}, {"batched", NarrowMode::batched}}}};
[[nodiscard]] inline std::string_view to_string(NarrowMode m) { return kNarrowModes.name_of(m); }

/// Whether the candidates carry the fixed rule's orphans (Representatives::append_pairs): in the steps where it
/// pays (batched mode; the rule is in narrow_phase.cpp), or in every step, or never (tests compare the three).
enum class OrphanCarry { when_it_pays, always, never };

/// Whether stage 0 (triangle_filter.hpp) runs in a step: when the narrow phase's counted work per candidate was
/// smaller in the last step that ran it than in the last step that did not (docs/appendix-narrow-phase.md, "End boxes
/// where they pay, stage 0 by the work it saves"). Counted, not timed, and from whole steps, so that every schedule decides alike and every
/// work counter is independent of how the candidates are cut into chunks (schedulers, threads, slices). What a
/// culled candidate saves differs between real steps at the same cull rate — its feature pairs may die in stage 1
/// or reach the costly stage 3 — so no fixed cull rate decides. Stage 0 runs until a step without it has been measured (step 3), then, every
/// kRemeasure steps, one step with it (2 mod 16) and one without (3 mod 16): after the end boxes' measuring
/// steps (0 and 1 mod 16, CcdPipeline), so that both see candidates of the same kind.
class TriangleStageRule {
 public:
  static constexpr std::uint64_t kRemeasure = 16;
  /// Whether stage 0 runs in step `step` (0 = a pipeline's first), given that it can (batched, a tester reach).
  [[nodiscard]] bool runs(std::uint64_t step) const;
  /// A step's merged counters, and whether stage 0 ran in it.
  void record(bool ran, const NarrowCounters& step, std::size_t faces, double test_cost = 1);

 private:
  double work_with_ = -1;     ///< counted work per candidate of the last step with stage 0 (−1: none yet)
  double work_without_ = -1;  ///< … and of the last step without it
};

/// What each stage costs a pair it receives, in ns, from docs/appendix-narrow-phase.md's stage tables and
/// docs/narrow-phase.md's: only the ratios matter to the rules, and they move little between SIMD targets.
struct StageNs {
  static constexpr double gather = 5;       ///< per candidate gathered
  static constexpr double frames = 4;       ///< stage 0's float frames and face boxes, per face
  static constexpr double box_pass = 5;     ///< stage 0, x, y, z from the faces' boxes, per candidate (counted
                                            ///< where skipped too: a bias against stage 0 that small)
  static constexpr double fine_pass = 25;   ///< stage 0, the other axes and normals, per candidate reaching them
  static constexpr double kdop = 3, plane = 10;  ///< stages 1 and 2, per pair received
  static constexpr double halves = 10;      ///< stage 3's halves, per pair stage 3 receives
  static constexpr double sixteenths = 60;  ///< stage 3's sixteenths, per pair they receive
  static constexpr double proximity = 50;   ///< stage 4, per pair received
  static constexpr double test = 150;       ///< per elementary test
};

/// Whether a culling pass that only saves work runs in a step — stage 3's sixteenths, stage 4: when, in the last
/// step that ran it, the tests it saved (pairs removed × a test's cost, PrimitiveTester::relative_test_cost)
/// outweighed what it cost (pairs received × its cost per pair, StageNs). Both passes are exact, so the contacts
/// are the same either way; on a dense step nearly every pair they receive is a contact, and they remove too few
/// to pay (docs/narrow-phase.md, "Contact-dense steps"). Stage 4 works on the windows stage 3 leaves open, and on
/// halves it removes next to nothing: it runs only with the sixteenths, and what it saves counts for them too.
/// A pass runs in the first step and every kRemeasure-th (0 mod 16, so that stage 0's measuring steps 2 and 3
/// see the same passes), and counts from whole steps, as stage 0's rule: every schedule decides alike.
class CullPassRule {
 public:
  static constexpr std::uint64_t kRemeasure = 16;
  /// `ns_per_pair`: the pass's cost per pair it receives (StageNs).
  explicit CullPassRule(double ns_per_pair) : ns_per_pair_(ns_per_pair) {}
  [[nodiscard]] bool runs(std::uint64_t step) const { return step % kRemeasure == 0 || pays_; }
  /// What a run of the pass saved, in ns, net of its own cost.
  [[nodiscard]] double net_saving(std::uint64_t received, std::uint64_t removed, double test_cost) const {
    return StageNs::test * test_cost * double(removed) - ns_per_pair_ * double(received);
  }
  /// A step's counts of the pass — 0 received: it did not run, which changes nothing —, the tester's relative
  /// test cost, and what the later passes that need this one saved (net, ns).
  void record(std::uint64_t received, std::uint64_t removed, double test_cost, double later_saving = 0) {
    if (received > 0) pays_ = net_saving(received, removed, test_cost) + later_saving > 0;
  }

 private:
  double ns_per_pair_;
  bool pays_ = true;
};

/// The narrow phase's work in a step, counted: the pairs each stage received (stage 0's two passes, the gather,
/// stages 1–4, the elementary tests, these × `test_cost`) times that stage's ns per pair (narrow_phase.cpp,
/// StageNs), per candidate the traversal found; 0 without candidates. A mesh of `faces` triangles (stage 0's
/// float frames).
[[nodiscard]] double counted_work_per_candidate(const NarrowCounters& c, std::size_t faces, double test_cost = 1);

struct NarrowOptions {
  NarrowMode mode = NarrowMode::batched;
  RepresentativeRule representative = RepresentativeRule::fixed;  // the faster with batched culling (docs/appendix-narrow-phase.md)
  OrphanCarry carry_orphans = OrphanCarry::when_it_pays;
};

class NarrowPhase {
 public:
  /// `self_collision(face)`: whether the face's body collides with itself (orphan sets exist only there).
  template <class Pred>
  NarrowPhase(const TriMesh& mesh, const PrimitiveTester& tester, NarrowOptions options, Pred&& self_collision)
      : mesh_(mesh), tester_(tester), options_(options), reps_(mesh, options.representative, self_collision),
        certificates_(reps_.orphans(), mesh) {}

  [[nodiscard]] const NarrowOptions& options() const { return options_; }
  [[nodiscard]] const Representatives& representatives() const { return reps_; }
  /// The orphans this step leaves to the pipeline's orphan loop: all of them, or in a step where the
  /// candidates carry the rest (begin_step), those no face pair can carry.
  [[nodiscard]] const OrphanSet& orphans_to_test() const {
    return carry_orphans_ ? reps_.uncarried_orphans() : reps_.orphans();
  }

  /// Sets the two frames of the step and every vertex's swept 26-DOP over it (stage 1's bounds, updated by
  /// the caller for this step with the tester's thickness: the pipeline's swept volumes). All three must
  /// outlive the step; one Positions passed as both frames is a step without motion (the proximity query), whose
  /// stage 3 is skipped. `end_boxes`: the traversal tests end boxes in this step, so stage 0 skips its x, y, z
  /// pass (triangle_filter's box_pass).
  void begin_step(const Positions& x_t0, const Positions& x_t1, const FeatureBounds& bounds, bool end_boxes = false);
  /// The step's merged counters: the work they count, with and without stage 0, decides whether it runs in the
  /// next steps (and its cull rate whether the candidates carry the orphans).
  void end_step(const NarrowCounters& step);

  /// Appends the feature pairs the candidates represent to `scratch.batch`: in a step where stage 0 runs
  /// (batched mode, a tester with a reach, and stage 0 paying: narrow_phase.cpp), those of the candidates it
  /// keeps (`cull = false`: every candidate's, as the ownership tests record them).
  void gather(std::span<const FacePair> candidates, NarrowScratch& scratch, NarrowCounters& c, bool cull = true) const;
  /// Before the orphan loop of a step (after begin_step): the orphan blocks' budgets lose the motion since the
  /// last step (orphan_certificates.hpp).
  void begin_orphans(const Positions& x_t0, const Positions& x_t1);
  /// Appends the pairs [b, e) of orphans_to_test() (VF first, then EE) to an empty `batch`. Batched mode skips
  /// the blocks whose certificate holds (orphan_certificates.hpp), runs stage 1's coarse test on the others where
  /// the set lies, measuring their gaps, and copies only the pairs it keeps, counting them as run() would.
  /// `cull = false` copies them all (tests that record every pair gathered).
  void gather_orphans(std::size_t b, std::size_t e, FeatureBatch& batch, NarrowCounters& c, bool cull = true) const;
  /// Culls and tests the pairs of `batch` (consumed: it holds the survivors afterwards); appends contacts.
  /// `cull = false` skips the culling stages (brute-force references).
  void run(NarrowScratch& scratch, Contacts& out, NarrowCounters& c, bool cull = true) const;

  /// The earliest-time query for the steps until reset to nullptr: the tests run in order of each pair's
  /// earliest possible time and stop at pairs that cannot beat `cut` (earliest_cut.hpp); each hit lowers it.
  void set_earliest(EarliestCut* cut) { earliest_ = cut; }

  [[nodiscard]] VertexFaceQuery vf_query(Index v, Index f) const;
  [[nodiscard]] EdgeEdgeQuery ee_query(Index a, Index b) const;

 private:
  /// Stage 1 (feature_bounds.hpp): the coarse 16-bit test on every pair first, the float one (the definition)
  /// on what stages 2–4 leave. Both count as stage 1.
  void cull_kdop(NarrowScratch& scratch, NarrowCounters& c, bool coarse) const;
  void cull_plane(NarrowScratch& scratch, CullReach reach, NarrowCounters& c) const;
  void test(const FeatureBatch& batch, Contacts& out, NarrowCounters& c) const;
  void test_earliest(const FeatureBatch& batch, Contacts& out, NarrowCounters& c) const;
  void test_vf(Index v, Index f, Contacts& out, NarrowCounters& c) const;
  void test_ee(Index a, Index b, Contacts& out, NarrowCounters& c) const;
  /// Counts a test and adds its contact when it hit, its time raised to `from` (FeatureBatch::from; 0 without
  /// one), and offers that time to the earliest-time cut, if set.
  void record_vf(const VertexFacePair& p, CcdHit hit, double from, Contacts& out, NarrowCounters& c) const;
  void record_ee(const EdgeEdgePair& p, CcdHit hit, double from, Contacts& out, NarrowCounters& c) const;

  const TriMesh& mesh_;
  const PrimitiveTester& tester_;
  EarliestCut* earliest_ = nullptr;
  NarrowOptions options_;
  Representatives reps_;
  OrphanCertificates certificates_;   ///< over reps_.orphans(): used in the steps whose orphan loop tests them all
  const FeatureBounds* bounds_ = nullptr;
  const Positions* x_t0_ = nullptr;
  const Positions* x_t1_ = nullptr;
  bool motionless_ = false;           ///< x_t0 and x_t1 are one frame (the proximity query): no stage 3 (begin_step)
  bool triangle_stage_ = false;       ///< stage 0 runs in this step (begin_step)
  bool triangle_box_pass_ = true;     ///< … with its x, y, z pass (not in steps that test end boxes)
  FloatFrames float_frames_;          ///< what stage 0 reads, made in begin_step when it runs
  double triangle_cull_rate_ = 0;     ///< its cull rate in the last step that ran it
  TriangleStageRule triangle_rule_;   ///< whether stage 0 runs in a step
  bool sixteenths_stage_ = true;      ///< stage 3's sixteenths run in this step (begin_step)
  CullPassRule sixteenths_rule_{StageNs::sixteenths};
  bool proximity_stage_ = true;       ///< stage 4 runs in this step (begin_step)
  CullPassRule proximity_rule_{StageNs::proximity};
  bool carry_orphans_ = false;        ///< the candidates carry the orphans in this step (begin_step)
  bool certify_orphans_ = false;      ///< … or the orphan loop tests them all, by their certificates
  std::uint64_t last_candidates_ = 0;  ///< the candidates of the last step
  std::uint64_t steps_ = 0;
};

}  // namespace ccdlab

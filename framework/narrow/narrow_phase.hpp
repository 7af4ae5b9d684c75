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
//   stage 4  the features' distance on the windows stage 3 left open (window_distance_filter.hpp)  〃, where it pays
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
#include "framework/narrow/rules/stage_rules.hpp"
#include "framework/primitive/tester.hpp"
#include "framework/traversal/candidates.hpp"
#include "framework/util/named_values.hpp"

namespace ccdlab {

enum class NarrowMode { scalar, batched };
/// narrow.mode's names: the one list every reader, message and choice list takes.
inline constexpr NamedValues<NarrowMode, 2> kNarrowModes{{{{"scalar", NarrowMode::scalar}, {"batched", NarrowMode::batched}}}};
[[nodiscard]] inline std::string_view to_string(NarrowMode m) { return kNarrowModes.name_of(m); }

struct NarrowOptions {
  NarrowMode mode = NarrowMode::batched;
  RepresentativeRule representative = RepresentativeRule::fixed;  // the faster with batched culling (docs/appendix-narrow-phase.md)
  StageRuleChoices rules;  ///< narrow.rules: which passes run by measurement, which are forced (rules/stage_rules.hpp)
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

  /// Which of the passes that only save work can run in this pipeline's steps (the rules choose among them).
  [[nodiscard]] StepPossible possible() const;
  /// Sets the two frames of the step and every vertex's swept 26-DOP over it (stage 1's bounds, updated by
  /// the caller for this step with the tester's thickness: the pipeline's swept volumes). All three must
  /// outlive the step; one Positions passed as both frames is a step without motion (the proximity query), whose
  /// stage 3 is skipped. `plan`: the passes this step runs (StageRules::plan); where the traversal tests end
  /// boxes, stage 0 skips its x, y, z pass (triangle_filter's box_pass).
  void begin_step(const Positions& x_t0, const Positions& x_t1, const FeatureBounds& bounds, const StepPlan& plan = {});

  /// Appends the feature pairs the candidates represent to `scratch.batch`: in a step where stage 0 runs
  /// (batched mode, a tester with a reach, and stage 0 paying: narrow_phase.cpp), those of the candidates it
  /// keeps (`cull = false`: every candidate's, as the ownership tests record them).
  void gather(std::span<const FacePair> candidates, NarrowScratch& scratch, NarrowCounters& c, bool cull = true) const;
  /// Before the orphan loop of a step (after begin_step): the orphan blocks' budgets lose the motion since the
  /// last step (orphan_certificates.hpp), in the steps that use them. Returns its thread-ns.
  std::uint64_t begin_orphans(const Positions& x_t0, const Positions& x_t1);
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
  /// The earliest-time query: narrows a hit that can still be the earliest (PrimitiveTester::tighten_toi), then
  /// offers its time to the cut.
  template <class Query>
  void offer_earliest(const Query& q, CcdHit& hit) const;
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
  bool sixteenths_stage_ = true;      ///< stage 3's sixteenths run in this step (begin_step)
  bool proximity_stage_ = true;       ///< stage 4 runs in this step (begin_step)
  bool carry_orphans_ = false;        ///< the candidates carry the orphans in this step (begin_step)
  bool certify_orphans_ = false;      ///< … or the orphan loop tests them all, by their certificates
  bool certificates_in_step_ = false;  ///< the plan lets the orphan loop use the certificates (begin_orphans decides)
};

}  // namespace ccdlab

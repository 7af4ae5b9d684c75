#include "framework/pipeline/ccd_pipeline.hpp"

#include <algorithm>
#include <optional>

#include "framework/pipeline/phase_clock.hpp"
#include "framework/pipeline/schedule_sim.hpp"
#include "framework/pipeline/work_estimate.hpp"
#include "framework/util/error.hpp"
#include "framework/util/memory.hpp"

namespace ccdlab {
void PipelineStrategies::validate(const SettingName& name) const {
  PipelineSettings::validate(name);
  if (!builder || !scheduler || !tester) fail("pipeline: a hierarchy builder, a scheduler and a tester are required");
  if (normal_cones && tester->thickness() > 0)
    fail("{}: culling is exact only for contact at zero distance; got tester thickness {}",
         name ? name("normal_cones") : std::string("normal_cones"), tester->thickness());
}

namespace {

/// The strategies, checked before anything is built from them.
PipelineStrategies validated(PipelineStrategies s) {
  s.validate();
  return s;
}

}  // namespace

CcdPipeline::CcdPipeline(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies)
    : mesh_(mesh),
      rules_(mesh, std::move(bodies)),
      strategies_(validated(std::move(strategies))),
      narrow_(mesh_, *strategies_.tester, strategies_.narrow,
              [this](Index f) {
                const int b = rules_.body_of_face(f);
                return rules_.bodies_interact(b, b);
              }),
      traversal_(*strategies_.scheduler, strategies_.threads, MemoryBudget(strategies_.memory_limit_bytes, strategies_.stream_slices)),
      narrow_driver_(narrow_, strategies_.threads),
      stage_rules_(strategies_.narrow.rules, strategies_.end_boxes == EndBoxMode::automatic ? PassChoice::adaptive
                                             : strategies_.end_boxes == EndBoxMode::on      ? PassChoice::on
                                                                                             : PassChoice::off) {
  if (const std::uint64_t limit = strategies_.memory_limit_bytes; limit > 0) {
    const std::uint64_t resident = current_rss_bytes(),
                        need = estimate_pipeline_bytes(mesh_, strategies_.k, strategies_.width, orphans().vf.size() + orphans().ee.size(),
                                                       end_boxes_kept());
    if (resident + need > limit)
      fail("memory_limit {}: this run needs about {} before its first step ({} resident now with the scene, {} more "
           "for the BVH, feature boxes and orphan set of {} triangles); lower the scene's size or raise memory_limit",
           format_bytes(limit), format_bytes(resident + need), format_bytes(resident), format_bytes(need),
           mesh_.num_faces());
  }
  const BodyHierarchy::Settings settings{strategies_.k, strategies_.width, strategies_.threads,
                                         strategies_.restructure_threshold, strategies_.normal_cones, end_boxes_kept()};
  const auto& bl = rules_.bodies();
  bodies_.reserve(bl.size());  // the passes point into the bodies: no reallocation after this
  for (std::size_t b = 0; b < bl.size(); ++b) {
    std::vector<Index> faces;
    for (Index f = bl[b].face_begin; f < bl[b].face_end; ++f) faces.push_back(f);
    bodies_.emplace_back(mesh_, std::move(faces), rules_.bodies_interact(int(b), int(b)), settings);
  }
  // Passes: self passes first, then body pairs; ids are stable for the pipeline's lifetime.
  const auto add_pass = [&](int i, int j) {
    const BodyHierarchy& a = bodies_[i];
    const BodyHierarchy& b = bodies_[j];
    const bool wide = strategies_.width == 4, ends = end_boxes_kept();
    TraversalPass pass{int(traversal_.passes().size()), &mesh_, a.side(wide, ends), b.side(wide, ends), i == j,
                       strategies_.threads};
    pass.split_threads = strategies_.split_threads > 0 ? strategies_.split_threads : strategies_.threads;
    if (i == j && strategies_.normal_cones) pass.skip_root = &a.skip_root();
    traversal_.add_pass(pass);
  };
  for (int i = 0; i < int(bl.size()); ++i)
    if (rules_.bodies_interact(i, i) && !bodies_[i].faces().empty()) add_pass(i, i);
  for (int i = 0; i < int(bl.size()); ++i)
    for (int j = i + 1; j < int(bl.size()); ++j)
      if (rules_.bodies_interact(i, j) && !bodies_[i].faces().empty() && !bodies_[j].faces().empty()) add_pass(i, j);
}

CcdPipeline::~CcdPipeline() = default;

bool CcdPipeline::end_boxes_kept() const {
  return strategies_.end_boxes != EndBoxMode::off && strategies_.tester->cull_reach().has_value();
}

double CcdPipeline::end_reach() const {
  const CullReach reach = *strategies_.tester->cull_reach();
  return end_boxes_reach(reach.abs, reach.rel, swept_.scene_extent());
}

StepResult CcdPipeline::step(const Positions& x_t0, const Positions& x_t1) {
  StepResult result;
  step(x_t0, x_t1, result);
  return result;
}

void CcdPipeline::step(const Positions& x_t0, const Positions& x_t1, StepResult& result) {
  if (Index(x_t0.size()) != mesh_.num_vertices() || Index(x_t1.size()) != mesh_.num_vertices())
    fail("step: frames have {} and {} vertices, the mesh has {}", x_t0.size(), x_t1.size(), mesh_.num_vertices());
  Contacts kept = std::move(result.contacts);
  result = StepResult{};
  result.contacts = std::move(kept);  // overwritten by the sort, its memory reused
  StepTimings& tm = result.timings;
  PhaseClock clock(result);
  const auto t_start = PhaseClock::Clock::now();
  reset_peak_rss();  // this step's peak, not the run's
  const std::uint64_t faults_at_start = minor_page_faults();
  const HierarchyBuilder& builder = *strategies_.builder;

  if (!built_)
    clock.parallel("build", &tm.build_ms, [&](PhaseTrace& t) {
      for (BodyHierarchy& body : bodies_) body.build(x_t0, x_t1, builder, t);
    });
  built_ = true;

  // 1. Swept volumes, read by the hierarchies' leaves and the narrow phase's stage 1.
  clock.parallel("swept_bv", &tm.swept_bv_ms, [&](PhaseTrace& t) {
    swept_.update(x_t0, x_t1, strategies_.tester->thickness(), strategies_.threads, t);
  });
  StepPossible possible = narrow_.possible();
  possible.end_boxes = end_boxes_kept();
  plan_ = stage_rules_.plan(steps_, possible);
  ends_in_step_ = plan_.end_boxes;
  narrow_.begin_step(x_t0, x_t1, swept_, plan_);

  // 2. Body hierarchies: refit, restructure, then what hangs on the topology.
  const std::optional<double> end_reach = ends_in_step_ ? std::optional(this->end_reach()) : std::nullopt;
  for (BodyHierarchy& body : bodies_)
    clock.parallel("refit", &tm.refit_ms, [&](PhaseTrace& t) { body.refit(swept_, end_reach, t); });
  if (strategies_.restructure_threshold > 0)
    clock.parallel("restructure", &tm.refit_ms, [&](PhaseTrace& t) {
      for (BodyHierarchy& body : bodies_) result.counters.restructured += body.restructure(x_t0, x_t1, swept_, end_reach, builder, t);
    });
  for (BodyHierarchy& body : bodies_)
    if (body.topology_changed()) clock.serial("build", &tm.build_ms, [&] { body.follow_topology(); });
  if (strategies_.width == 4)
    for (BodyHierarchy& body : bodies_) clock.parallel("refit_wide", &tm.refit_ms, [&](PhaseTrace& t) { body.refit_wide(ends_in_step_, t); });
  if (strategies_.normal_cones)
    clock.parallel("normal_cones", &tm.cones_ms, [&](PhaseTrace& t) {
      face_patch_.assign(mesh_.num_faces(), -1);
      for (BodyHierarchy& body : bodies_) {
        result.traversal.cone_culled += body.update_cones(x_t0, x_t1, t);
        result.traversal.contour_edges += body.contour_edge_tests();
        body.mark_skipped_patches(face_patch_);
      }
    });

  refuse_exploding_work(x_t0, x_t1);
  watch_.start(strategies_.time_limit, expected_candidates_, &progress_);  // room for contacts: TraversalDriver
  narrow_driver_.watch(&watch_);
  narrow_driver_.begin_step();

  // 3–4. Traversal, its candidates into the narrow phase as they are found; then the orphan set, less the blocks
  //      that moved too little since they were last tested (orphan_certificates.hpp).
  traversal_.test_end_boxes(ends_in_step_);
  traversal_.run(std::size_t(mesh_.num_faces()), narrow_driver_, result);
  refuse_late_step("its candidates");
  clock.serial("orphan_motion", &tm.orphan_ms, [&] { result.counters.orphan_motion_ns += narrow_.begin_orphans(x_t0, x_t1); });
  narrow_driver_.test_orphans(strategies_.normal_cones ? &face_patch_ : nullptr, result);
  refuse_late_step("its orphan set");
  expected_candidates_ = double(result.counters.candidate_pairs);
  // What the step cost, for the rules: its narrow phase's thread-ns, and its time but for the build (end boxes
  // change the refit and the traversal too).
  const double step_ms = ms_between(t_start, PhaseClock::Clock::now()) - tm.build_ms;
  stage_rules_.record(steps_++, plan_, result.counters, {StageRules::narrow_ns(result.counters), step_ms * 1e6});

  // 5. One order, whatever the schedule.
  clock.parallel("sort_contacts", nullptr, [&](PhaseTrace& t) { narrow_driver_.sort_contacts_into(result.contacts, sort_scratch_, t); });

  tm.total_ms = ms_between(t_start, PhaseClock::Clock::now());
  result.traces.push_back(untraced_time(result.traces, tm.total_ms));  // serial for the schedule simulator
  result.memory.peak_rss_bytes = peak_rss_bytes();
  result.memory.page_faults = minor_page_faults() - faults_at_start;
}

void CcdPipeline::refuse_exploding_work(const Positions& x_t0, const Positions& x_t1) {
  const double limit = strategies_.candidate_limit, extent = swept_.scene_extent();
  if (estimated_extent_ >= 0 && !(extent > 2 * estimated_extent_)) return;
  estimated_extent_ = extent;
  if (const std::string problem = scale_problem(x_t0, x_t1); !problem.empty()) fail("step: {}", problem);
  // Estimated whatever the limit: the memory plan and the progress report read it too.
  const WorkEstimate e = estimate_candidates(traversal_.passes(), std::size_t(mesh_.num_faces()));
  expected_candidates_ = e.candidates;
  traversal_.expect_candidates(e.candidates);
  if (limit <= 0 || !(e.per_face() > limit)) return;
  const double per_face = e.per_face();
  fail("step: about {:.2g} candidate triangle pairs expected ({} per triangle of {}, estimated from {} sampled "
       "triangles), above candidate_limit = {:g} per triangle: {} To run it anyway, raise candidate_limit "
       "(--candidate-limit on the command line; 0 = no limit).",
       e.candidates, per_face >= 100 ? fmt::format("{:.0f}", per_face) : fmt::format("{:.2g}", per_face), e.faces, e.sampled, limit,
       explain_work(mesh_, x_t0, x_t1, strategies_.tester->thickness(), strategies_.tester->thickness_name()));
}

void CcdPipeline::refuse_late_step(const char* where) {
  const double expected = watch_.pairs_expected();
  if (watch_.out_of_room())
    fail("memory_limit {}: the step's contacts would not fit: {} found, in {}, after {} candidate pairs{} (each "
         "holds ~{} bytes until the step ends; room for {}); raise memory_limit{}",
         format_bytes(strategies_.memory_limit_bytes), watch_.contacts(), where, watch_.pairs_done(),
         expected > 0 ? fmt::format(" of about {:.2g}", expected) : std::string(), StepWatch::kBytesPerContact,
         watch_.max_contacts(),
         strategies_.tester->thickness() > 0 ? fmt::format(", or lower {} ({:g})", strategies_.tester->thickness_name(), strategies_.tester->thickness())
                                              : std::string());
  if (!watch_.expired()) return;
  fail("time_limit {:g} s: the step was stopped after {:.1f} s, in {}, with {} candidate pairs tested{}; raise "
       "time_limit (ccdlab step: --time-limit; 0 = no limit)",
       strategies_.time_limit, watch_.seconds(), where, watch_.pairs_done(),
       expected > 0 ? fmt::format(" of about {:.2g} expected", expected) : std::string());
}

double CcdPipeline::earliest_toi(const Positions& x_t0, const Positions& x_t1, StepResult* result) {
  EarliestCut cut;
  narrow_.set_earliest(&cut);
  struct Unset {  // the next step() is a whole one again, even when this one throws
    NarrowPhase& narrow;
    ~Unset() { narrow.set_earliest(nullptr); }
  } unset{narrow_};
  StepResult r = step(x_t0, x_t1);
  if (result) *result = std::move(r);
  return std::min(cut.best(), 1.0);
}

const TraversalOutput& CcdPipeline::last_candidates() const {
  if (!traversal_.keeps_candidates())
    fail("last_candidates: the pipeline keeps the candidates only after keep_candidates(true)");
  return traversal_.candidates();
}

std::size_t CcdPipeline::memory_bytes() const {
  const Ownership& own = narrow_.representatives().owners();
  std::size_t bytes = mesh_.memory_bytes() + own.vertex_owner.size() * sizeof(Index) +
                      own.edge_owner.size() * sizeof(Index) + own.owned_mask.size() + swept_.memory_bytes() +
                      orphans().vf.size() * sizeof(VertexFacePair) + orphans().ee.size() * sizeof(EdgeEdgePair);
  for (const BodyHierarchy& b : bodies_) bytes += b.memory_bytes();
  return bytes;
}

}  // namespace ccdlab

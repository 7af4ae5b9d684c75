#include "framework/pipeline/ccd_pipeline.hpp"

#include <algorithm>
#include <optional>

#include "framework/pipeline/phase_clock.hpp"
#include "framework/pipeline/schedule_sim.hpp"
#include "framework/util/error.hpp"
#include "framework/util/memory.hpp"

namespace ccdlab {
namespace {

/// bv.end_boxes: auto (CcdPipeline::end_boxes_pay). End boxes cost every step a pass over the nodes (their refit
/// beside the k-DOPs) and 12 more compares per node pair the walk opens; they save the node pairs and the
/// candidates they drop. They run in a step when the last step run with them kept at most kEndsKeepAtMost of
/// the candidates of the last step run without them, and dropped at least kEndsDropPerFace candidates per face
/// (docs/wide-bvh.md, "End boxes", gives the thresholds' margins on the real steps). Both counts are measured again every
/// kEndsRemeasure steps, one step without (step 0 mod 16), then one with (1 mod 16) when the step without had
/// enough candidates to drop. Whole-step candidate counts are the same for every scheduler, width, thread count
/// and slicing, so every schedule decides alike and reports the same counters.
constexpr double kEndsKeepAtMost = 0.5;
constexpr double kEndsDropPerFace = 4;
constexpr std::uint64_t kEndsRemeasure = 16;
static_assert(kEndsRemeasure == TriangleStageRule::kRemeasure,
              "stage 0 measures at 2 and 3 mod 16, after the end boxes' steps 0 and 1, on the same kind of candidates");

}  // namespace

void PipelineStrategies::validate() const {
  if (!is_kdop_k(k)) fail("bv.k: expected one of {}, got {}", kKdopKs, k);
  if (!is_bvh_width(width)) fail("bv.width: expected {}, got {}", kBvhWidths, width);
  if (threads < 1 || threads > kMaxThreads) fail("threads: expected an integer from 1 to {}, got {}", kMaxThreads, threads);
  if (split_threads < 0 || split_threads > kMaxThreads)
    fail("split_threads: expected 0 (= threads) or an integer up to {}, got {}", kMaxThreads, split_threads);
  if (!(restructure_threshold >= 0) || !std::isfinite(restructure_threshold))
    fail("restructure: expected a finite threshold ≥ 0 (0 = off), got {}", restructure_threshold);
  if (!builder || !scheduler || !tester) fail("pipeline: a hierarchy builder, a scheduler and a tester are required");
  if (normal_cones && tester->thickness() > 0)
    fail("normal_cones: culling is exact only for contact at zero distance; got tester thickness {}", tester->thickness());
}

std::string_view to_string(EndBoxMode m) {
  return m == EndBoxMode::on ? "on" : m == EndBoxMode::off ? "off" : "auto";
}

EndBoxMode parse_end_box_mode(std::string_view name) {
  if (name == "true" || name == "on") return EndBoxMode::on;
  if (name == "false" || name == "off") return EndBoxMode::off;
  if (name == "auto") return EndBoxMode::automatic;
  fail("bv.end_boxes: expected true, false or auto, got '{}'", name);
}

std::uint64_t estimate_pipeline_bytes(const TriMesh& mesh, int k, int width, std::size_t orphan_pairs, bool end_boxes) {
  const std::uint64_t v = std::uint64_t(mesh.num_vertices()), e = std::uint64_t(mesh.num_edges()),
                      f = std::uint64_t(mesh.num_faces());
  const std::uint64_t bv = std::visit([](const auto& vec) { return std::uint64_t(sizeof(vec[0])); }, make_bvs(k));
  const std::uint64_t bvh = 2 * f * (sizeof(BvhNode) + sizeof(Index) + bv);  // nodes, leaf counts, node volumes
  const std::uint64_t wide_bounds =
      std::visit([](const auto& vec) { return std::uint64_t(sizeof(vec[0])); }, make_wide_bvs(k));
  // One wide node per inner node (f − 1) and the top one: its lanes, bounds and owner, plus a slot and a home per node.
  const std::uint64_t wide = width == 4 ? f * (sizeof(WideLayout::Lanes) + wide_bounds + sizeof(Index)) + 4 * f * sizeof(Index) : 0;
  const std::uint64_t feature_boxes = v * FeatureBounds::kBytesPerVertex;
  const std::uint64_t records = std::max<std::uint64_t>(f * sizeof(GatherRecord), kLargeAllocation);  // one huge page at least
  const std::uint64_t ownership = (v + e) * sizeof(Index) + f + records;  // owners, masks, the gather's records
  // The orphan set, and the same pairs again by the face that carries them (representatives.hpp), with a list
  // start and a signature per face.
  const std::uint64_t orphans = std::uint64_t(orphan_pairs) * (sizeof(EdgeEdgePair) + sizeof(CarriedOrphan)) +
                                f * (sizeof(std::uint32_t) + sizeof(std::uint64_t));
  // The frames, and stage 0's float copy with its faces' boxes (framework/swept/frame_points.hpp).
  const std::uint64_t frames = 2 * v * sizeof(Vec3) + v * sizeof(FloatFramePoints) + f * sizeof(FloatFaceBoxes);
  // End boxes: per node, and per wide node (framework/swept/end_boxes.hpp).
  const std::uint64_t ends = end_boxes ? 2 * f * sizeof(EndBoxes) + (width == 4 ? f * sizeof(WideEnds) : 0) : 0;
  return bvh + wide + feature_boxes + ownership + orphans + frames + ends;
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
      traversal_(*strategies_.scheduler, strategies_.threads, MemoryBudget(strategies_.memory_limit, strategies_.stream_slices)),
      narrow_driver_(narrow_, strategies_.threads) {
  if (const std::uint64_t limit = strategies_.memory_limit; limit > 0) {
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
    TraversalPass pass{int(traversal_.passes().size()), &mesh_, &a.bvh(), &a.node_bvs(), &b.bvh(), &b.node_bvs(), i == j,
                       strategies_.threads};
    pass.split_threads = strategies_.split_threads > 0 ? strategies_.split_threads : strategies_.threads;
    if (i == j && strategies_.normal_cones) pass.skip_root = &a.skip_root();
    if (strategies_.width == 4) {
      pass.wide_layout_a = &a.wide_layout();
      pass.wide_a = &a.node_wide();
      pass.wide_layout_b = &b.wide_layout();
      pass.wide_b = &b.node_wide();
    }
    if (end_boxes_kept()) {
      pass.ends_a = &a.node_ends(), pass.ends_b = &b.node_ends();
      if (strategies_.width == 4) pass.wide_ends_a = &a.wide_ends(), pass.wide_ends_b = &b.wide_ends();
    }
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

bool CcdPipeline::end_boxes_pay() const {
  if (!end_boxes_kept()) return false;
  if (strategies_.end_boxes == EndBoxMode::on) return true;
  const double faces = double(mesh_.num_faces());
  const bool may_pay = double(candidates_without_ends_) >= kEndsDropPerFace * faces;
  switch (steps_ % kEndsRemeasure) {
    case 0: return false;     // measures the candidates without
    case 1: return may_pay;  // measures them with
    default:
      return may_pay && double(candidates_with_ends_) <= kEndsKeepAtMost * double(candidates_without_ends_) &&
             double(candidates_without_ends_ - std::min(candidates_with_ends_, candidates_without_ends_)) >=
                 kEndsDropPerFace * faces;
  }
}

double CcdPipeline::end_reach() const {
  const CullReach reach = *strategies_.tester->cull_reach();
  return end_boxes_reach(reach.abs, reach.rel, swept_.scene_extent());
}

StepResult CcdPipeline::step(const Positions& x_t0, const Positions& x_t1) {
  if (Index(x_t0.size()) != mesh_.num_vertices() || Index(x_t1.size()) != mesh_.num_vertices())
    fail("step: frames have {} and {} vertices, the mesh has {}", x_t0.size(), x_t1.size(), mesh_.num_vertices());
  StepResult result;
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
  ends_in_step_ = end_boxes_pay();
  narrow_.begin_step(x_t0, x_t1, swept_, ends_in_step_);

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

  // 3–4. Traversal, its candidates into the narrow phase as they are found; then the orphan set.
  traversal_.test_end_boxes(ends_in_step_);
  traversal_.run(std::size_t(mesh_.num_faces()), narrow_driver_, result);
  narrow_driver_.test_orphans(strategies_.normal_cones ? &face_patch_ : nullptr, result);
  narrow_.end_step(result.counters);
  (ends_in_step_ ? candidates_with_ends_ : candidates_without_ends_) = result.counters.candidate_pairs;
  ++steps_;

  // 5. One order, whatever the schedule.
  clock.serial("sort_contacts", nullptr, [&] { sort_contacts(result.contacts, sort_scratch_); });

  tm.total_ms = ms_between(t_start, PhaseClock::Clock::now());
  result.traces.push_back(untraced_time(result.traces, tm.total_ms));  // serial for the schedule simulator
  result.memory.peak_rss_bytes = peak_rss_bytes();
  result.memory.page_faults = minor_page_faults() - faults_at_start;
  return result;
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

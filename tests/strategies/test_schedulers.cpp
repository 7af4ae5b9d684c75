// Every scheduler × thread count yields the identical candidate set and contact set, step after step (the
// determinism invariant of design.md); the BVTT front stays an exact cover of the leaf pairs while it sprouts,
// prunes and rebuilds.
#include <gtest/gtest.h>

#include <algorithm>

#include <array>
#include <map>

#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/traversal/bvtt_tasks.hpp"
#include "strategies/registry.hpp"
#include "strategies/scenes/drape_fold_scene.hpp"
#include "strategies/schedulers/front_scheduler.hpp"
#include "support/registries.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

PipelineStrategies make(const std::string& scheduler, const std::map<std::string, ParamValues::Value>& params,
                        int threads, int k = 18) {
  PipelineStrategies s;
  s.k = k;
  s.threads = threads;
  s.builder = builder_registry().make({"median", {}});
  ParamValues pv = scheduler_registry().find(scheduler)->defaults();
  for (const auto& [name, value] : params) pv.set(name, value);
  s.scheduler = scheduler_registry().make({scheduler, pv});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
  // Timed rules may choose differently from run to run; forced, every schedule counts the same work.
  s.narrow.rules = StageRuleChoices::all(PassChoice::on);
  s.end_boxes = EndBoxMode::on;
  return s;
}

struct RunResult {
  std::vector<FacePairs> candidates;  // sorted, per step (only when the pipeline kept them)
  std::vector<std::uint64_t> hashes;
  std::vector<std::array<std::uint64_t, 3>> work;  // candidate pairs, feature pairs, elementary tests, per step
  std::vector<bool> end_boxes;  // whether the step tested end boxes
  std::uint64_t bv_tests = 0;
};

/// hand_over = 0: the pipeline keeps every candidate (compared here); otherwise the narrow phase takes a
/// thread's candidates whenever it holds that many, while the traversal runs (the default path, made to trigger
/// on a small scene).
RunResult run(const MeshSequence& scene, PipelineStrategies s, std::size_t hand_over = 0) {
  CcdPipeline p(scene.topology(), scene.bodies(), std::move(s));
  p.keep_candidates(hand_over == 0);
  if (hand_over > 0) p.set_hand_over_pairs(hand_over);
  RunResult r;
  Positions x0 = scene.frame(0);
  for (int i = 0; i < scene.num_steps(); ++i) {
    Positions x1 = scene.frame(i + 1);
    StepResult res = p.step(x0, x1);
    if (hand_over == 0) {
      auto c = p.last_candidates().pairs.flatten();
      std::sort(c.begin(), c.end());
      EXPECT_EQ(std::adjacent_find(c.begin(), c.end()), c.end()) << "duplicate candidate at step " << i;
      r.candidates.push_back(std::move(c));
    }
    r.hashes.push_back(contact_set_hash(res.contacts));
    const StepCounters& k = res.counters;
    r.work.push_back({k.candidate_pairs, k.vf_pairs + k.ee_pairs, k.vf_tests + k.ee_tests});
    r.bv_tests += res.counters.bv_tests;
    r.end_boxes.push_back(p.end_boxes_in_last_step());
    x0 = std::move(x1);
  }
  return r;
}

MeshSequence small_scene() {
  DrapeFoldParams p;
  p.resolution = 20;
  p.frames = 9;
  p.sphere_segments = 12;
  return make_drape_fold_scene(p);
}

/// A crumpled sheet flying along the diagonal, about seven cells a step, slightly shaken: each face's swept volume
/// covers hundreds of others, though faces hardly move relative to one another — where end boxes pay.
MeshSequence flying_sheet(int steps) {
  MeshData g = test::grid(24, 24);
  std::mt19937 rng(9);
  const Positions rest = test::crumple(g.positions, rng, 0.002);
  auto frames = std::make_shared<std::vector<Positions>>();
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i <= steps; ++i) {
    Positions x = rest;
    for (Vec3& p : x) p += 0.3 * i * Vec3(1, 1, 1) + 0.001 * Vec3(u(rng), u(rng), u(rng));
    frames->push_back(std::move(x));
  }
  TriMesh mesh(Index(g.positions.size()), g.faces);
  std::vector<std::string> labels;
  for (int i = 0; i <= steps; ++i) labels.push_back(std::to_string(i));
  auto bodies = single_cloth_body(mesh);
  return MeshSequence(std::move(mesh), bodies, labels, [frames](int i) { return (*frames)[std::size_t(i)]; },
                      "flying sheet");
}

TEST(Schedulers, IdenticalAnswersForEverySchedulerAndThreadCount) {
  const MeshSequence scene = small_scene();
  const RunResult reference = run(scene, make("sequential", {}, 1));
  std::size_t contacts_steps = 0;
  for (std::uint64_t h : reference.hashes) contacts_steps += h != contact_set_hash({});
  ASSERT_GE(contacts_steps, 3u) << "the scene must have contacts in several steps";
  struct Variant {
    std::string name;
    std::map<std::string, ParamValues::Value> params;
  };
  const std::vector<Variant> variants{
      {"sequential", {}},
      {"phc", {}},
      {"phc", {{"c", 1LL}}},
      {"static", {}},
      {"static", {{"c", 3LL}}},
      {"front", {}},
      {"front", {{"chunk", 7LL}}},
      {"front", {{"prune", false}}},
      {"front", {{"rebuild_every", 2LL}, {"chunk", 33LL}}},
      {"front", {{"rebuild_growth", 1.01}}},
  };
  for (const auto& variant : variants)
    for (int threads : {1, 2, 3, 4, 8}) {
      SCOPED_TRACE(variant.name + " x" + std::to_string(threads) + " (" + std::to_string(variant.params.size()) + " params)");
      const RunResult r = run(scene, make(variant.name, variant.params, threads));
      ASSERT_EQ(r.candidates.size(), reference.candidates.size());
      for (std::size_t s = 0; s < r.candidates.size(); ++s) {
        EXPECT_EQ(r.candidates[s], reference.candidates[s]) << "step " << s;
        EXPECT_EQ(r.hashes[s], reference.hashes[s]) << "step " << s;
      }
      if (variant.name == "front") {
        EXPECT_LT(r.bv_tests, reference.bv_tests) << "the front must save BV tests";
      }
      // Candidates tested while the traversal runs (handed over after every task): same answers, same work.
      const RunResult taken = run(scene, make(variant.name, variant.params, threads), 1);
      EXPECT_EQ(taken.hashes, reference.hashes);
      EXPECT_EQ(taken.work, r.work);
    }
}

TEST(Schedulers, EndBoxesGiveEverySchedulerWidthAndThreadCountTheSameCandidates) {
  // bv.end_boxes (framework/swept/end_boxes.hpp) changes which node pairs every walk opens — the binary walk,
  // the task splits of phc and static, the binary and wide fronts, the SSE2 and lane-pair walks — but never the
  // leaf pairs they reach together, nor the contacts.
  const MeshSequence scene = small_scene();
  PipelineStrategies off = make("sequential", {}, 1), on = make("sequential", {}, 1);
  off.end_boxes = EndBoxMode::off, on.end_boxes = EndBoxMode::on;
  const RunResult without = run(scene, std::move(off));
  const RunResult reference = run(scene, std::move(on));
  EXPECT_EQ(reference.hashes, without.hashes);
  std::size_t kept = 0, all = 0;
  for (std::size_t s = 0; s < reference.candidates.size(); ++s) {
    const FacePairs &a = reference.candidates[s], &b = without.candidates[s];
    EXPECT_TRUE(std::includes(b.begin(), b.end(), a.begin(), a.end())) << "step " << s;
    kept += a.size(), all += b.size();
  }
  EXPECT_LT(kept, all) << "the end boxes dropped no candidate: the test proves nothing";
  for (const std::string& scheduler : test::bvtt_schedulers())
    for (int width : {2, 4})
      for (int threads : {1, 3}) {
        SCOPED_TRACE(std::string(scheduler) + " width " + std::to_string(width) + " x" + std::to_string(threads));
        PipelineStrategies s = make(scheduler, {}, threads);
        s.width = width, s.end_boxes = EndBoxMode::on;
        const RunResult r = run(scene, std::move(s));
        EXPECT_EQ(r.candidates, reference.candidates);
        EXPECT_EQ(r.hashes, reference.hashes);
      }
}

TEST(Schedulers, AutomaticEndBoxesFindTheCandidatesOfOnOrOffInEveryStepAndSchedule) {
  // bv.end_boxes: auto runs the end boxes in the steps their measured rule chooses (rules/stage_rules.hpp):
  // timed, so the choice may differ between runs and schedules, but each step finds the candidates of `on` or of
  // `off` and the contacts of both.
  const MeshSequence flying = flying_sheet(19), folding = small_scene();
  for (const MeshSequence* scene : {&flying, &folding}) {
    SCOPED_TRACE(scene->description());
    PipelineStrategies off = make("sequential", {}, 1), on = make("sequential", {}, 1);
    off.end_boxes = EndBoxMode::off, on.end_boxes = EndBoxMode::on;
    const RunResult without = run(*scene, std::move(off)), with = run(*scene, std::move(on));
    for (const std::string& scheduler : test::bvtt_schedulers())
      for (int width : {2, 4})
        for (int threads : {1, 3}) {
          SCOPED_TRACE(std::string(scheduler) + " width " + std::to_string(width) + " x" + std::to_string(threads));
          PipelineStrategies s = make(scheduler, {}, threads);
          s.width = width, s.end_boxes = EndBoxMode::automatic;
          const RunResult r = run(*scene, std::move(s));
          ASSERT_EQ(r.end_boxes.size(), std::size_t(scene->num_steps()));
          EXPECT_FALSE(r.end_boxes[0]) << "nothing measured yet: the first steps run without them";
          for (std::size_t i = 0; i < r.end_boxes.size(); ++i) {
            EXPECT_EQ(r.candidates[i], r.end_boxes[i] ? with.candidates[i] : without.candidates[i]) << "step " << i;
            EXPECT_EQ(r.hashes[i], without.hashes[i]) << "step " << i;
          }
          if (r.end_boxes.size() > RuleCalendar::end_boxes) {
            EXPECT_TRUE(r.end_boxes[RuleCalendar::end_boxes]) << "the calendar's step with them";
          }
        }
  }
}

// phc hands a pass's tasks out largest first by their costs at the last step, only when they are the same tasks
// (IdenticalAnswersForEverySchedulerAndThreadCount above runs it over several steps: same candidates).
TEST(Schedulers, PhcHandsOutTheLastStepsLargestTasksFirst) {
  TaskCosts costs;
  const std::vector<BvttNode> tasks{{1, 1}, {2, 2}, {1, 2}, {3, 4}};
  using Order = std::vector<std::size_t>;
  EXPECT_EQ(costs.order(tasks), (Order{0, 1, 2, 3})) << "no history: breadth-first";
  // Handed out as 3, 2, 1, 0, the costs in that order: tasks[3] 5 ms, tasks[2] 1, tasks[1] 7, tasks[0] 1.
  costs.record(tasks, Order{3, 2, 1, 0}, {5.0, 1.0, 7.0, 1.0});
  EXPECT_EQ(costs.order(tasks), (Order{1, 3, 0, 2})) << "7, 5, then the equal ones in breadth-first order";
  std::vector<BvttNode> other = tasks;
  other[2] = {2, 3};
  EXPECT_EQ(costs.order(other), (Order{0, 1, 2, 3})) << "other tasks: their own order";
  EXPECT_EQ(costs.order({tasks.begin(), tasks.end() - 1}), (Order{0, 1, 2}));
}

/// Leaf pairs (faces) covered by each front node of a self pass, counted.
std::map<std::pair<Index, Index>, int> coverage(const BvhTopology& bvh, const std::vector<FrontNode>& front) {
  std::vector<std::vector<Index>> leaves(bvh.nodes.size());
  for (Index i = bvh.size() - 1; i >= 0; --i) {
    const BvhNode& n = bvh.nodes[i];
    if (n.is_leaf()) leaves[i] = {n.face};
    else {
      leaves[i] = leaves[n.left];
      leaves[i].insert(leaves[i].end(), leaves[n.right].begin(), leaves[n.right].end());
    }
  }
  std::map<std::pair<Index, Index>, int> cover;
  for (const FrontNode& f : front)
    for (Index a : leaves[f.a])
      for (Index b : leaves[f.b]) ++cover[{std::min(a, b), std::max(a, b)}];
  return cover;
}

// The simulator replays, for N cores, a 1-thread run split for N threads (bench's recording runs): that run must
// cut exactly the tasks an N-thread run cuts, and only the schedulers that say so depend on the thread count.
TEST(Schedulers, ARunSplitForNThreadsCutsTheTasksOfAnNThreadRun) {
  const MeshSequence scene = small_scene();
  const Positions x0 = scene.frame(0), x1 = scene.frame(1);
  auto traverse_tasks = [&](const std::string& scheduler, int threads, int split) {
    PipelineStrategies s = make(scheduler, {}, threads);
    s.split_threads = split;
    CcdPipeline p(scene.topology(), scene.bodies(), std::move(s));
    const StepResult r = p.step(x0, x1);
    std::size_t tasks = 0;
    for (const PhaseTrace& t : r.traces)
      if (t.phase == "traverse") tasks += t.task_ms.size();
    return std::pair{tasks, contact_set_hash(r.contacts)};
  };
  for (const std::string scheduler : {"phc", "static"}) {
    EXPECT_TRUE(scheduler_registry().make({scheduler, scheduler_registry().find(scheduler)->defaults()})->splits_by_threads()) << scheduler;
    const auto one = traverse_tasks(scheduler, 1, 0);
    const auto four = traverse_tasks(scheduler, 4, 0);
    const auto recorded = traverse_tasks(scheduler, 1, 4);
    EXPECT_GT(four.first, one.first) << scheduler << ": c·threads tasks";
    EXPECT_EQ(recorded.first, four.first) << scheduler;
    EXPECT_EQ(recorded.second, one.second) << scheduler;
  }
  for (const std::string scheduler : {"sequential", "front"}) {
    EXPECT_FALSE(scheduler_registry().make({scheduler, scheduler_registry().find(scheduler)->defaults()})->splits_by_threads());
    EXPECT_EQ(traverse_tasks(scheduler, 1, 4).first, traverse_tasks(scheduler, 1, 0).first) << scheduler;
  }
}

// `static` fixes each thread's tasks before a step: equal-count chunks on the first step, then by the last step's
// costs (the same tasks: same topology and top); the candidates never change.
TEST(StaticScheduler, FirstStepInChunksThenBalancedByTheLastStepsCosts) {
  const MeshSequence scene = small_scene();
  CcdPipeline p(scene.topology(), scene.bodies(), make("static", {}, 2));
  std::vector<Distribution> seen;
  Positions x0 = scene.frame(0);
  for (int i = 0; i < 3; ++i) {
    const StepResult r = p.step(x0, scene.frame(1));  // the same step again: the same tasks
    for (const PhaseTrace& t : r.traces)
      if (t.phase == "traverse" && !t.task_ms.empty()) {
        seen.push_back(t.distribution);
        break;
      }
  }
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], Distribution::static_chunks);
  EXPECT_EQ(seen[1], Distribution::static_balanced);
  EXPECT_EQ(seen[2], Distribution::static_balanced);
}

TEST(FrontScheduler, FrontCoversEveryNonAdjacentLeafPairExactlyOnceAndShrinksWhenContactEnds) {
  // Two parallel sheets (one self-colliding body) that approach, touch and separate again.
  MeshData sheets = test::concat(test::grid(8, 8), test::grid(8, 8));
  const Index half = Index(sheets.positions.size() / 2);
  TriMesh mesh(Index(sheets.positions.size()), sheets.faces);
  auto frame = [&](double gap) {
    Positions x = sheets.positions;
    for (Index v = half; v < Index(x.size()); ++v) x[v].z() = gap + 0.01 * std::sin(9 * x[v].x());
    return x;
  };
  // Apart again for longer than kPruneWait steps: the wide front's sprouted groups wait that long before their
  // first prune attempt.
  std::vector<double> gaps{1.0, 0.5, 0.1, 0.0, 0.1, 0.5, 1.0};
  gaps.insert(gaps.end(), kPruneWait + 2, 1.0);
  // Width 2: the binary front of node pairs; width 4: the wide front of record pairs (where the CPU has the
  // lane-pair walk; the binary front elsewhere).
  for (int width : {2, 4})
  for (bool prune : {true, false}) {
    SCOPED_TRACE("width " + std::to_string(width) + (prune ? " prune" : " no prune"));
    PipelineStrategies s = make("front", {{"prune", prune}, {"rebuild_growth", 0.0}, {"chunk", 16LL}}, 2);
    s.width = width;
    auto* front = dynamic_cast<FrontScheduler*>(s.scheduler.get());
    ASSERT_NE(front, nullptr);
    CcdPipeline p(mesh, single_cloth_body(mesh), std::move(s));
    std::vector<std::size_t> sizes;
    for (std::size_t i = 0; i + 1 < gaps.size(); ++i) {
      StepResult r = p.step(frame(gaps[i]), frame(gaps[i + 1]));
      const auto cover = coverage(p.bvh(0), front->front(0));  // a copy, concatenated
      for (Index a = 0; a < mesh.num_faces(); ++a)
        for (Index b = a + 1; b < mesh.num_faces(); ++b) {
          auto it = cover.find({a, b});
          const int n = it == cover.end() ? 0 : it->second;
          if (mesh.faces_adjacent(a, b)) ASSERT_LE(n, 1) << "step " << i;
          else ASSERT_EQ(n, 1) << "step " << i << " pair " << a << " " << b;
        }
      sizes.push_back(front->front(0).size());
      if (i == 3) {
        EXPECT_GT(r.contacts.size(), 0u);
      }
    }
    const std::size_t peak = *std::max_element(sizes.begin(), sizes.end());
    if (prune) {
      EXPECT_LT(sizes.back(), peak) << "pruning must shrink the front once the sheets separate";
    } else {
      EXPECT_EQ(sizes.back(), peak) << "without pruning the front only grows";
    }
  }
}

}  // namespace
}  // namespace ccdlab

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

TEST(AdaptiveRestructuring, RebuildsDegradedSubtreesWithoutChangingAnswers) {
  const MeshSequence scene = small_scene();
  // With end boxes, the rebuilt sub-trees' boxes are made again too (BodyHierarchy::restructure).
  for (const bool end_boxes : {false, true}) {
    PipelineStrategies base = make("sequential", {}, 1);
    base.end_boxes = end_boxes ? EndBoxMode::on : EndBoxMode::off;
    const RunResult reference = run(scene, std::move(base));
    for (const std::string scheduler : {"sequential", "front", "phc"})
      for (int threads : {1, 3}) {
        SCOPED_TRACE(scheduler + " x" + std::to_string(threads) + (end_boxes ? " end boxes" : ""));
        PipelineStrategies s = make(scheduler, {}, threads);
        s.restructure_threshold = 1.01;  // aggressive: rebuild at the slightest degradation
        s.end_boxes = end_boxes ? EndBoxMode::on : EndBoxMode::off;
        CcdPipeline p(scene.topology(), scene.bodies(), std::move(s));
        p.keep_candidates(true);
        std::uint64_t restructured = 0, version_before = 0;
        Positions x0 = scene.frame(0);
        for (int i = 0; i < scene.num_steps(); ++i) {
          Positions x1 = scene.frame(i + 1);
          version_before = p.bvh(0).version;
          StepResult r = p.step(x0, x1);
          restructured += r.counters.restructured;
          if (r.counters.restructured > 0 && i > 0) {
            EXPECT_GT(p.bvh(0).version, version_before);
          }
          std::vector<Index> faces;
          for (Index f = scene.bodies()[0].face_begin; f < scene.bodies()[0].face_end; ++f) faces.push_back(f);
          ASSERT_NO_THROW(validate_bvh(p.bvh(0), faces)) << "step " << i;
          auto c = p.last_candidates().pairs.flatten();
          std::sort(c.begin(), c.end());
          EXPECT_EQ(c, reference.candidates[i]) << "step " << i;
          EXPECT_EQ(contact_set_hash(r.contacts), reference.hashes[i]) << "step " << i;
          x0 = std::move(x1);
        }
        EXPECT_GT(restructured, 0u) << "the folding scene must degrade some sub-trees";
      }
  }
}

}  // namespace
}  // namespace ccdlab

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

TEST(EmbreeScheduler, YieldsExactlyTheCandidatesOfSequentialStepAfterStep) {
  // Embree's rtcCollide over boxes, then the leaf k-DOPs: the same candidates as ccdlab's own traversal, on a
  // scene with a self pass and a cloth–obstacle pass, for two K and two thread counts.
  const MeshSequence scene = small_scene();
  for (int k : {6, 18}) {
    const RunResult reference = run(scene, make("sequential", {}, 1, k));
    ASSERT_GT(reference.candidates.back().size(), 50u);
    for (int threads : {1, 2}) {
      const RunResult embree = run(scene, make("embree", {}, threads, k));
      EXPECT_EQ(embree.candidates, reference.candidates) << "K=" << k << " threads=" << threads;
      EXPECT_EQ(embree.hashes, reference.hashes) << "K=" << k << " threads=" << threads;
    }
  }
}

}  // namespace
}  // namespace ccdlab

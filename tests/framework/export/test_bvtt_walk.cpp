// The teaching page's BVTT walk-through (framework/export/bvtt_walk.hpp): the orders of sequential, phc and front
// re-enacted with the traversal's own rule find exactly the candidates the pipeline's traversal finds, the
// sequential walk makes as many BV tests as the binary depth-first kernel, and phc / front share their work out
// as their algorithms say.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "framework/export/bvtt_walk.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "strategies/schedulers/front_scheduler.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

std::set<std::pair<Index, Index>> candidates_of(const BvttWalk& w, const BvhTopology& bvh) {
  std::set<std::pair<Index, Index>> out;
  for (const WalkVisit& v : w.visits)
    if (v.candidate) {
      const Index fa = bvh.nodes[v.a].face, fb = bvh.nodes[v.b].face;
      out.insert({std::min(fa, fb), std::max(fa, fb)});
    }
  return out;
}

TEST(BvttWalk, EveryOrderFindsThePipelinesCandidatesWithItsTestCount) {
  const MeshData g = test::grid(12, 12);
  const TriMesh mesh(Index(g.positions.size()), g.faces);
  std::mt19937 rng(4);
  const Positions x0 = test::crumple(g.positions, rng, 0.05), x1 = test::crumple(g.positions, rng, 0.05),
                  x2 = test::crumple(g.positions, rng, 0.05);
  PipelineStrategies s = contact_strategies(18, "front", 1, 0.0);
  s.width = 2;
  s.end_boxes = EndBoxMode::off;
  CcdPipeline pipeline(mesh, single_cloth_body(mesh), std::move(s));
  pipeline.keep_candidates(true);
  (void)pipeline.step(x0, x1);
  const auto* front = dynamic_cast<const FrontScheduler*>(pipeline.strategies().scheduler.get());
  const std::vector<FrontNode> last = front->front(pipeline.passes()[0].id);
  (void)pipeline.step(x1, x2);
  const TraversalPass& pass = pipeline.passes()[0];
  ASSERT_TRUE(pass.self);
  std::set<std::pair<Index, Index>> truth;
  for (const FacePair& p : pipeline.last_candidates().pairs.flatten()) truth.insert({std::min(p.a, p.b), std::max(p.a, p.b)});
  ASSERT_GT(truth.size(), 10u);

  const BvhTopology& bvh = *pass.side_a.bvh;
  const BvttWalk seq = walk_sequential(pass, {0, 0});
  const BvttWalk phc = walk_phc(pass, {0, 0}, 2, 4);
  const BvttWalk fr = walk_front(pass, {0, 0}, last, 2, 16);
  EXPECT_EQ(candidates_of(seq, bvh), truth);
  EXPECT_EQ(candidates_of(phc, bvh), truth);
  EXPECT_EQ(candidates_of(fr, bvh), truth);

  // The sequential walk is the binary kernel's: one BV test per pair node visited.
  const auto tests = [](const BvttWalk& w) { return std::count_if(w.visits.begin(), w.visits.end(), [](const WalkVisit& v) { return v.tested; }); };
  StepResult again;
  {
    PipelineStrategies q = contact_strategies(18, "sequential", 1, 0.0);
    q.width = 2;
    q.end_boxes = EndBoxMode::off;
    CcdPipeline sequential(mesh, single_cloth_body(mesh), std::move(q));
    (void)sequential.step(x0, x1);
    again = sequential.step(x1, x2);
  }
  EXPECT_EQ(std::uint64_t(tests(seq)), again.counters.bv_tests);
  EXPECT_EQ(tests(phc), tests(seq)) << "phc splits the same BVTT";
  EXPECT_LT(tests(fr), tests(seq)) << "the front starts below the top, where last step's walk stopped";

  // phc: a breadth-first top on one thread, then at least c · threads sub-tasks on both threads.
  EXPECT_GE(phc.tasks, 8);
  EXPECT_EQ(phc.visits.front().task, -1);
  std::set<int> threads;
  for (const WalkVisit& v : phc.visits) threads.insert(v.thread);
  EXPECT_EQ(threads, (std::set<int>{0, 1}));
  EXPECT_TRUE(std::is_sorted(phc.visits.begin(), phc.visits.end(), [](const WalkVisit& a, const WalkVisit& b) { return a.time < b.time; }));
  // front: chunks of 16 of last step's front nodes.
  EXPECT_EQ(fr.tasks, int((last.size() + 15) / 16));

  // A sub-tree: only pairs of its own nodes.
  const Index r = bvh.nodes[0].left;
  for (const WalkVisit& v : walk_sequential(pass, {r, r}).visits) {
    EXPECT_TRUE(v.a >= r && v.a < bvh.subtree_end(r));
    EXPECT_TRUE(v.b >= r && v.b < bvh.subtree_end(r));
  }
}

}  // namespace
}  // namespace ccdlab

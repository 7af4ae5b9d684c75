// Micro-benchmarks of the sequential pipeline's phases, per K, on one step of the built-in drape_fold scene
// (the step with the most candidates of the default run). Run: build/bin/ccdlab_microbench
//   --benchmark_filter=Traverse   (or TraverseWidth, SweptBv, Refit, Step, FloatTester, FloatTesterSurvivors, Tester)
// Google Benchmark interleaves nothing by itself: compare ratios within one invocation. CCDLAB_SIMD=avx2 (as for
// the command line, docs/config.md) limits the kernels, e.g. to time width 4's AVX2 walk on an AVX-512 CPU
// (CCDLAB_SIMD=sse4: the SSE2 walk).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <optional>
#include <random>
#include <sstream>
#include <string>

#include "framework/util/simd_target.hpp"
#include "framework/pipeline/brute_force.hpp"
#include "framework/traversal/bvtt.hpp"
#include "framework/scene/mesh_sequence.hpp"
#include "strategies/registry.hpp"
#include "strategies/scenes/drape_fold_scene.hpp"
#include "framework/queries/hard_cases.hpp"
#include "strategies/testers/float_tester.hpp"

namespace ccdlab {
namespace {

struct Fixture {
  MeshSequence scene = make_drape_fold_scene(DrapeFoldParams{});
  Positions x0 = scene.frame(12), x1 = scene.frame(13);
};
const Fixture& fixture() {
  static const Fixture f;
  return f;
}

std::unique_ptr<CcdPipeline> make_pipeline(int k) {
  PipelineStrategies s;
  s.k = k;
  s.builder = builder_registry().make({"median", {}});
  s.scheduler = scheduler_registry().make({"sequential", {}});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
  const Fixture& f = fixture();
  return std::make_unique<CcdPipeline>(f.scene.topology(), f.scene.bodies(), std::move(s));
}

void BM_Step(benchmark::State& state) {
  auto p = make_pipeline(int(state.range(0)));
  const Fixture& f = fixture();
  StepResult r;
  for (auto _ : state) benchmark::DoNotOptimize(r = p->step(f.x0, f.x1));
  state.counters["bv_tests"] = double(r.counters.bv_tests);
  state.counters["elementary_tests"] = double(r.counters.vf_tests + r.counters.ee_tests);
  state.counters["contacts"] = double(r.contacts.size());
}
BENCHMARK(BM_Step)->Arg(6)->Arg(14)->Arg(18)->Arg(26)->Unit(benchmark::kMillisecond);

void BM_SweptBv(benchmark::State& state) {
  const Fixture& f = fixture();
  AnyBvs bvs = make_bvs(int(state.range(0)));
  for (auto _ : state) {
    compute_face_bvs(f.scene.topology(), f.x0, f.x1, 0.0, bvs);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * f.scene.topology().num_faces());
}
BENCHMARK(BM_SweptBv)->Arg(6)->Arg(14)->Arg(18)->Arg(26)->Unit(benchmark::kMillisecond);

/// Times the sequential scheduler on `pass` (its volumes refit already): BV tests, candidates, ns per BV test.
void time_sequential_traversal(benchmark::State& state, const TraversalPass& pass) {
  auto scheduler = scheduler_registry().make({"sequential", {}});
  std::vector<PhaseTrace> traces;
  TraversalOutput out;
  for (auto _ : state) {
    out.clear();
    traces.clear();
    scheduler->collect(pass, out, traces);
  }
  state.counters["bv_tests"] = double(out.bv_tests);
  state.counters["candidates"] = double(out.pairs.size());
  state.counters["ns_per_bv_test"] = benchmark::Counter(double(out.bv_tests) * double(state.iterations()),
                                                        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Traverse(benchmark::State& state) {
  auto p = make_pipeline(int(state.range(0)));
  const Fixture& f = fixture();
  (void)p->step(f.x0, f.x1);  // builds and refits
  const BvhTopology& bvh = p->bvh(0);
  const AnyBvs& node_bvs = p->node_bvs(0);
  time_sequential_traversal(state, TraversalPass{0, &p->mesh(), {&bvh, &node_bvs}, {&bvh, &node_bvs}, true, 1});
}
BENCHMARK(BM_Traverse)->Arg(6)->Arg(14)->Arg(18)->Arg(26)->Unit(benchmark::kMillisecond);

// The traversal alone at BVH width 2 (binary) and 4 (wide view), K = 18, on the built-in step or, when
// CCDLAB_BENCH_STEP="a.ply b.ply" is set, on that real step (e.g. ../shared/data/meshes/rod-twist/3036.ply and
// 3037.ply). One thread, memory already touched: what a BV test costs without the step's page faults. Run with
// --benchmark_repetitions and compare ns_per_bv_test of the two widths within one invocation.
/// The step to time: the built-in one, or the two files named by CCDLAB_BENCH_STEP="a.ply b.ply".
struct BenchStep {
  std::optional<MeshSequence> files;
  const MeshSequence* scene = &fixture().scene;
  Positions x0 = fixture().x0, x1 = fixture().x1;
  BenchStep() {
    if (const char* names = std::getenv("CCDLAB_BENCH_STEP")) {
      std::istringstream in(names);
      std::string a, b;
      in >> a >> b;
      scene = &files.emplace(load_frame_files({a, b}));
      x0 = scene->frame(0), x1 = scene->frame(1);
    }
  }
};

void BM_TraverseWidth(benchmark::State& state) {
  const int width = int(state.range(0));
  const BenchStep step;
  const MeshSequence* scene = step.scene;
  const Positions &x0 = step.x0, &x1 = step.x1;
  PipelineStrategies s;
  s.width = width;
  s.builder = builder_registry().make({"median", {}});
  s.scheduler = scheduler_registry().make({"sequential", {}});
  s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
  CcdPipeline p(scene->topology(), scene->bodies(), std::move(s));
  (void)p.step(x0, x1);  // builds and refits both views
  time_sequential_traversal(state, p.passes().front());
}
BENCHMARK(BM_TraverseWidth)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

// The narrow phase of a whole step repeated in one process (memory touched, as in a simulation's later steps):
// ms per step of the candidates' narrow phase and the orphans', and of each stage (NarrowCounters), K = 18,
// sequential, one thread; on CCDLAB_BENCH_STEP's step if set. For comparing two builds' narrow phases with less
// noise than one-step runs; compare within one machine and period.
void BM_NarrowStep(benchmark::State& state) {
  const BenchStep step;
  CcdPipeline p(step.scene->topology(), step.scene->bodies(), [] {
    PipelineStrategies s;
    s.builder = builder_registry().make({"median", {}});
    s.scheduler = scheduler_registry().make({"sequential", {}});
    s.tester = tester_registry().make({"float", tester_registry().find("float")->defaults()});
    return s;
  }());
  (void)p.step(step.x0, step.x1);  // builds; first touch
  StepTimings sum;
  NarrowCounters stages;
  for (auto _ : state) {
    const StepResult r = p.step(step.x0, step.x1);
    sum.narrow_ms += r.timings.narrow_ms, sum.orphan_ms += r.timings.orphan_ms;
    stages += r.counters;
  }
  const double n = double(state.iterations());
  state.counters["narrow_ms"] = sum.narrow_ms / n;
  state.counters["orphans_ms"] = sum.orphan_ms / n;
  state.counters["narrow_orphans_ms"] = (sum.narrow_ms + sum.orphan_ms) / n;
  const auto per_step_ms = [n](std::uint64_t ns) { return double(ns) * 1e-6 / n; };
  state.counters["gather_ms"] = per_step_ms(stages.gather_ns);
  state.counters["kdop_ms"] = per_step_ms(stages.kdop_ns);
  state.counters["plane_ms"] = per_step_ms(stages.plane_ns);
  state.counters["split_ms"] = per_step_ms(stages.split_ns + stages.sixteenths_ns);
  state.counters["proximity_ms"] = per_step_ms(stages.proximity_ns);
  state.counters["test_ms"] = per_step_ms(stages.test_ns);
}
BENCHMARK(BM_NarrowStep)->Unit(benchmark::kMillisecond);

void BM_FloatTesterEdgeEdge(benchmark::State& state) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<EdgeEdgeQuery> queries(4096);
  for (auto& q : queries)
    for (Vec3* p : {&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1})
      *p = Vec3(u(rng), u(rng), u(rng));
  FloatTester t;
  std::size_t i = 0, hits = 0;
  for (auto _ : state) hits += t.edge_edge(queries[i++ & 4095]).hit;
  state.counters["hit_rate"] = double(hits) / double(state.iterations());
}
BENCHMARK(BM_FloatTesterEdgeEdge);

// `float` on queries like the narrow phase's survivors: each crosses the other's plane during the step (the cubic
// has a root to refine), a minority touching. One query at a time against the batched root search
// (float_roots.hpp). Args: 0 VF, 1 EE; 0 one at a time, 1 batched. ns per query = the time / 4096.
void BM_FloatTesterSurvivors(benchmark::State& state) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto slab = [&] { return Vec3(u(rng), u(rng), 0.05 * u(rng)); };
  const auto turned = [&](const Vec3& p) { return Vec3(p + 0.1 * Vec3(u(rng), u(rng), u(rng))); };
  constexpr std::size_t kQueries = 4096;
  std::vector<VertexFaceQuery> vf(kQueries);
  std::vector<EdgeEdgeQuery> ee(kQueries);
  for (std::size_t i = 0; i < kQueries; ++i) {
    const Vec3 a = slab(), b = slab(), c = slab(), v = 0.6 * Vec3(u(rng), u(rng), 0);
    vf[i] = {v + Vec3(0, 0, 1), a, b, c, v - Vec3(0, 0, 1) + 0.2 * Vec3(u(rng), u(rng), 0), turned(a), turned(b), turned(c)};
    const Vec3 e0 = 0.6 * Vec3(u(rng), u(rng), 1), e1 = 0.6 * Vec3(u(rng), u(rng), 1);
    ee[i] = {e0, e1, a, b, e0 - Vec3(0, 0, 1.2), e1 - Vec3(0, 0, 1.2), turned(a), turned(b)};
  }
  const FloatTester t;
  const bool edges = state.range(0) == 1, batched = state.range(1) == 1;
  std::vector<CcdHit> hits(kQueries);
  for (auto _ : state) {
    if (batched) {
      if (edges) t.edge_edges(ee, hits.data());
      else t.vertex_faces(vf, hits.data());
    } else {
      for (std::size_t i = 0; i < kQueries; ++i) hits[i] = edges ? t.edge_edge(ee[i]) : t.vertex_face(vf[i]);
    }
    benchmark::DoNotOptimize(hits.data());
  }
  std::size_t n_hit = 0;
  for (const CcdHit& h : hits) n_hit += h.hit;
  state.SetLabel(std::string(edges ? "EE" : "VF") + (batched ? " batched" : " one at a time"));
  state.counters["hit_rate"] = double(n_hit) / double(kQueries);
  state.SetItemsProcessed(std::int64_t(state.iterations() * kQueries));
}
BENCHMARK(BM_FloatTesterSurvivors)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);

// `float`'s batched kernel on hits and on misses apart: every query's features cross each other's plane
// (a root to refine), inside the other feature (a hit: the distance at the root, barycentrics, the record's
// coordinates) or beside it (a miss). Args: 0 VF, 1 EE; 0 hits, 1 misses. ns per query = the time / 4096;
// CCDLAB_SIMD picks the target (docs/narrow-phase.md, "SIMD: Google Highway").
void BM_FloatTesterHitsMisses(benchmark::State& state) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const bool edges = state.range(0) == 1, hit = state.range(1) == 0;
  const double beside = hit ? 0.0 : 3.0;  // how far the crossing lies from the other feature
  const auto wobble = [&](const Vec3& p) { return Vec3(p + 0.02 * Vec3(u(rng), u(rng), u(rng))); };
  constexpr std::size_t kQueries = 4096;
  std::vector<VertexFaceQuery> vf(kQueries);
  std::vector<EdgeEdgeQuery> ee(kQueries);
  for (std::size_t i = 0; i < kQueries; ++i) {
    const Vec3 a(-1 + 0.1 * u(rng), -1 + 0.1 * u(rng), 0.02 * u(rng)), b(1 + 0.1 * u(rng), -1 + 0.1 * u(rng), 0.02 * u(rng)),
        c(0.1 * u(rng), 1 + 0.1 * u(rng), 0.02 * u(rng));
    const Vec3 v(beside + 0.2 * u(rng), 0.2 * u(rng), 1);
    vf[i] = {v, a, b, c, wobble(v - Vec3(0, 0, 2)), wobble(a), wobble(b), wobble(c)};
    const Vec3 e0(-1, 0.3 * u(rng), 1), e1(1, 0.3 * u(rng), 1), f0(beside + 0.2 * u(rng), -1, 0.02 * u(rng)),
        f1(beside + 0.2 * u(rng), 1, 0.02 * u(rng));
    ee[i] = {e0, e1, f0, f1, wobble(e0 - Vec3(0, 0, 2)), wobble(e1 - Vec3(0, 0, 2)), wobble(f0), wobble(f1)};
  }
  const FloatTester t;
  std::vector<CcdHit> hits(kQueries);
  for (auto _ : state) {
    if (edges) t.edge_edges(ee, hits.data());
    else t.vertex_faces(vf, hits.data());
    benchmark::DoNotOptimize(hits.data());
  }
  std::size_t n_hit = 0;
  for (const CcdHit& h : hits) n_hit += h.hit;
  state.SetLabel(std::string(edges ? "EE" : "VF") + (hit ? " hits" : " misses"));
  state.counters["hit_rate"] = double(n_hit) / double(kQueries);
  state.SetItemsProcessed(std::int64_t(state.iterations() * kQueries));
}
BENCHMARK(BM_FloatTesterHitsMisses)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);

// The accuracy ladder on random edge–edge queries (mostly separated: the filters' case) and on every built-in
// hard case (degenerate: the expensive paths). Arg: the tester's place in the registry (the ladder's order).
const std::string& tester_name(std::int64_t i) { return tester_registry().entries().at(std::size_t(i)).name; }
std::unique_ptr<PrimitiveTester> make_tester(std::int64_t i) {
  return tester_registry().make({tester_name(i), tester_registry().find(tester_name(i))->defaults()});
}
const int kLastTester = int(tester_registry().entries().size()) - 1;

void BM_TesterRandomEdgeEdge(benchmark::State& state) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<EdgeEdgeQuery> queries(4096);
  for (auto& q : queries)
    for (Vec3* p : {&q.ea0_t0, &q.ea1_t0, &q.eb0_t0, &q.eb1_t0, &q.ea0_t1, &q.ea1_t1, &q.eb0_t1, &q.eb1_t1})
      *p = Vec3(u(rng), u(rng), u(rng));
  const auto t = make_tester(int(state.range(0)));
  std::size_t i = 0, hits = 0;
  for (auto _ : state) hits += t->edge_edge(queries[i++ & 4095]).hit;
  state.SetLabel(tester_name(state.range(0)));
  state.counters["hit_rate"] = double(hits) / double(state.iterations());
}
BENCHMARK(BM_TesterRandomEdgeEdge)->DenseRange(0, kLastTester);

void BM_TesterHardCases(benchmark::State& state) {
  static const std::vector<QuerySet> sets = hard_case_sets();
  const auto t = make_tester(int(state.range(0)));
  std::size_t queries = 0;
  for (auto _ : state)
    for (const QuerySet& s : sets) {
      for (const auto& q : s.vf) benchmark::DoNotOptimize(t->vertex_face(q));
      for (const auto& q : s.ee) benchmark::DoNotOptimize(t->edge_edge(q));
      queries += s.size();
    }
  state.SetLabel(tester_name(state.range(0)));
  state.SetItemsProcessed(std::int64_t(queries));
}
BENCHMARK(BM_TesterHardCases)->DenseRange(0, kLastTester)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace ccdlab

int main(int argc, char** argv) {
  if (const char* simd = std::getenv("CCDLAB_SIMD")) ccdlab::limit_simd_target(simd);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

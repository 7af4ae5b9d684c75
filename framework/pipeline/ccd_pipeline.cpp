#include "framework/pipeline/ccd_pipeline.hpp"

#include <chrono>

#include "framework/traversal/bvtt_tasks.hpp"
#include "framework/util/error.hpp"
#include "framework/util/memory.hpp"

namespace ccdlab {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return ms_between(t, Clock::now()); }

/// Chunk sizes of the parallel phases: large enough to amortise scheduling, small enough to balance.
constexpr std::size_t kCandidateChunk = 512;  // 128 before: n-body's narrow phase at 2 threads 1.04x (fewer
                                              // dispatches, clock reads, batch paddings; same answers)
constexpr std::size_t kOrphanChunk = 8192;   // 2048 before: rod-twist's orphans 5.9 -> 5.2 ms (1 thread), 3.8 -> 3.0
                                              // (2 threads); per-chunk costs, now that a pair's stage 1 is ~2.5 ns
constexpr std::size_t kFaceChunk = 2048;

/// The swept k-DOP of face f over the step: the union of its vertices' swept 26-DOPs, inflated by half the
/// thickness (FeatureBounds::face_dop: the one definition, shared with the narrow phase's stage 1).
template <class BV>
struct SweptFaceBv {
  const TriMesh& mesh;
  const FeatureBounds& bounds;
  BV operator()(Index f) const { return bounds.face_dop<BV::k>(mesh.face(f)); }
};

}  // namespace

AnyWideBvs make_wide_bvs(int k) {
  switch (k) {
    case 6: return WideBvs<KDop<6>>{};
    case 14: return WideBvs<KDop<14>>{};
    case 18: return WideBvs<KDop<18>>{};
    case 26: return WideBvs<KDop<26>>{};
  }
  fail("bv.k: expected one of {}, got {}", kKdopKs, k);
}

AnyBvs make_bvs(int k) {
  switch (k) {
    case 6: return BvArray<KDop<6>>{};
    case 14: return BvArray<KDop<14>>{};
    case 18: return BvArray<KDop<18>>{};
    case 26: return BvArray<KDop<26>>{};
  }
  fail("bv.k: expected one of {}, got {}", kKdopKs, k);
}

void compute_face_bvs(const TriMesh& mesh, const Positions& x0, const Positions& x1, double thickness, AnyBvs& out,
                      int threads, PhaseTrace* trace) {
  PhaseTrace unused;
  FeatureBounds vertex_dops;
  vertex_dops.update(x0, x1, thickness, threads, trace ? *trace : unused);
  std::visit(
      [&](auto& bvs) {
        using BV = typename std::decay_t<decltype(bvs)>::value_type;
        bvs.resize(mesh.num_faces());
        const SweptFaceBv<BV> swept{mesh, vertex_dops};
        parallel_chunks(std::size_t(mesh.num_faces()), kFaceChunk, threads, trace ? *trace : unused,
                        [&](std::size_t b, std::size_t e, int) {
                          for (std::size_t f = b; f < e; ++f) bvs[f] = swept(Index(f));
                        });
      },
      out);
}

std::uint64_t estimate_pipeline_bytes(const TriMesh& mesh, int k, int width, std::size_t orphan_pairs) {
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
  const std::uint64_t orphans = std::uint64_t(orphan_pairs) * sizeof(EdgeEdgePair);
  const std::uint64_t frames = 2 * v * sizeof(Vec3);
  return bvh + wide + feature_boxes + ownership + orphans + frames;
}

CcdPipeline::CcdPipeline(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies)
    : mesh_(mesh),
      rules_(mesh, std::move(bodies)),
      strategies_(std::move(strategies)),
      narrow_(mesh_, *strategies_.tester, strategies_.narrow,
              [this](Index f) {
                const int b = rules_.body_of_face(f);
                return rules_.bodies_interact(b, b);
              }),
      budget_(strategies_.memory_limit, strategies_.stream_slices) {
  if (strategies_.threads < 1 || strategies_.threads > kMaxThreads)
    fail("threads: expected an integer from 1 to {}, got {}", kMaxThreads, strategies_.threads);
  if (strategies_.normal_cones && strategies_.tester->thickness() > 0)
    fail("normal_cones: culling is exact only for contact at zero distance; got tester thickness {}",
         strategies_.tester->thickness());
  if (const std::uint64_t limit = strategies_.memory_limit; limit > 0) {
    const std::uint64_t resident = current_rss_bytes(),
                        need = estimate_pipeline_bytes(mesh_, strategies_.k, strategies_.width, orphans().vf.size() + orphans().ee.size());
    if (resident + need > limit)
      fail("memory_limit {}: this run needs about {} before its first step ({} resident now with the scene, {} more "
           "for the BVH, feature boxes and orphan set of {} triangles); lower the scene's size or raise memory_limit",
           format_bytes(limit), format_bytes(resident + need), format_bytes(resident), format_bytes(need),
           mesh_.num_faces());
  }
  const auto& bl = rules_.bodies();
  bodies_.resize(bl.size());
  for (std::size_t b = 0; b < bl.size(); ++b) {
    for (Index f = bl[b].face_begin; f < bl[b].face_end; ++f) bodies_[b].faces.push_back(f);
    bodies_[b].node_bvs = make_bvs(strategies_.k);
    bodies_[b].node_wide = make_wide_bvs(strategies_.k);
  }
  // Passes: self passes first, then body pairs; ids are stable for the pipeline's lifetime.
  const auto add_pass = [&](int i, int j) {
    BodyState& a = bodies_[i];
    BodyState& b = bodies_[j];
    TraversalPass pass{int(passes_.size()), &mesh_, &a.bvh, &a.node_bvs, &b.bvh, &b.node_bvs, i == j, strategies_.threads};
    pass.split_threads = strategies_.split_threads > 0 ? strategies_.split_threads : strategies_.threads;
    if (i == j && strategies_.normal_cones) pass.skip_root = &a.skip_root;
    if (strategies_.width == 4) {
      pass.wide_layout_a = &a.wide_layout;
      pass.wide_a = &a.node_wide;
      pass.wide_layout_b = &b.wide_layout;
      pass.wide_b = &b.node_wide;
    }
    passes_.push_back(pass);
  };
  for (int i = 0; i < int(bl.size()); ++i)
    if (rules_.bodies_interact(i, i) && !bodies_[i].faces.empty()) add_pass(i, i);
  for (int i = 0; i < int(bl.size()); ++i)
    for (int j = i + 1; j < int(bl.size()); ++j)
      if (rules_.bodies_interact(i, j) && !bodies_[i].faces.empty() && !bodies_[j].faces.empty()) add_pass(i, j);
}

CcdPipeline::~CcdPipeline() = default;

void CcdPipeline::build_hierarchies(const Positions& x_t0, const Positions& x_t1, PhaseTrace& trace) {
  for (BodyState& body : bodies_) {
    UninitializedVector<Box3> boxes(body.faces.size());  // large: in huge pages (memory.hpp)
    parallel_chunks(body.faces.size(), kFaceChunk, strategies_.threads, trace, [&](std::size_t b, std::size_t e, int) {
      for (std::size_t i = b; i < e; ++i) {
        Box3 box;
        for (Index v : mesh_.face(body.faces[i])) {
          box.grow(x_t0[v]);
          box.grow(x_t1[v]);
        }
        boxes[i] = box;
      }
    });
    body.bvh = strategies_.builder->build(body.faces, boxes, {strategies_.threads, &trace});
    if (body.bvh.nodes.empty()) continue;
    const auto t1 = Clock::now();
    // Restructuring units, independent of the thread count.
    body.restructure_roots.clear();
    const Index max_leaves = std::max<Index>(64, body.bvh.num_leaves() / 64);
    std::vector<Index> stack{0};
    while (!stack.empty()) {
      const Index n = stack.back();
      stack.pop_back();
      if (body.bvh.leaf_count[n] <= max_leaves) {
        if (body.bvh.leaf_count[n] > 2) body.restructure_roots.push_back(n);
      } else {
        stack.push_back(body.bvh.nodes[n].right);
        stack.push_back(body.bvh.nodes[n].left);
      }
    }
    body.quality_ref.assign(body.restructure_roots.size(), 0.0);  // set after the first refit
    trace.serial_ms += ms_since(t1);
  }
  built_ = true;
}

namespace {

/// Σ size of the inner nodes of a sub-tree ÷ size of its root: grows when refit lets siblings overlap.
template <class Vec>
double subtree_quality(const BvhTopology& bvh, const Vec& bvs, Index root) {
  const double root_size = bvs[root].size_measure();
  if (!(root_size > 0)) return 0;
  double sum = 0;
  for (Index i = root; i < bvh.subtree_end(root); ++i)
    if (!bvh.nodes[i].is_leaf()) sum += bvs[i].size_measure();
  return sum / root_size;
}

}  // namespace

std::uint64_t CcdPipeline::restructure(const Positions& x_t0, const Positions& x_t1, PhaseTrace& trace) {
  std::uint64_t rebuilt = 0;
  for (BodyState& body : bodies_) {
    std::visit(
        [&](auto& node_bvs) {
          using BV = typename std::decay_t<decltype(node_bvs)>::value_type;
          BvhTopology& bvh = body.bvh;
          const std::size_t units = body.restructure_roots.size();
          std::vector<char> degraded(units, 0);
          std::vector<BvhTopology> replacement(units);
          PhaseTrace part;
          parallel_chunks(units, 1, strategies_.threads, part, [&](std::size_t u, std::size_t, int) {
            const Index r = body.restructure_roots[u];
            const double q = subtree_quality(bvh, node_bvs, r);
            if (body.quality_ref[u] == 0) {
              body.quality_ref[u] = q;  // first refit after a (re)build
              return;
            }
            if (q <= strategies_.restructure_threshold * body.quality_ref[u]) return;
            // Degraded: rebuild this sub-tree over its faces from their current swept boxes.
            std::vector<Index> faces = subtree_faces(bvh, r);
            std::vector<Box3> boxes(faces.size());
            for (std::size_t i = 0; i < faces.size(); ++i)
              for (Index v : mesh_.face(faces[i])) {
                boxes[i].grow(x_t0[v]);
                boxes[i].grow(x_t1[v]);
              }
            replacement[u] = strategies_.builder->build(faces, boxes);
            degraded[u] = 1;
          });
          trace.task_ms.insert(trace.task_ms.end(), part.task_ms.begin(), part.task_ms.end());
          const auto t0 = Clock::now();
          for (std::size_t u = 0; u < units; ++u) {
            if (!degraded[u]) continue;
            const Index r = body.restructure_roots[u];
            // A new topology version: the refit plan, normal cones and fronts are cut again from it.
            replace_subtree(bvh, r, replacement[u]);
            // Its leaves now hold other faces: their swept volumes are computed again.
            refit_subtree(bvh, node_bvs, r, SweptFaceBv<BV>{mesh_, narrow_.bounds()});
            for (Index p = bvh.nodes[r].parent; p >= 0; p = bvh.nodes[p].parent)
              refit_node(bvh, node_bvs, p, LeavesInPlace{});
            body.quality_ref[u] = subtree_quality(bvh, node_bvs, r);
            ++rebuilt;
          }
          trace.serial_ms += ms_since(t0);
        },
        body.node_bvs);
  }
  return rebuilt;
}

void CcdPipeline::refit_body(BodyState& body, PhaseTrace& trace) {
  const BvhTopology& bvh = body.bvh;
  std::visit(
      [&](auto& node_bvs) {
        using BV = typename std::decay_t<decltype(node_bvs)>::value_type;
        node_bvs.resize(bvh.nodes.size());  // uninitialised: the leaves' pass touches every page first, in parallel
        // The leaves first, in node order: their faces and vertex 26-DOPs are scattered reads, which the CPU
        // overlaps across independent iterations. (Leaves, inner nodes and wide records fused into the bottom-up
        // sweep below measured 1.00× against 1.15× for separate passes: docs/pipeline.md, section 2.)
        const SweptFaceBv<BV> swept{mesh_, narrow_.bounds()};
        parallel_chunks(bvh.nodes.size(), 2 * kFaceChunk, strategies_.threads, trace, [&](std::size_t b, std::size_t e, int) {
          for (std::size_t i = b; i < e; ++i)
            if (bvh.nodes[i].is_leaf()) node_bvs[i] = swept(bvh.nodes[i].face);
        });
        const RefitPlan& plan = bvh.refit_plan();  // cut again whenever restructuring changed the topology
        const LeavesInPlace leaf_bv;
        parallel_chunks(plan.subtrees.size(), 1, strategies_.threads, trace, [&](std::size_t b, std::size_t e, int) {
          for (std::size_t s = b; s < e; ++s) refit_subtree(bvh, node_bvs, plan.subtrees[s], leaf_bv);
        });
        const auto t0 = Clock::now();
        for (Index i : plan.top) refit_node(bvh, node_bvs, i, leaf_bv);
        trace.serial_ms += ms_since(t0);
      },
      body.node_bvs);
}

void CcdPipeline::refit_wide(BodyState& body, PhaseTrace& trace) {
  const BvhTopology& bvh = body.bvh;
  const bool recut = body.wide_layout.version != bvh.version;  // first step, or after restructuring
  if (recut) body.wide_layout = WideLayout::of(bvh, mesh_.faces());
  const WideLayout& layout = body.wide_layout;
  std::visit(
      [&](auto& node_wide) {
        using Bounds = typename std::decay_t<decltype(node_wide)>::value_type;
        using Vec = BvArray<typename Bounds::Volume>;
        const Vec& bvs = std::get<Vec>(body.node_bvs);
        node_wide.resize(layout.lanes.size());
        parallel_chunks(layout.lanes.size(), 4096, strategies_.threads, trace, [&](std::size_t b, std::size_t e, int) {
          for (std::size_t w = b; w < e; ++w) {
            // The lanes are scattered over the binary array: ask for the next nodes' early (memory-bound loop).
            if (w + 8 < e)
              for (Index c : layout.lanes[w + 8].node)
                if (c >= 0) __builtin_prefetch(&bvs[c]);
            if (recut) node_wide[w].lanes = layout.lanes[w];  // the LaneIds: fixed until the topology changes
            refit_wide_bounds(layout, bvs, Index(w), node_wide[w]);
          }
        });
      },
      body.node_wide);
}

/// One thread's narrow-phase state over a parallel loop: what it found and counted, and its batch memory.
struct CcdPipeline::NarrowLocal {
  Contacts contacts;
  NarrowCounters counters;
  NarrowScratch scratch;
  std::vector<VertexFacePair> tested_vf;
  std::vector<EdgeEdgePair> tested_ee;
};

template <class Gather>
void CcdPipeline::narrow_chunk(NarrowLocal& l, Gather&& gather) {
  FeatureBatch& batch = l.scratch.batch;
  batch.clear();
  const auto t = Clock::now();
  const std::uint64_t kdop_before = l.counters.kdop_ns;
  gather(batch, l.counters);
  // What a gather spent on stage 1 (gather_orphans) counts as stage 1, not twice.
  l.counters.gather_ns += std::uint64_t(ms_since(t) * 1e6) - (l.counters.kdop_ns - kdop_before);
  if (record_tested_) {
    l.tested_vf.insert(l.tested_vf.end(), batch.vf.begin(), batch.vf.end());
    l.tested_ee.insert(l.tested_ee.end(), batch.ee.begin(), batch.ee.end());
  }
  narrow_.run(l.scratch, l.contacts, l.counters);
}

void CcdPipeline::merge_narrow(const std::vector<PerThread<NarrowLocal>>& local, StepResult& result,
                               PhaseTrace& trace) {
  // In thread order; the final sort makes the result independent of the schedule.
  const auto t0 = Clock::now();
  std::size_t found = 0;
  for (const auto& per_thread : local) found += per_thread.value.contacts.size();
  result.contacts.reserve(result.contacts.size() + found);
  for (const auto& per_thread : local) {
    const NarrowLocal& l = per_thread.value;
    result.contacts.insert(result.contacts.end(), l.contacts.begin(), l.contacts.end());
    result.counters += l.counters;
    result.tested_vf.insert(result.tested_vf.end(), l.tested_vf.begin(), l.tested_vf.end());
    result.tested_ee.insert(result.tested_ee.end(), l.tested_ee.begin(), l.tested_ee.end());
  }
  trace.serial_ms += ms_since(t0);
}

template <class Gather>
void CcdPipeline::narrow_in_parallel(std::size_t n, std::size_t chunk, const char* phase, StepResult& result,
                                     Gather&& gather) {
  std::vector<PerThread<NarrowLocal>> local(strategies_.threads);
  PhaseTrace trace{phase, Distribution::dynamic, 0, {}, {}};
  parallel_chunks(n, chunk, strategies_.threads, trace, [&](std::size_t b, std::size_t e, int tid) {
    narrow_chunk(local[tid].value, [&](FeatureBatch& batch, NarrowCounters& c) { gather(b, e, batch, c); });
  });
  merge_narrow(local, result, trace);
  result.traces.push_back(std::move(trace));
}

StepResult CcdPipeline::step(const Positions& x_t0, const Positions& x_t1) {
  if (Index(x_t0.size()) != mesh_.num_vertices() || Index(x_t1.size()) != mesh_.num_vertices())
    fail("step: frames have {} and {} vertices, the mesh has {}", x_t0.size(), x_t1.size(), mesh_.num_vertices());
  const int threads = strategies_.threads;
  StepResult result;
  StepCounters& c = result.counters;
  StepTimings& tm = result.timings;
  const auto t_start = Clock::now();
  reset_peak_rss();  // this step's peak, not the run's
  const std::uint64_t faults_at_start = minor_page_faults();

  auto t = Clock::now();
  if (!built_) {
    PhaseTrace build{"build", Distribution::dynamic, 0, {}, {}};
    build_hierarchies(x_t0, x_t1, build);
    tm.build_ms = ms_since(t);
    result.traces.push_back(std::move(build));
  }

  // Swept volumes: every vertex's 26-DOP (the narrow phase's stage 1 bounds); the leaves are cut from them in
  // the refit.
  t = Clock::now();
  PhaseTrace swept{"swept_bv", Distribution::dynamic, 0, {}, {}};
  narrow_.begin_step(x_t0, x_t1, threads, swept);
  result.traces.push_back(std::move(swept));
  tm.swept_bv_ms = ms_since(t);

  t = Clock::now();
  for (BodyState& body : bodies_) {
    PhaseTrace trace{"refit", Distribution::dynamic, 0, {}, {}};
    refit_body(body, trace);
    result.traces.push_back(std::move(trace));
  }
  if (strategies_.restructure_threshold > 0) {
    PhaseTrace trace{"restructure", Distribution::dynamic, 0, {}, {}};
    c.restructured = restructure(x_t0, x_t1, trace);
    result.traces.push_back(std::move(trace));
  }
  if (strategies_.width == 4)
    for (BodyState& body : bodies_) {
      PhaseTrace trace{"refit_wide", Distribution::dynamic, 0, {}, {}};
      refit_wide(body, trace);
      result.traces.push_back(std::move(trace));
    }
  tm.refit_ms = ms_since(t);
  if (strategies_.normal_cones) {
    const auto tc = Clock::now();
    PhaseTrace cone_trace{"normal_cones", Distribution::dynamic, 0, {}, {}};
    face_patch_.assign(mesh_.num_faces(), -1);
    double cones_build_ms = 0;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      BodyState& body = bodies_[b];
      if (!rules_.bodies_interact(int(b), int(b)) || body.bvh.nodes.empty()) continue;
      if (!body.cones || body.cones_version != body.bvh.version) {
        // One-time topology analysis (which patches are disks): build time, like the BVH's.
        const auto tb = Clock::now();
        body.cones = std::make_unique<NormalConeCuller>(mesh_, body.bvh, threads);
        body.cones_version = body.bvh.version;
        const double ms = ms_since(tb);
        tm.build_ms += ms;
        cones_build_ms += ms;
      }
      PhaseTrace body_trace;
      result.traversal.cone_culled += body.cones->update(x_t0, x_t1, threads, body_trace);
      cone_trace.serial_ms += body_trace.serial_ms;
      cone_trace.task_ms.insert(cone_trace.task_ms.end(), body_trace.task_ms.begin(), body_trace.task_ms.end());
      result.traversal.contour_edges += body.cones->contour_edge_tests();
      body.skip_root = body.cones->skip_root();
      // Orphan pairs of two faces in one skipped patch cannot touch either (same height-field argument).
      for (Index i = 0; i < body.bvh.size(); ++i)
        if (body.bvh.nodes[i].is_leaf()) face_patch_[body.bvh.nodes[i].face] = body.skip_root[i];
    }
    tm.cones_ms = ms_since(tc) - cones_build_ms;
    result.traces.push_back(std::move(cone_trace));
    if (cones_build_ms > 0) result.traces.push_back(PhaseTrace{"build", Distribution::dynamic, cones_build_ms, {}, {}});
  }

  // The step before's candidate pages are kept for this step's candidates while the step fits with them resident
  // (MemoryBudget::fits). Freeing them at every step made each step fault and zero them again: rod-twist's
  // traversal at 2 threads 1.11x slower (docs/reliability.md, "Memory").
  const std::size_t faces = std::size_t(mesh_.num_faces());
  std::uint64_t resident = budget_.limit() > 0 ? current_rss_bytes() : 0;
  if (!budget_.fits(resident, faces)) {
    candidates_.pairs.release();
    if (budget_.limit() > 0) resident = current_rss_bytes();
  }
  const MemoryPlan plan = budget_.plan(resident, faces);
  traverse_and_test(plan, result);
  budget_.record(c.candidate_pairs, result.traversal.front_bytes);
  result.memory.limit_bytes = budget_.limit();
  result.memory.slices = plan.streamed ? plan.slices : 0;

  test_orphans(result);

  t = Clock::now();
  sort_contacts(result.contacts, sort_scratch_);
  result.traces.push_back(PhaseTrace{"sort_contacts", Distribution::dynamic, ms_since(t), {}, {}});  // serial
  tm.total_ms = ms_since(t_start);
  result.memory.peak_rss_bytes = peak_rss_bytes();
  result.memory.page_faults = minor_page_faults() - faults_at_start;
  return result;
}

void CcdPipeline::test_candidates(StepResult& result) {
  const auto t = Clock::now();
  const CandidateList& pairs = candidates_.pairs;
  result.counters.candidate_pairs += pairs.size();
  narrow_in_parallel(pairs.size(), kCandidateChunk, "narrow", result,
                     [&](std::size_t b, std::size_t e, FeatureBatch& batch, NarrowCounters&) {
                       pairs.for_each_span(b, e, [&](std::span<const FacePair> s) { narrow_.gather(s, batch); });
                     });
  result.timings.narrow_ms += ms_since(t);
}

void CcdPipeline::test_orphans(StepResult& result) {
  const auto t = Clock::now();
  StepCounters& c = result.counters;
  const std::uint64_t vf_before = c.vf_pairs, ee_before = c.ee_pairs, tests_before = c.vf_tests + c.ee_tests;
  const OrphanSet& orphans = this->orphans();
  const Representatives& reps = narrow_.representatives();
  // With normal cones, orphan pairs of two faces in one skipped patch cannot touch (same height-field argument
  // as for the candidates the traversal skipped).
  const bool cull = strategies_.normal_cones;
  auto same_skipped_patch = [this](Index f, Index g) { return face_patch_[f] >= 0 && face_patch_[f] == face_patch_[g]; };
  const std::size_t nvf = orphans.vf.size(), n = nvf + orphans.ee.size();
  narrow_in_parallel(n, kOrphanChunk, "orphans", result,
                     [&](std::size_t b, std::size_t e, FeatureBatch& batch, NarrowCounters& lc) {
                       if (!cull) {  // the chunk as it is
                         const std::span<const VertexFacePair> vf(orphans.vf.data() + std::min(b, nvf), orphans.vf.data() + std::min(e, nvf));
                         const std::span<const EdgeEdgePair> ee(orphans.ee.data() + (std::max(b, nvf) - nvf), orphans.ee.data() + (std::max(e, nvf) - nvf));
                         if (record_tested_) {  // every orphan is recorded as gathered: copy them whole
                           batch.vf.insert(batch.vf.end(), vf.begin(), vf.end());
                           batch.ee.insert(batch.ee.end(), ee.begin(), ee.end());
                         } else {
                           narrow_.gather_orphans(vf, ee, batch, lc);
                         }
                         return;
                       }
                       for (std::size_t i = b; i < std::min(e, nvf); ++i) {
                         const VertexFacePair& p = orphans.vf[i];
                         if (same_skipped_patch(reps.face_of_vertex(p.v), p.f)) ++lc.orphans_culled;
                         else batch.vf.push_back(p);
                       }
                       for (std::size_t i = std::max(b, nvf); i < e; ++i) {
                         const EdgeEdgePair& p = orphans.ee[i - nvf];
                         if (same_skipped_patch(reps.face_of_edge(p.a), reps.face_of_edge(p.b))) ++lc.orphans_culled;
                         else batch.ee.push_back(p);
                       }
                     });
  c.orphan_vf = c.vf_pairs - vf_before;  // orphan pairs considered (culled ones counted apart)
  c.orphan_ee = c.ee_pairs - ee_before;
  c.orphan_tests = c.vf_tests + c.ee_tests - tests_before;
  result.timings.orphan_ms = ms_since(t);
}

void CcdPipeline::traverse_and_test(const MemoryPlan& plan, StepResult& result) {
  candidates_.clear();
  double traverse_ms = 0;
  if (!plan.streamed) {
    const auto t = Clock::now();
    candidates_.pairs.reserve(strategies_.threads, plan.expected_pairs);
    // The narrow phase takes the candidates as the traversal finds them (TraversalOutput::hand_over), on
    // the same thread; its time there is counted as narrow, not traversal (the threads' mean: they run at once).
    const int threads = strategies_.threads;
    std::vector<PerThread<NarrowLocal>> local(threads);
    struct Taken {
      std::uint64_t pairs = 0;
      double ms = 0;
    };
    std::vector<PerThread<Taken>> taken(threads);
    struct Unset {  // the consumer refers to this frame: never left set, even when a scheduler throws
      TraversalOutput& out;
      ~Unset() { out.consumer = nullptr; }
    } unset{candidates_};
    if (!keep_candidates_)
      candidates_.consumer = [&](int tid, std::span<const FacePair> pairs) {
        const auto tc = Clock::now();
        for (std::size_t b = 0; b < pairs.size(); b += kCandidateChunk) {
          const auto piece = pairs.subspan(b, std::min(kCandidateChunk, pairs.size() - b));
          narrow_chunk(local[tid].value, [&](FeatureBatch& batch, NarrowCounters&) { narrow_.gather(piece, batch); });
        }
        taken[tid].value.pairs += pairs.size();
        taken[tid].value.ms += ms_since(tc);
      };
    for (const TraversalPass& pass : passes_) strategies_.scheduler->collect(pass, candidates_, result.traces);
    candidates_.consumer = nullptr;
    double narrow_ms = 0;
    for (const auto& tk : taken) {
      result.counters.candidate_pairs += tk.value.pairs;
      narrow_ms += tk.value.ms / threads;
    }
    traverse_ms = ms_since(t) - narrow_ms;
    const auto t_merge = Clock::now();
    PhaseTrace trace{"narrow_in_traversal", Distribution::dynamic, 0, {}, {}};  // its tasks are the traversal's
    merge_narrow(local, result, trace);
    result.traces.push_back(std::move(trace));
    result.timings.narrow_ms += narrow_ms + ms_since(t_merge);
    test_candidates(result);  // what is left in the parts
  } else {
    // Each pass cut into slices (the BVTT nodes of one breadth-first level, BV tests counted, leaf pairs met
    // on the way kept as candidates); each slice traversed on its own and its scheduler state (a front)
    // released after it, and the candidates tested whenever `flush_pairs` are buffered. The pass's own kept
    // state is released too: a memory-bounded step keeps no front across steps.
    for (const TraversalPass& pass : passes_) {
      strategies_.scheduler->release(pass.id);
      if (pass.bvh_a->nodes.empty() || pass.bvh_b->nodes.empty()) continue;
      auto t = Clock::now();
      std::vector<BvttNode> slices;
      with_bvtt_view(pass, [&](const auto& view) { slices = expand_breadth_first(view, plan.slices, candidates_); });
      traverse_ms += ms_since(t);
      for (std::size_t s = 0; s < slices.size(); ++s) {
        TraversalPass slice = pass;
        slice.root = slices[s];
        slice.id = -1 - pass.id;  // never a kept pass's id
        t = Clock::now();
        strategies_.scheduler->collect(slice, candidates_, result.traces);
        strategies_.scheduler->release(slice.id);
        traverse_ms += ms_since(t);
        if (candidates_.pairs.size() >= plan.flush_pairs) {
          test_candidates(result);
          candidates_.pairs.release();  // free, not just clear: the point is the memory
        }
      }
    }
    test_candidates(result);
  }
  result.counters.bv_tests = candidates_.bv_tests;
  const std::uint64_t culled = result.traversal.cone_culled, edges = result.traversal.contour_edges;
  result.traversal = candidates_.stats;
  result.traversal.bv_tests = candidates_.bv_tests;
  result.traversal.cone_culled = culled;
  result.traversal.contour_edges = edges;
  result.timings.traverse_ms = traverse_ms;
}

const TraversalOutput& CcdPipeline::last_candidates() const {
  if (!keep_candidates_) fail("last_candidates: the pipeline keeps the candidates only after keep_candidates(true)");
  return candidates_;
}

std::size_t CcdPipeline::memory_bytes() const {
  const Ownership& own = narrow_.representatives().owners();
  std::size_t bytes = mesh_.memory_bytes() + own.vertex_owner.size() * sizeof(Index) +
                      own.edge_owner.size() * sizeof(Index) + own.owned_mask.size() + narrow_.memory_bytes() +
                      orphans().vf.size() * sizeof(VertexFacePair) + orphans().ee.size() * sizeof(EdgeEdgePair);
  for (const BodyState& b : bodies_)
    bytes += b.bvh.memory_bytes() + std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, b.node_bvs) +
             b.wide_layout.memory_bytes() + std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, b.node_wide);
  return bytes;
}

}  // namespace ccdlab

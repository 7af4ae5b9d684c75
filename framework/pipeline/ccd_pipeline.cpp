#include "framework/pipeline/ccd_pipeline.hpp"

#include <chrono>

#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

}  // namespace

AnyBvs make_bvs(int k) {
  switch (k) {
    case 6: return std::vector<KDop<6>>{};
    case 14: return std::vector<KDop<14>>{};
    case 18: return std::vector<KDop<18>>{};
    case 26: return std::vector<KDop<26>>{};
  }
  fail("bv.k: expected one of 6, 14, 18, 26, got {}", k);
}

void compute_face_bvs(const TriMesh& mesh, const Positions& x0, const Positions& x1, double thickness, AnyBvs& out) {
  std::visit(
      [&](auto& bvs) {
        using BV = typename std::decay_t<decltype(bvs)>::value_type;
        bvs.resize(mesh.num_faces());
        for (Index f = 0; f < mesh.num_faces(); ++f) {
          const Face& t = mesh.face(f);
          bvs[f] = swept_triangle_bv<BV>(x0[t[0]], x0[t[1]], x0[t[2]], x1[t[0]], x1[t[1]], x1[t[2]], thickness);
        }
      },
      out);
}

CcdPipeline::CcdPipeline(const TriMesh& mesh, std::vector<Body> bodies, PipelineStrategies strategies)
    : mesh_(mesh),
      rules_(mesh, std::move(bodies)),
      strategies_(std::move(strategies)),
      owners_(assign_owners(mesh)),
      narrow_(mesh_, owners_, *strategies_.tester),
      face_bvs_(make_bvs(strategies_.k)) {
  orphans_ = build_orphan_set(mesh_, owners_, [this](Index f) {
    int b = rules_.body_of_face(f);
    return rules_.bodies_interact(b, b);
  });
  const auto& bl = rules_.bodies();
  bodies_.resize(bl.size());
  for (std::size_t b = 0; b < bl.size(); ++b) {
    for (Index f = bl[b].face_begin; f < bl[b].face_end; ++f) bodies_[b].faces.push_back(f);
    bodies_[b].node_bvs = make_bvs(strategies_.k);
  }
  // Passes: self passes first, then body pairs; ids are stable for the pipeline's lifetime.
  for (int i = 0; i < int(bl.size()); ++i)
    if (rules_.bodies_interact(i, i) && !bodies_[i].faces.empty())
      passes_.push_back({int(passes_.size()), &mesh_, &bodies_[i].bvh, &bodies_[i].node_bvs, &bodies_[i].bvh,
                         &bodies_[i].node_bvs, true});
  for (int i = 0; i < int(bl.size()); ++i)
    for (int j = i + 1; j < int(bl.size()); ++j)
      if (rules_.bodies_interact(i, j) && !bodies_[i].faces.empty() && !bodies_[j].faces.empty())
        passes_.push_back({int(passes_.size()), &mesh_, &bodies_[i].bvh, &bodies_[i].node_bvs, &bodies_[j].bvh,
                           &bodies_[j].node_bvs, false});
}

CcdPipeline::~CcdPipeline() = default;

void CcdPipeline::build_hierarchies(const Positions& x_t0, const Positions& x_t1) {
  for (BodyState& body : bodies_) {
    std::vector<Box3> boxes(body.faces.size());
    for (std::size_t i = 0; i < body.faces.size(); ++i)
      for (Index v : mesh_.face(body.faces[i])) {
        boxes[i].grow(x_t0[v]);
        boxes[i].grow(x_t1[v]);
      }
    body.bvh = strategies_.builder->build(body.faces, boxes);
  }
  built_ = true;
}

StepResult CcdPipeline::step(const Positions& x_t0, const Positions& x_t1) {
  if (Index(x_t0.size()) != mesh_.num_vertices() || Index(x_t1.size()) != mesh_.num_vertices())
    fail("step: frames have {} and {} vertices, the mesh has {}", x_t0.size(), x_t1.size(), mesh_.num_vertices());
  StepResult result;
  StepCounters& c = result.counters;
  StepTimings& tm = result.timings;
  const auto t_start = Clock::now();

  auto t = Clock::now();
  if (!built_) build_hierarchies(x_t0, x_t1);
  tm.build_ms = ms_since(t);

  t = Clock::now();
  compute_face_bvs(mesh_, x_t0, x_t1, strategies_.tester->thickness(), face_bvs_);
  tm.swept_bv_ms = ms_since(t);

  t = Clock::now();
  for (BodyState& body : bodies_)
    std::visit(
        [&](auto& node_bvs) {
          using Vec = std::decay_t<decltype(node_bvs)>;
          const Vec& leaf = std::get<Vec>(face_bvs_);
          refit(body.bvh, node_bvs, [&](Index f) { return leaf[f]; });
        },
        body.node_bvs);
  tm.refit_ms = ms_since(t);

  t = Clock::now();
  candidates_.clear();
  for (const TraversalPass& pass : passes_) strategies_.scheduler->collect(pass, candidates_);
  c.bv_tests = candidates_.bv_tests;
  c.candidate_pairs = candidates_.pairs.size();
  tm.traverse_ms = ms_since(t);

  t = Clock::now();
  narrow_.begin_step(x_t0, x_t1);
  StepResult* record = record_tested_ ? &result : nullptr;
  for (const FacePair& p : candidates_.pairs) narrow_.test_face_pair(p.a, p.b, result.contacts, c, record);
  tm.narrow_ms = ms_since(t);

  t = Clock::now();
  const std::uint64_t vf_before = c.vf_pairs, ee_before = c.ee_pairs, tests_before = c.vf_tests + c.ee_tests;
  for (const VertexFacePair& p : orphans_.vf) narrow_.test_vf(p.v, p.f, result.contacts, c);
  for (const EdgeEdgePair& p : orphans_.ee) narrow_.test_ee(p.a, p.b, result.contacts, c);
  c.orphan_vf = c.vf_pairs - vf_before;
  c.orphan_ee = c.ee_pairs - ee_before;
  c.orphan_tests = c.vf_tests + c.ee_tests - tests_before;
  if (record) {
    record->tested_vf.insert(record->tested_vf.end(), orphans_.vf.begin(), orphans_.vf.end());
    record->tested_ee.insert(record->tested_ee.end(), orphans_.ee.begin(), orphans_.ee.end());
  }
  tm.orphan_ms = ms_since(t);

  sort_contacts(result.contacts);
  tm.total_ms = ms_since(t_start);
  return result;
}

std::size_t CcdPipeline::memory_bytes() const {
  std::size_t bytes = mesh_.memory_bytes() + owners_.vertex_owner.size() * sizeof(Index) +
                      owners_.edge_owner.size() * sizeof(Index) + owners_.owned_mask.size() +
                      orphans_.vf.size() * sizeof(VertexFacePair) + orphans_.ee.size() * sizeof(EdgeEdgePair);
  for (const BodyState& b : bodies_)
    bytes += b.bvh.memory_bytes() + std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, b.node_bvs);
  return bytes;
}

}  // namespace ccdlab

#include "experiments/cli/export/teaching_data.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "ccdlab/build_info.hpp"
#include "experiments/cli/export/pass_fronts.hpp"
#include "framework/export/bvtt_walk.hpp"
#include "framework/export/ccd_pictures.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"

namespace ccdlab::cli {
namespace {

using json = nlohmann::json;

/// Coordinates as integers: x = origin + i · quantum (per axis the same quantum).
struct Grid {
  Vec3 origin = Vec3::Zero();
  double quantum = 1;
  [[nodiscard]] long at(double v, int axis) const { return std::lround((v - origin[axis]) / quantum); }
  /// A slab value along the integer direction d: d·x = d·origin + i · quantum.
  [[nodiscard]] long slab(double v, const std::array<int, 3>& d) const {
    return std::lround((v - (d[0] * origin.x() + d[1] * origin.y() + d[2] * origin.z())) / quantum);
  }
};

Grid grid_of(const MeshSequence& scene) {
  Box3 box;
  for (int f = 0; f < scene.num_frames(); ++f)
    for (const Vec3& p : scene.frame(f)) box.grow(p);
  Grid g;
  g.origin = box.lo;
  const double extent = box.extent().maxCoeff();
  g.quantum = extent > 0 ? extent / 65536 : 1;
  return g;
}

json positions(const Positions& x, const Grid& g) {
  std::vector<long> out;
  out.reserve(3 * x.size());
  for (const Vec3& p : x)
    for (int a = 0; a < 3; ++a) out.push_back(g.at(p[a], a));
  return out;
}

/// Which body's hierarchy a pass side is (by address).
int body_of(const CcdPipeline& p, const BvhTopology* bvh, std::size_t bodies) {
  for (std::size_t b = 0; b < bodies; ++b)
    if (&p.bvh(int(b)) == bvh) return int(b);
  return -1;
}

/// The centre of every node's box part (its first three axes are x, y, z): where the front's lines end.
json centres(const BvhTopology& bvh, const AnyBvs& bvs, const Grid& g) {
  std::vector<long> out;
  out.reserve(3 * std::size_t(bvh.size()));
  std::visit(
      [&](const auto& array) {
        for (Index n = 0; n < bvh.size(); ++n)
          for (int a = 0; a < 3; ++a) out.push_back(g.at(0.5 * (double(array[n].min(a)) + double(array[n].max(a))), a));
      },
      bvs);
  return out;
}

json topology(const BvhTopology& bvh) {
  const std::vector<int> depth = node_depths(bvh);
  json left = json::array(), right = json::array(), face = json::array();
  for (const BvhNode& n : bvh.nodes) left.push_back(n.left), right.push_back(n.right), face.push_back(n.face);
  return {{"left", left}, {"right", right}, {"face", face}, {"depth", depth}};
}

/// The slabs of every node above depth `levels`: per node K values (the K/2 minima, then the maxima), or null.
json slabs(const BvhTopology& bvh, const AnyBvs& bvs, int levels, const Grid& g) {
  const std::vector<int> depth = node_depths(bvh);
  json out = json::array();
  std::visit(
      [&](const auto& array) {
        using BV = typename std::decay_t<decltype(array)>::value_type;
        for (Index n = 0; n < bvh.size(); ++n) {
          if (depth[std::size_t(n)] >= levels) {
            out.push_back(nullptr);
            continue;
          }
          std::vector<long> v;
          for (int i = 0; i < BV::num_axes; ++i) v.push_back(g.slab(array[n].min(i), BV::axes[std::size_t(i)]));
          for (int i = 0; i < BV::num_axes; ++i) v.push_back(g.slab(array[n].max(i), BV::axes[std::size_t(i)]));
          out.push_back(v);
        }
      },
      bvs);
  return out;
}

/// The slabs of the nodes of one sub-tree (null elsewhere): what the walk-through draws.
json subtree_slabs(const BvhTopology& bvh, const AnyBvs& bvs, Index root, const Grid& g) {
  json all = slabs(bvh, bvs, 1 << 20, g);
  for (Index n = 0; n < bvh.size(); ++n)
    if (n < root || n >= bvh.subtree_end(root)) all[std::size_t(n)] = nullptr;
  return all;
}

template <int K>
json axes_of() {
  json out = json::array();
  for (const auto& d : KDop<K>::axes) out.push_back({d[0], d[1], d[2]});
  return out;
}

template <std::size_t... I>
json axes_of_every_k(std::index_sequence<I...>) {
  json out = json::object();
  ((out[std::to_string(KdopKs::values[I])] = axes_of<KdopKs::values[I]>()), ...);
  return out;
}
json all_axes() { return axes_of_every_k(std::make_index_sequence<KdopKs::values.size()>{}); }

/// The leaf node of every face, per body hierarchy.
std::map<std::pair<int, Index>, Index> leaf_of_face(const CcdPipeline& p, std::size_t bodies) {
  std::map<std::pair<int, Index>, Index> out;
  for (std::size_t b = 0; b < bodies; ++b)
    for (Index n = 0; n < p.bvh(int(b)).size(); ++n)
      if (p.bvh(int(b)).nodes[n].is_leaf()) out[{int(b), p.bvh(int(b)).nodes[n].face}] = n;
  return out;
}

int body_of_face(const std::vector<Body>& bodies, Index f) {
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (f >= bodies[b].face_begin && f < bodies[b].face_end) return int(b);
  return -1;
}

/// Each contact: kind, features, vertices, time, coordinates, and how the traversal led to it — the face pair the
/// ownership rule tests it in, and that pair's BVH leaves (none: it is in the orphan set, adjacent faces).
json contacts_json(const CcdPipeline& p, const MeshSequence& scene, const Contacts& contacts) {
  const TriMesh& mesh = scene.topology();
  const Ownership& own = p.representatives().owners();
  const auto leaves = leaf_of_face(p, scene.bodies().size());
  json out = json::array();
  for (const Contact& c : contacts) {
    const Index fa = c.kind == ContactKind::vf ? own.vertex_owner[std::size_t(c.feature_a)] : own.edge_owner[std::size_t(c.feature_a)];
    const Index fb = c.kind == ContactKind::vf ? c.feature_b : own.edge_owner[std::size_t(c.feature_b)];
    const int ba = body_of_face(scene.bodies(), fa), bb = body_of_face(scene.bodies(), fb);
    const bool orphan = fa == fb || mesh.faces_adjacent(fa, fb);
    const auto la = leaves.find({ba, fa}), lb = leaves.find({bb, fb});
    json j = {{"kind", c.kind == ContactKind::vf ? "vf" : "ee"}, {"a", c.feature_a}, {"b", c.feature_b},
              {"v", {c.vertices[0], c.vertices[1], c.vertices[2], c.vertices[3]}}, {"toi", c.toi},
              {"coords", {c.coords[0], c.coords[1]}}, {"faces", {fa, fb}}, {"bodies", {ba, bb}}, {"orphan", orphan}};
    if (!orphan && la != leaves.end() && lb != leaves.end()) j["leaves"] = {la->second, lb->second};
    out.push_back(j);
  }
  return out;
}

/// The front of each pass after a step, each node [a, b, change (0 kept, 1 sprouted, 2 pruned), overlapped].
json fronts_json(const CcdPipeline& p, const Fronts& before, const Fronts& after, std::size_t bodies) {
  json out = json::array();
  for (std::size_t i = 0; i < p.passes().size(); ++i) {
    const TraversalPass& pass = p.passes()[i];
    const std::vector<FrontNode> none;
    const auto change = classify_front(*pass.side_a.bvh, *pass.side_b.bvh, before.empty() ? none : before[i], after[i]);
    json nodes = json::array();
    for (std::size_t n = 0; n < after[i].size(); ++n)
      nodes.push_back({after[i][n].a, after[i][n].b, int(change[n]), int(after[i][n].flags & FrontNode::kOverlapped)});
    out.push_back({{"bodies", {body_of(p, pass.side_a.bvh, bodies), body_of(p, pass.side_b.bvh, bodies)}},
                   {"self", pass.self}, {"nodes", nodes}});
  }
  return out;
}

json walk_json(const BvttWalk& w) {
  json visits = json::array();
  for (const WalkVisit& v : w.visits)
    visits.push_back({v.a, v.b, int(v.tested) | int(v.overlap) << 1 | int(v.candidate) << 2, v.task, v.thread, v.time});
  return {{"scheduler", w.scheduler}, {"threads", w.threads}, {"tasks", w.tasks}, {"visits", visits}};
}

/// The self node of the first self pass with at most `leaves` leaves whose faces hold the most contacts.
Index walk_root(const BvhTopology& bvh, const std::vector<int>& face_contacts, int leaves) {
  Index best = 0;
  long best_count = -1;
  for (Index n = 0; n < bvh.size(); ++n) {
    if (bvh.leaf_count[n] > leaves || bvh.leaf_count[n] < 2) continue;
    long count = 0;
    for (Index m = n; m < bvh.subtree_end(n); ++m)
      if (bvh.nodes[m].is_leaf()) count += face_contacts[std::size_t(bvh.nodes[m].face)];
    if (count > best_count || (count == best_count && bvh.leaf_count[n] > bvh.leaf_count[best])) best = n, best_count = count;
  }
  return best;
}

}  // namespace

json teaching_data(const ExperimentConfig& config, const Registries& reg, const MeshSequence& scene,
                   const TeachingOptions& o, Progress& progress) {
  const TriMesh& mesh = scene.topology();
  const int steps = scene.num_steps();
  const std::size_t bodies = scene.bodies().size();
  const Grid g = grid_of(scene);
  std::vector<int> ks{config.k};
  for (int k : KdopKs::values)
    if (k != config.k) ks.push_back(k);

  json faces = json::array(), face_body = json::array(), frames = json::array(), body_names = json::array();
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (Index v : mesh.face(f)) faces.push_back(v);
    face_body.push_back(body_of_face(scene.bodies(), f));
  }
  for (int f = 0; f <= steps; ++f) frames.push_back(positions(scene.frame(f), g));
  for (const Body& b : scene.bodies()) body_names.push_back(b.name);

  json per_k = json::object(), steps_json = json::array(), topologies = json::array();
  std::vector<int> contacts_per_step(std::size_t(steps), 0);
  std::vector<std::vector<int>> face_contacts(static_cast<std::size_t>(steps));
  long done = 0;
  for (std::size_t ki = 0; ki < ks.size(); ++ki) {
    ExperimentConfig c = config;
    c.k = ks[ki];
    const bool main_k = ki == 0;
    CcdPipeline pipeline(mesh, scene.bodies(), make_strategies(c, reg));
    pipeline.keep_candidates(main_k);
    json k_steps = json::array();
    for (int s = 0; s < steps; ++s) {
      const Fronts before = main_k && s > 0 ? fronts_of(pipeline) : Fronts{};
      const StepResult r = pipeline.step(scene.frame(s), scene.frame(s + 1));
      json st = {{"bv_tests", r.counters.bv_tests}, {"candidates", r.counters.candidate_pairs},
                 {"contacts", r.contacts.size()}, {"ms", r.timings.total_ms}};
      json bvs = json::array();
      for (std::size_t b = 0; b < bodies; ++b) bvs.push_back(slabs(pipeline.bvh(int(b)), pipeline.node_bvs(int(b)), o.levels, g));
      st["slabs"] = bvs;
      if (main_k) {
        if (s == 0)
          for (std::size_t b = 0; b < bodies; ++b) topologies.push_back(topology(pipeline.bvh(int(b))));
        st["fronts"] = fronts_json(pipeline, before, fronts_of(pipeline), bodies);
        json c = json::array();
        for (std::size_t b = 0; b < bodies; ++b) c.push_back(centres(pipeline.bvh(int(b)), pipeline.node_bvs(int(b)), g));
        st["centres"] = c;
        json cand = json::array();
        for (const FacePair& fp : pipeline.last_candidates().pairs.flatten()) cand.push_back({fp.a, fp.b});
        st["candidate_pairs"] = cand;
        face_contacts[std::size_t(s)] = contacts_per_face(mesh, r.contacts);
        contacts_per_step[std::size_t(s)] = int(r.contacts.size());
        steps_json.push_back({{"contacts", contacts_json(pipeline, scene, r.contacts)},
                              {"face_contacts", face_contacts[std::size_t(s)]}});
      }
      k_steps.push_back(st);
      progress.update(++done);
    }
    per_k[std::to_string(ks[ki])] = k_steps;
  }

  // The walk-through: one small self sub-tree of the detailed step, with the BVs of that step.
  int detail = o.detail_step;
  if (detail < 0 && steps > 0)
    detail = int(std::max_element(contacts_per_step.begin(), contacts_per_step.end()) - contacts_per_step.begin());
  json walks = json::object();
  if (detail >= 0) {
    CcdPipeline pipeline(mesh, scene.bodies(), make_strategies(config, reg));
    Fronts before;
    for (int s = 0; s <= detail; ++s) {
      if (s == detail) before = fronts_of(pipeline);
      (void)pipeline.step(scene.frame(s), scene.frame(s + 1));
    }
    const auto& passes = pipeline.passes();
    const auto self = std::find_if(passes.begin(), passes.end(), [](const TraversalPass& p) { return p.self; });
    if (self != passes.end()) {
      const std::size_t pass = std::size_t(self - passes.begin());
      const Index root = walk_root(*self->side_a.bvh, face_contacts[std::size_t(detail)], o.walk_leaves);
      const BvttNode start{root, root};
      const int threads = 2;
      walks = {{"step", detail}, {"body", body_of(pipeline, self->side_a.bvh, bodies)}, {"root", root},
               {"threads", threads}, {"phc_c", 1}, {"front_chunk", 4},
               {"orders", {walk_json(walk_sequential(*self, start)), walk_json(walk_phc(*self, start, threads, 1)),
                           walk_json(walk_front(*self, start, before.empty() ? std::vector<FrontNode>{} : before[pass], threads, 4))}},
               {"slabs", subtree_slabs(*self->side_a.bvh, *self->side_a.bvs, root, g)}};
    }
  }

  return {{"meta", {{"name", config.name}, {"scene", scene.description()}, {"revision", build_info::git_revision},
                    {"triangles", mesh.num_faces()}, {"frames", steps + 1}, {"k", config.k}, {"ks", ks},
                    {"levels", o.levels}, {"scheduler", "front"}, {"tester", config.tester.name}}},
          {"config", to_json(config)},
          {"grid", {{"origin", {g.origin.x(), g.origin.y(), g.origin.z()}}, {"quantum", g.quantum}}},
          {"axes", all_axes()},
          {"mesh", {{"faces", faces}, {"face_body", face_body}, {"frames", frames}, {"bodies", body_names}}},
          {"bodies", topologies},
          {"steps", steps_json},
          {"ks_data", per_k},
          {"walk", walks}};
}

}  // namespace ccdlab::cli

#include "framework/pipeline/proximity/sweep_proximity.hpp"

#include <algorithm>

#include "framework/primitive/feature_pairs.hpp"
#include "framework/primitive/static_distance.hpp"

namespace ccdlab {

namespace {

struct SweepBox {
  Vec3 lo, hi;
  Index id;
};

/// The boxes of `features` (faces or edges) at x, grown by r, sorted by lo.x.
template <class Feature>
std::vector<SweepBox> sweep_boxes(std::span<const Feature> features, const Positions& x, double r) {
  std::vector<SweepBox> out;
  out.reserve(features.size());
  for (std::size_t i = 0; i < features.size(); ++i) {
    Vec3 lo = x[features[i][0]], hi = lo;
    for (const Index v : features[i]) lo = lo.cwiseMin(x[v]), hi = hi.cwiseMax(x[v]);
    out.push_back({lo.array() - r, hi.array() + r, Index(i)});
  }
  std::sort(out.begin(), out.end(), [](const SweepBox& a, const SweepBox& b) { return a.lo.x() < b.lo.x(); });
  return out;
}

bool overlap_yz(const Vec3& lo, const Vec3& hi, const SweepBox& b) {
  return lo.y() <= b.hi.y() && b.lo.y() <= hi.y() && lo.z() <= b.hi.z() && b.lo.z() <= hi.z();
}

}  // namespace

Contacts sweep_proximity(const TriMesh& mesh, const CollisionRules& rules, const Positions& x, double dhat) {
  // Boxes grown a little beyond d̂ (and half of it for each of two edges): rounding never drops a pair at d̂.
  const double r = dhat * (1 + 1e-6);
  Contacts out;
  const auto add = [&](ContactKind kind, Index a, Index b, const std::array<Index, 4>& v) {
    out.push_back({kind, a, b, v, 0.0, {0, 0}});
  };
  std::vector<Index> by_x(std::size_t(mesh.num_vertices()));
  for (Index v = 0; v < mesh.num_vertices(); ++v) by_x[std::size_t(v)] = v;
  std::sort(by_x.begin(), by_x.end(), [&](Index a, Index b) { return x[a].x() < x[b].x(); });
  for (const SweepBox& box : sweep_boxes(std::span(mesh.faces()), x, r)) {
    const Face& f = mesh.face(box.id);
    const int body = rules.body_of_face(box.id);
    auto it = std::lower_bound(by_x.begin(), by_x.end(), box.lo.x(), [&](Index v, double lo) { return x[v].x() < lo; });
    for (; it != by_x.end() && x[*it].x() <= box.hi.x(); ++it) {
      const Index v = *it;
      if (contains_vertex(f, v) || !overlap_yz(x[v], x[v], box) || !rules.bodies_interact(rules.body_of_vertex(v), body)) continue;
      if (vertex_face_closer(x[v], x[f[0]], x[f[1]], x[f[2]], dhat).closer) add(ContactKind::vf, v, box.id, {v, f[0], f[1], f[2]});
    }
  }
  const std::vector<SweepBox> edges = sweep_boxes(std::span(mesh.edges()), x, r / 2);
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size() && edges[j].lo.x() <= edges[i].hi.x(); ++j) {
      if (!overlap_yz(edges[i].lo, edges[i].hi, edges[j])) continue;
      const Index a = std::min(edges[i].id, edges[j].id), b = std::max(edges[i].id, edges[j].id);
      const Edge &ea = mesh.edge(a), &eb = mesh.edge(b);
      if (shares_vertex(ea, eb) || !rules.bodies_interact(rules.body_of_vertex(ea[0]), rules.body_of_vertex(eb[0]))) continue;
      if (edge_edge_closer(x[ea[0]], x[ea[1]], x[eb[0]], x[eb[1]], dhat).closer) add(ContactKind::ee, a, b, {ea[0], ea[1], eb[0], eb[1]});
    }
  sort_contacts(out);
  return out;
}

}  // namespace ccdlab

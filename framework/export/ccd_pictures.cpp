#include "framework/export/ccd_pictures.hpp"

#include <unordered_set>

#include "framework/geometry/kdop_polyhedron.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {

std::vector<int> contacts_per_face(const TriMesh& mesh, const Contacts& contacts) {
  std::vector<int> count(std::size_t(mesh.num_faces()), 0);
  std::vector<Index> touched;
  for (const Contact& c : contacts) {
    touched.clear();
    if (c.kind == ContactKind::vf) {
      touched.push_back(c.feature_b);
      for (Index f : mesh.vertex_faces(c.feature_a)) touched.push_back(f);
    } else {
      for (Index e : {c.feature_a, c.feature_b})
        for (Index f : mesh.edge_faces(e)) touched.push_back(f);
    }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (Index f : touched) ++count[std::size_t(f)];
  }
  return count;
}

VtkGrid mesh_grid(const TriMesh& mesh, const std::vector<Body>& bodies, const Positions& x, const Positions& x_next,
                  const std::vector<int>& face_contacts) {
  VtkGrid g;
  std::vector<double> displacement;
  for (std::size_t v = 0; v < x.size(); ++v) {
    g.add_point(x[v]);
    displacement.push_back((x_next[v] - x[v]).norm());
  }
  g.set_point_array("displacement", std::move(displacement));
  for (std::size_t b = 0; b < bodies.size(); ++b)
    for (Index f = bodies[b].face_begin; f < bodies[b].face_end; ++f) {
      const auto& face = mesh.face(f);
      g.add_cell(VtkCell::triangle, {int(face[0]), int(face[1]), int(face[2])});
      g.set_cell_value("body", double(b));
      g.set_cell_value("contacts", face_contacts.empty() ? 0.0 : double(face_contacts[std::size_t(f)]));
    }
  return g;
}

std::vector<int> node_depths(const BvhTopology& bvh) {
  std::vector<int> depth(bvh.nodes.size(), 0);
  for (std::size_t i = 1; i < bvh.nodes.size(); ++i) depth[i] = depth[std::size_t(bvh.nodes[i].parent)] + 1;  // pre-order
  return depth;
}

namespace {

/// Centre of a k-DOP: the middle of its first three (coordinate) slabs.
template <int K>
Vec3 centre(const KDop<K>& bv) {
  return Vec3(double(bv.min(0)) + bv.max(0), double(bv.min(1)) + bv.max(1), double(bv.min(2)) + bv.max(2)) / 2;
}

}  // namespace

VtkGrid bvh_level_grid(const BvhTopology& bvh, const AnyBvs& bvs, int depth, int body) {
  const std::vector<int> depths = node_depths(bvh);
  VtkGrid out;
  std::visit(
      [&](const auto& v) {
        if (v.size() != bvh.nodes.size()) fail("bvh_level_grid: {} volumes for {} nodes", v.size(), bvh.nodes.size());
        for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
          if (depths[i] != depth) continue;
          const Polyhedron p = kdop_polyhedron(v[i]);
          const int first = int(out.num_points());
          for (const Vec3& q : p.vertices) out.add_point(q);
          for (auto face : p.faces) {
            for (int& q : face) q += first;
            out.add_cell(face.size() == 3 ? VtkCell::triangle : VtkCell::polygon, face);
            out.set_cell_value("node", double(i));
            out.set_cell_value("depth", double(depth));
            out.set_cell_value("leaf", bvh.nodes[i].is_leaf() ? 1.0 : 0.0);
            out.set_cell_value("body", double(body));
          }
        }
      },
      bvs);
  return out;
}

std::vector<FrontChange> classify_front(const BvhTopology& bvh_a, const BvhTopology& bvh_b,
                                        const std::vector<FrontNode>& previous, const std::vector<FrontNode>& current) {
  auto key = [](Index a, Index b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); };
  std::unordered_set<std::uint64_t> before;
  for (const FrontNode& n : previous) before.insert(key(n.a, n.b));
  std::vector<FrontChange> out;
  out.reserve(current.size());
  for (const FrontNode& n : current) {
    if (previous.empty()) {
      out.push_back(FrontChange::sprouted);
      continue;
    }
    if (before.count(key(n.a, n.b))) {
      out.push_back(FrontChange::kept);
      continue;
    }
    // An ancestor pair in the last front: this node is below it. The front covers every leaf pair once, so a
    // node neither kept nor below the last front is above it (pruned back).
    bool below = false;
    for (Index a = n.a; a >= 0 && !below; a = bvh_a.nodes[std::size_t(a)].parent)
      for (Index b = n.b; b >= 0 && !below; b = bvh_b.nodes[std::size_t(b)].parent)
        below = (a != n.a || b != n.b) && before.count(key(a, b));
    out.push_back(below ? FrontChange::sprouted : FrontChange::pruned);
  }
  return out;
}

VtkGrid front_grid(const BvhTopology& bvh_a, const AnyBvs& bvs_a, const BvhTopology& bvh_b, const AnyBvs& bvs_b,
                   const std::vector<FrontNode>& nodes, const std::vector<FrontChange>& change) {
  VtkGrid g;
  const std::vector<int> depth_a = node_depths(bvh_a), depth_b = node_depths(bvh_b);
  std::visit(
      [&](const auto& va) {
        using Vector = std::decay_t<decltype(va)>;
        const Vector& vb = std::get<Vector>(bvs_b);
        for (std::size_t i = 0; i < nodes.size(); ++i) {
          const FrontNode& n = nodes[i];
          const int pa = g.add_point(centre(va[std::size_t(n.a)]));
          if (&bvh_a == &bvh_b && n.a == n.b) {
            g.add_cell(VtkCell::vertex, {pa});
          } else {
            g.add_cell(VtkCell::line, {pa, g.add_point(centre(vb[std::size_t(n.b)]))});
          }
          g.set_cell_value("change", double(change[i]));
          g.set_cell_value("overlapping", (n.flags & FrontNode::kOverlapped) ? 1.0 : 0.0);
          g.set_cell_value("depth_a", depth_a[std::size_t(n.a)]);
          g.set_cell_value("depth_b", depth_b[std::size_t(n.b)]);
          g.set_cell_value("self", &bvh_a == &bvh_b ? 1.0 : 0.0);
        }
      },
      bvs_a);
  return g;
}

VtkGrid contacts_grid(const Contacts& contacts, const Positions& x_t0, const Positions& x_t1) {
  VtkGrid g;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    auto at = [&](Index v) { return Vec3((1 - c.toi) * x_t0[std::size_t(v)] + c.toi * x_t1[std::size_t(v)]); };
    std::array<Vec3, 4> p{at(c.vertices[0]), at(c.vertices[1]), at(c.vertices[2]), at(c.vertices[3])};
    const auto [s, t] = c.coords;
    const Vec3 point = c.kind == ContactKind::vf
                           ? p[0]
                           : Vec3(((1 - s) * p[0] + s * p[1] + (1 - t) * p[2] + t * p[3]) / 2);
    auto label = [&](double role) {
      g.set_cell_value("contact", double(i));
      g.set_cell_value("kind", double(c.kind));
      g.set_cell_value("toi", c.toi);
      g.set_cell_value("role", role);
    };
    g.add_cell(VtkCell::vertex, {g.add_point(point)});
    label(0);
    std::array<int, 4> id{};
    for (int k = 0; k < 4; ++k) id[k] = g.add_point(p[k]);
    if (c.kind == ContactKind::vf) {
      g.add_cell(VtkCell::triangle, {id[1], id[2], id[3]});
      label(1);
    } else {
      g.add_cell(VtkCell::line, {id[0], id[1]});
      label(1);
      g.add_cell(VtkCell::line, {id[2], id[3]});
      label(1);
    }
  }
  return g;
}

}  // namespace ccdlab

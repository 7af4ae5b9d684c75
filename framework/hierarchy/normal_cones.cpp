#include "framework/hierarchy/normal_cones.hpp"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <numeric>


namespace ccdlab {
namespace {

constexpr double kHalfPi = 1.5707963267948966;
constexpr double kConeMargin = 1e-6;  // radians kept away from π/2
constexpr double kRelMargin = 1e-9;   // relative margin of the contour signs

struct Cone {
  Vec3 axis;
  double half_angle;
};

double angle_between(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

/// Smallest cone (approximately; always enclosing) containing two cones.
Cone merge(const Cone& a, const Cone& b) {
  if (a.half_angle >= kHalfPi || b.half_angle >= kHalfPi) return {Vec3::UnitZ(), 10};
  const double phi = angle_between(a.axis, b.axis);
  if (phi + b.half_angle <= a.half_angle) return a;
  if (phi + a.half_angle <= b.half_angle) return b;
  const double half = 0.5 * (phi + a.half_angle + b.half_angle);
  if (half >= kHalfPi) return {a.axis, 10};
  // Rotate a's axis towards b's by (half − a.half_angle) in their common plane.
  Vec3 u = b.axis - a.axis.dot(b.axis) * a.axis;
  const double un = u.norm();
  if (!(un > 1e-12)) return {a.axis, std::max(a.half_angle, b.half_angle) + 1e-9};
  u /= un;
  const double rot = half - a.half_angle;
  return {(std::cos(rot) * a.axis + std::sin(rot) * u).normalized(), half + 1e-9};
}

}  // namespace

namespace {

/// What the disk analysis keeps per node while merging bottom-up.
struct PatchInfo {
  std::vector<std::array<Index, 4>> boundary;  ///< half-edges (edge id, from, to, component), sorted by edge id
  Index vertices = 0, edges = 0, faces = 0;
  Index components = 0;  ///< connected components with boundary (labels 0 … components − 1)
  Index closed = 0;      ///< components without boundary
  bool ok = true;        ///< consistently oriented and manifold (monotone: inherited by every ancestor)
};

/// Faces touching a non-manifold edge (> 2 faces) or a non-manifold vertex (faces around it not one fan):
/// patches containing them are never treated as disks.
std::vector<char> non_manifold_faces(const TriMesh& mesh) {
  std::vector<char> bad(mesh.num_faces(), 0);
  for (Index e = 0; e < mesh.num_edges(); ++e)
    if (mesh.edge_faces(e).size() > 2)
      for (Index f : mesh.edge_faces(e)) bad[f] = 1;
  std::vector<Index> fan, stack;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    auto faces = mesh.vertex_faces(v);
    if (faces.size() <= 1) continue;
    // Walk the fan from the first face through edges containing v.
    fan.assign(1, faces[0]);
    stack.assign(1, faces[0]);
    while (!stack.empty()) {
      const Index f = stack.back();
      stack.pop_back();
      for (Index e : mesh.face_edges(f)) {
        const Edge& ed = mesh.edge(e);
        if (ed[0] != v && ed[1] != v) continue;
        for (Index g : mesh.edge_faces(e))
          if (std::find(fan.begin(), fan.end(), g) == fan.end()) fan.push_back(g), stack.push_back(g);
      }
    }
    if (fan.size() != faces.size())
      for (Index f : faces) bad[f] = 1;
  }
  return bad;
}

void merge_patches(const PatchInfo& a, const PatchInfo& b, PatchInfo& out) {
  out.faces = a.faces + b.faces;
  out.ok = a.ok && b.ok;
  // Component labels: a's as they are, b's shifted; shared edges unite them.
  std::vector<Index> parent(std::size_t(a.components + b.components));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<std::array<Index, 4>> merged;
  merged.reserve(a.boundary.size() + b.boundary.size());
  Index shared_edges = 0;
  std::size_t i = 0, j = 0;
  while (i < a.boundary.size() || j < b.boundary.size()) {
    if (j == b.boundary.size() || (i < a.boundary.size() && a.boundary[i][0] < b.boundary[j][0])) {
      merged.push_back(a.boundary[i++]);
    } else if (i == a.boundary.size() || b.boundary[j][0] < a.boundary[i][0]) {
      auto h = b.boundary[j++];
      h[3] += a.components;
      merged.push_back(h);
    } else {  // an edge on both boundaries: interior now; consistent orientation runs it both ways
      if (a.boundary[i][1] != b.boundary[j][2]) out.ok = false;
      parent[find(a.boundary[i][3])] = find(b.boundary[j][3] + a.components);
      ++shared_edges, ++i, ++j;
    }
  }
  // Shared vertices of two manifold patches lie on both boundaries.
  std::vector<Index> va, vb;
  for (const auto& h : a.boundary) va.push_back(h[1]), va.push_back(h[2]);
  for (const auto& h : b.boundary) vb.push_back(h[1]), vb.push_back(h[2]);
  std::sort(va.begin(), va.end());
  va.erase(std::unique(va.begin(), va.end()), va.end());
  std::sort(vb.begin(), vb.end());
  vb.erase(std::unique(vb.begin(), vb.end()), vb.end());
  Index shared_vertices = 0;
  for (std::size_t p = 0, q = 0; p < va.size() && q < vb.size();) {
    if (va[p] < vb[q]) ++p;
    else if (vb[q] < va[p]) ++q;
    else ++shared_vertices, ++p, ++q;
  }
  out.vertices = a.vertices + b.vertices - shared_vertices;
  out.edges = a.edges + b.edges - shared_edges;
  // Relabel components compactly; roots left without boundary edges became closed components.
  std::vector<Index> compact(parent.size(), -1);
  Index next = 0;
  for (auto& h : merged) {
    Index& c = compact[find(h[3])];
    if (c < 0) c = next++;
    h[3] = c;
  }
  Index roots = 0;
  for (Index x = 0; x < Index(parent.size()); ++x) roots += find(x) == x;
  out.components = next;
  out.closed = a.closed + b.closed + (roots - next);
  out.boundary = std::move(merged);
}

/// One boundary loop through distinct vertices (each boundary vertex starts exactly one boundary edge).
bool single_loop(const std::vector<std::array<Index, 4>>& boundary) {
  if (boundary.size() < 3) return false;
  std::vector<std::array<Index, 2>> by_start;
  for (const auto& h : boundary) by_start.push_back({h[1], h[2]});
  std::sort(by_start.begin(), by_start.end());
  for (std::size_t k = 1; k < by_start.size(); ++k)
    if (by_start[k][0] == by_start[k - 1][0]) return false;
  std::size_t steps = 0;
  Index at = by_start[0][1];
  while (steps < by_start.size()) {
    auto it = std::lower_bound(by_start.begin(), by_start.end(), std::array<Index, 2>{at, -1});
    if (it == by_start.end() || (*it)[0] != at) return false;
    at = (*it)[1];
    ++steps;
    if (at == by_start[0][1]) break;
  }
  return steps == by_start.size();
}

}  // namespace

NormalConeCuller::NormalConeCuller(const TriMesh& mesh, const BvhTopology& bvh, int threads) : mesh_(mesh), bvh_(bvh) {
  const Index n = bvh.size();
  is_disk_.assign(n, 0);
  cone_.resize(n);
  skip_root_.assign(n, -1);
  // Disk analysis, bottom-up: a node's patch from its children's (O(boundary) per node).
  const std::vector<char> bad = non_manifold_faces(mesh);
  std::vector<PatchInfo> info(n);
  auto analyse = [&](Index i) {
    const BvhNode& node = bvh.nodes[i];
    PatchInfo& p = info[i];
    if (node.is_leaf()) {
      const Face& t = mesh.face(node.face);
      for (int j = 0; j < 3; ++j) p.boundary.push_back({mesh.face_edges(node.face)[j], t[j], t[(j + 1) % 3], 0});
      std::sort(p.boundary.begin(), p.boundary.end());
      p.vertices = 3, p.edges = 3, p.faces = 1, p.components = 1, p.closed = 0, p.ok = !bad[node.face];
    } else {
      merge_patches(info[node.left], info[node.right], p);
      // Children's boundaries are no longer needed unless they are big enough to be culled themselves.
      if (bvh.leaf_count[node.left] < kMinLeaves) std::vector<std::array<Index, 4>>().swap(info[node.left].boundary);
      if (bvh.leaf_count[node.right] < kMinLeaves) std::vector<std::array<Index, 4>>().swap(info[node.right].boundary);
    }
    // A disk: one connected, consistently oriented manifold patch, Euler characteristic 1, one boundary loop.
    is_disk_[i] = bvh.leaf_count[i] >= kMinLeaves && p.ok && p.components == 1 && p.closed == 0 &&
                  p.vertices - p.edges + p.faces == 1 && single_loop(p.boundary);
  };
  // Bottom-up along the tree's refit plan: its sub-trees in parallel, then the nodes above them.
  const RefitPlan& plan = bvh.refit_plan();
  PhaseTrace unused;
  parallel_chunks(plan.subtrees.size(), 1, threads, unused, [&](std::size_t k, std::size_t, int) {
    const Index r = plan.subtrees[k];
    for (Index i = bvh.subtree_end(r) - 1; i >= r; --i) analyse(i);
  });
  for (Index i : plan.top) analyse(i);

  boundary_.offsets.assign(n + 1, 0);
  for (Index i = 0; i < n; ++i) boundary_.offsets[i + 1] = boundary_.offsets[i] + (is_disk_[i] ? 2 * Index(info[i].boundary.size()) : 0);
  boundary_.items.resize(boundary_.offsets[n]);
  for (Index i = 0; i < n; ++i) {
    if (!is_disk_[i]) continue;
    Index at = boundary_.offsets[i];
    for (const auto& h : info[i].boundary) boundary_.items[at++] = h[1], boundary_.items[at++] = h[2];
  }
}

void NormalConeCuller::merge_children(Index i) {
  const BvhNode& node = bvh_.nodes[i];
  const auto m = merge({cone_[node.left].axis, cone_[node.left].half_angle}, {cone_[node.right].axis, cone_[node.right].half_angle});
  cone_[i] = {m.axis, m.half_angle};
}

bool NormalConeCuller::passes(Index i, const Positions& x0, const Positions& x1, std::uint64_t& edges) const {
  if (!is_disk_[i] || !(cone_[i].half_angle < kHalfPi - kConeMargin)) return false;
  edges += boundary_.of(i).size() / 2;
  return contour_is_star(i, cone_[i].axis, x0, x1);
}

bool NormalConeCuller::contour_is_star(Index node, const Vec3& V, const Positions& x0, const Positions& x1) const {
  auto items = boundary_.of(node);
  const std::size_t m = items.size() / 2;
  Vec3 p0 = Vec3::Zero(), p1 = Vec3::Zero();
  for (std::size_t k = 0; k < m; ++k) p0 += x0[items[2 * k]], p1 += x1[items[2 * k]];
  p0 /= double(m);
  p1 /= double(m);
  for (std::size_t k = 0; k < m; ++k) {
    const Vec3 a0 = x0[items[2 * k]] - p0, b0 = x0[items[2 * k + 1]] - p0;
    const Vec3 a1 = x1[items[2 * k]] - p1, b1 = x1[items[2 * k + 1]] - p1;
    const double scale = std::max({a0.norm() * b0.norm(), a1.norm() * b1.norm(), a0.norm() * b1.norm(), a1.norm() * b0.norm()});
    const double margin = kRelMargin * scale;
    const double c0 = V.dot(a0.cross(b0)), c2 = V.dot(a1.cross(b1)), c1 = 0.5 * V.dot(a0.cross(b1) + a1.cross(b0));
    if (!(c0 > margin && c1 > margin && c2 > margin)) return false;
  }
  return true;
}

std::uint64_t NormalConeCuller::update(const Positions& x0, const Positions& x1, int threads, PhaseTrace& trace) {
  using Clock = std::chrono::steady_clock;
  auto face_cone = [&](Index i) {
    const Face& t = mesh_.face(bvh_.nodes[i].face);
    const Vec3 B0 = x0[t[1]] - x0[t[0]], C0 = x0[t[2]] - x0[t[0]], B1 = x1[t[1]] - x1[t[0]], C1 = x1[t[2]] - x1[t[0]];
    // The Bernstein coefficients of the quadratic n(t).
    const Vec3 beta[3] = {B0.cross(C0), 0.5 * (B0.cross(C1) + B1.cross(C0)), B1.cross(C1)};
    Vec3 sum = Vec3::Zero();
    for (const Vec3& b : beta) {
      const double len = b.norm();
      if (!(len > 0)) return Cone{Vec3::UnitZ(), 10};
      sum += b / len;
    }
    if (!(sum.norm() > 0)) return Cone{Vec3::UnitZ(), 10};
    const Vec3 axis = sum.normalized();
    double half = 0;
    for (const Vec3& b : beta) half = std::max(half, angle_between(axis, b));
    return Cone{axis, half + 1e-9};
  };
  // 1. Cones bottom-up inside each sub-tree of the cut (parallel), then above it (serial).
  const RefitPlan& plan = bvh_.refit_plan();
  parallel_chunks(plan.subtrees.size(), 1, threads, trace, [&](std::size_t k, std::size_t, int) {
    const Index r = plan.subtrees[k];
    for (Index i = bvh_.subtree_end(r) - 1; i >= r; --i) {
      if (bvh_.nodes[i].is_leaf()) cone_[i] = face_cone(i);
      else merge_children(i);
    }
  });
  auto t0 = Clock::now();
  for (Index i : plan.top) merge_children(i);
  // 2. Skips top-down: above the cut (serial), then inside each sub-tree (parallel).
  std::uint64_t edges = 0, skipped = 0;
  auto decide = [&](Index i, std::uint64_t& e, std::uint64_t& s) {
    const Index p = bvh_.nodes[i].parent;
    if (p >= 0 && skip_root_[p] >= 0) skip_root_[i] = skip_root_[p];
    else if (bvh_.leaf_count[i] >= kMinLeaves && passes(i, x0, x1, e)) skip_root_[i] = i, ++s;
    else skip_root_[i] = -1;
  };
  for (auto it = plan.top.rbegin(); it != plan.top.rend(); ++it) decide(*it, edges, skipped);
  trace.serial_ms += ms_between(t0, Clock::now());
  std::vector<PerThread<std::array<std::uint64_t, 2>>> counts(threads);
  parallel_chunks(plan.subtrees.size(), 1, threads, trace, [&](std::size_t k, std::size_t, int tid) {
    const Index r = plan.subtrees[k];
    auto& c = counts[tid].value;
    for (Index i = r; i < bvh_.subtree_end(r); ++i) decide(i, c[0], c[1]);
  });
  for (const auto& c : counts) edges += c.value[0], skipped += c.value[1];
  contour_edge_tests_ = edges;
  return skipped;
}

}  // namespace ccdlab

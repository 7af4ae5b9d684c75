#include "framework/traversal/normal_cones.hpp"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <numeric>

#include <omp.h>

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

NormalConeCuller::NormalConeCuller(const TriMesh& mesh, const BvhTopology& bvh) : mesh_(mesh), bvh_(bvh) {
  const Index n = bvh.size();
  is_disk_.assign(n, 0);
  std::vector<std::vector<std::array<Index, 2>>> boundary(n);
#pragma omp parallel for schedule(dynamic, 16)
  for (Index node = 0; node < n; ++node) {
    if (bvh.leaf_count[node] < kMinLeaves) continue;
    std::vector<Index> faces = subtree_faces(bvh, node);
    // Directed half-edges (edge id, from, to), sorted by edge id.
    std::vector<std::array<Index, 3>> half;
    for (Index f : faces)
      for (int j = 0; j < 3; ++j) half.push_back({mesh.face_edges(f)[j], mesh.face(f)[j], mesh.face(f)[(j + 1) % 3]});
    std::sort(half.begin(), half.end());
    std::vector<std::array<Index, 2>> loop;
    std::vector<Index> verts;
    Index edges = 0;
    bool ok = true;
    // Union-find over local face order for connectivity through interior edges.
    std::vector<Index> face_of_half(half.size());  // local face index of each sorted half-edge
    {
      std::vector<std::pair<std::array<Index, 3>, Index>> tagged;
      for (std::size_t k = 0; k < faces.size(); ++k)
        for (int j = 0; j < 3; ++j)
          tagged.push_back({{mesh.face_edges(faces[k])[j], mesh.face(faces[k])[j], mesh.face(faces[k])[(j + 1) % 3]}, Index(k)});
      std::sort(tagged.begin(), tagged.end());
      for (std::size_t i = 0; i < tagged.size(); ++i) face_of_half[i] = tagged[i].second;
    }
    std::vector<Index> parent(faces.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](Index x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (std::size_t i = 0; i < half.size() && ok;) {
      std::size_t j = i;
      while (j < half.size() && half[j][0] == half[i][0]) ++j;
      ++edges;
      if (j - i == 1) {
        loop.push_back({half[i][1], half[i][2]});
      } else if (j - i == 2) {
        // Interior edge: consistent orientation means opposite directions.
        if (half[i][1] != half[i + 1][2]) ok = false;
        parent[find(face_of_half[i])] = find(face_of_half[i + 1]);
      } else {
        ok = false;
      }
      verts.push_back(half[i][1]);
      verts.push_back(half[i][2]);
      i = j;
    }
    if (!ok || loop.size() < 3) continue;
    for (std::size_t k = 1; k < faces.size() && ok; ++k) ok = find(Index(k)) == find(0);
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    if (!ok || Index(verts.size()) - edges + Index(faces.size()) != 1) continue;  // Euler characteristic of a disk
    // One boundary loop through distinct vertices: each boundary vertex starts exactly one boundary edge, and
    // following successors from the first edge visits them all.
    std::vector<std::array<Index, 2>> by_start = loop;
    std::sort(by_start.begin(), by_start.end());
    bool simple = true;
    for (std::size_t k = 1; k < by_start.size(); ++k) simple &= by_start[k][0] != by_start[k - 1][0];
    if (!simple) continue;
    std::size_t steps = 0;
    Index at = by_start[0][1];
    while (steps < by_start.size()) {
      auto it = std::lower_bound(by_start.begin(), by_start.end(), std::array<Index, 2>{at, -1});
      if (it == by_start.end() || (*it)[0] != at) break;
      at = (*it)[1];
      ++steps;
      if (at == by_start[0][1]) break;
    }
    if (steps != by_start.size()) continue;
    is_disk_[node] = 1;
    boundary[node] = std::move(loop);
  }
  boundary_.offsets.assign(n + 1, 0);
  for (Index i = 0; i < n; ++i) boundary_.offsets[i + 1] = boundary_.offsets[i] + 2 * Index(boundary[i].size());
  boundary_.items.resize(boundary_.offsets[n]);
  for (Index i = 0; i < n; ++i)
    for (std::size_t k = 0; k < boundary[i].size(); ++k) {
      boundary_.items[boundary_.offsets[i] + 2 * Index(k)] = boundary[i][k][0];
      boundary_.items[boundary_.offsets[i] + 2 * Index(k) + 1] = boundary[i][k][1];
    }
  cone_.resize(n);
  skip_root_.assign(n, -1);
  // Fixed cut: open nodes level by level until 256 sub-trees (or leaves).
  std::vector<Index> level{0};
  while (level.size() < 256) {
    std::vector<Index> next;
    for (Index i : level) {
      if (bvh.nodes[i].is_leaf()) next.push_back(i);
      else top_.push_back(i), next.push_back(bvh.nodes[i].left), next.push_back(bvh.nodes[i].right);
    }
    if (next.size() == level.size()) break;
    level = std::move(next);
  }
  subtrees_ = std::move(level);
  std::sort(top_.begin(), top_.end());
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
  PhaseTrace part;
  parallel_chunks(subtrees_.size(), 1, threads, part, [&](std::size_t k, std::size_t, int) {
    const Index r = subtrees_[k];
    for (Index i = r + 2 * bvh_.leaf_count[r] - 2; i >= r; --i) {
      if (bvh_.nodes[i].is_leaf()) cone_[i] = face_cone(i);
      else merge_children(i);
    }
  });
  trace.task_ms = part.task_ms;
  auto t0 = Clock::now();
  for (auto it = top_.rbegin(); it != top_.rend(); ++it) merge_children(*it);
  // 2. Skips top-down: above the cut (serial), then inside each sub-tree (parallel).
  std::uint64_t edges = 0, skipped = 0;
  auto decide = [&](Index i, std::uint64_t& e, std::uint64_t& s) {
    const Index p = bvh_.nodes[i].parent;
    if (p >= 0 && skip_root_[p] >= 0) skip_root_[i] = skip_root_[p];
    else if (bvh_.leaf_count[i] >= kMinLeaves && passes(i, x0, x1, e)) skip_root_[i] = i, ++s;
    else skip_root_[i] = -1;
  };
  for (Index i : top_) decide(i, edges, skipped);
  trace.serial_ms += ms_between(t0, Clock::now());
  std::vector<PerThread<std::array<std::uint64_t, 2>>> counts(threads);
  parallel_chunks(subtrees_.size(), 1, threads, part, [&](std::size_t k, std::size_t, int tid) {
    const Index r = subtrees_[k];
    auto& c = counts[tid].value;
    for (Index i = r; i < r + 2 * bvh_.leaf_count[r] - 1; ++i) decide(i, c[0], c[1]);
  });
  trace.task_ms.insert(trace.task_ms.end(), part.task_ms.begin(), part.task_ms.end());
  for (const auto& c : counts) edges += c.value[0], skipped += c.value[1];
  contour_edge_tests_ = edges;
  return skipped;
}

}  // namespace ccdlab

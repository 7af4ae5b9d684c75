#include "framework/pipeline/work_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

#include <fmt/format.h>

namespace ccdlab {
namespace {

/// Whether `outer` contains `inner` on every axis (then every leaf under inner overlaps outer).
template <class BV>
bool contains(const BV& outer, const BV& inner) {
  for (int i = 0; i < BV::num_axes; ++i)
    if (inner.min(i) < outer.min(i) || inner.max(i) > outer.max(i)) return false;
  return true;
}

/// Leaves of `bvh` whose volumes overlap `query`, leaf `skip` (the query's own, in a self pass) left out.
template <class BV>
double overlapping_leaves(const BvhTopology& bvh, const BvArray<BV>& bvs, const BV& query, Index skip,
                          std::vector<Index>& stack) {
  double count = 0;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const Index n = stack.back();
    stack.pop_back();
    if (!query.overlaps(bvs[n])) continue;
    const BvhNode& node = bvh.nodes[n];
    const bool holds_skip = skip >= n && skip < bvh.subtree_end(n);
    if (node.is_leaf()) {
      count += n != skip;
    } else if (contains(query, bvs[n])) {
      count += double(bvh.leaf_count[n]) - (holds_skip ? 1 : 0);
    } else {
      stack.push_back(node.left), stack.push_back(node.right);
    }
  }
  return count;
}

}  // namespace

WorkEstimate estimate_candidates(const std::vector<TraversalPass>& passes, std::size_t faces, std::size_t samples) {
  WorkEstimate e;
  e.faces = faces;
  std::vector<Index> leaves, stack;
  for (const TraversalPass& pass : passes) {
    const BvhTopology& a = *pass.side_a.bvh;
    const BvhTopology& b = *pass.side_b.bvh;
    leaves.clear();
    for (Index n = 0; n < a.size(); ++n)
      if (a.nodes[n].is_leaf()) leaves.push_back(n);
    if (leaves.empty() || b.size() == 0) continue;
    const std::size_t picked = std::min(samples, leaves.size());
    double sum = 0;
    std::visit(
        [&](const auto& bvs_a) {
          using Array = std::decay_t<decltype(bvs_a)>;
          const Array& bvs_b = std::get<Array>(*pass.side_b.bvs);
          for (std::size_t s = 0; s < picked; ++s) {
            const Index leaf = leaves[s * leaves.size() / picked];  // evenly spaced over the pre-order
            sum += overlapping_leaves(b, bvs_b, bvs_a[leaf], pass.self ? leaf : Index(-1), stack);
          }
        },
        *pass.side_a.bvs);
    e.sampled += picked;
    e.candidates += sum / double(picked) * double(leaves.size()) * (pass.self ? 0.5 : 1.0);
  }
  return e;
}

namespace {

struct SceneSize {
  double diagonal = 0, largest = 0;  ///< the bounding box's diagonal over both frames; the largest |coordinate|
};
SceneSize scene_size(const Positions& x_t0, const Positions& x_t1) {
  Box3 box;
  for (std::size_t v = 0; v < x_t0.size(); ++v) box.grow(x_t0[v]), box.grow(x_t1[v]);
  if (x_t0.empty()) return {};
  // stableNorm: the diagonal of a scene at 1e-200 must not underflow to 0 on the way.
  return {box.extent().stableNorm(), std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff())};
}

}  // namespace

double bounding_box_diagonal(const Positions& x) { return scene_size(x, x).diagonal; }

std::string scale_problem(const Positions& x_t0, const Positions& x_t1) {
  const SceneSize s = scene_size(x_t0, x_t1);
  if (s.largest > kMaxCoordinate)
    return fmt::format("coordinates up to {:.3g}, above {:g}: ccdlab's bounding volumes are single precision and the "
                       "float tester multiplies three coordinates, both would overflow; express the scene in a larger "
                       "unit", s.largest, kMaxCoordinate);
  if (s.diagonal > 0 && s.diagonal < kMinDiagonal)
    return fmt::format("the scene's bounding-box diagonal is {:.3g}, below {:g}: the float tester's tolerances "
                       "(products of three lengths) would underflow; express the scene in a smaller unit",
                       s.diagonal, kMinDiagonal);
  return {};
}

std::string explain_work(const TriMesh& mesh, const Positions& x_t0, const Positions& x_t1, double thickness,
                         std::string_view thickness_name) {
  double motion = 0;
  for (std::size_t v = 0; v < x_t0.size(); ++v) motion = std::max(motion, (x_t1[v] - x_t0[v]).norm());
  const auto [diagonal, largest] = scene_size(x_t0, x_t1);
  double edges = 0;
  for (const Edge& edge : mesh.edges()) edges += (x_t0[edge[1]] - x_t0[edge[0]]).norm();
  const double mean_edge = mesh.edges().empty() ? 0.0 : edges / double(mesh.edges().size());
  if (diagonal < 1e-5 * largest)  // a float's step at the scene's coordinates is above a fiftieth of its size
    return fmt::format("the scene (diagonal {:.3g}) lies at coordinates up to {:.3g}: at that distance from the origin "
                       "single-precision bounding volumes cannot tell its triangles apart; move it near the origin.",
                       diagonal, largest);
  if (thickness >= 0.1 * mean_edge && thickness > 0)
    return fmt::format("{} {:g} is {:.3g}× the scene's diagonal ({:.3g}) and {:.3g}× its mean edge length ({:.3g}): is it "
                       "in the scene's units? It is usually below the mean edge length.",
                       thickness_name, thickness, thickness / diagonal, diagonal, thickness / mean_edge, mean_edge);
  return fmt::format("the swept volumes overlap most of the scene: the largest vertex motion in this step is {:.3g}, "
                     "{:.3g}× the mean edge length ({:.3g}) and {:.3g}× the scene's diagonal ({:.3g}): are the two "
                     "frames of one simulation, in one unit?",
                     motion, motion / mean_edge, mean_edge, motion / diagonal, diagonal);
}

}  // namespace ccdlab

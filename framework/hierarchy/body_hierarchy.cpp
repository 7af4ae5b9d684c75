#include "framework/hierarchy/body_hierarchy.hpp"

#include <chrono>

#include "framework/swept/feature_bounds.hpp"
#include "framework/util/memory.hpp"

namespace ccdlab {
namespace {

using Clock = std::chrono::steady_clock;

/// How many nodes ahead the refit's leaf pass asks for a leaf's vertices: enough to cover a miss to memory at
/// about two nodes a leaf.
constexpr std::size_t kLeafAhead = 16;


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

/// The box each face sweeps over the step (its six vertex positions): what the builders split on.
Box3 swept_box(const TriMesh& mesh, Index f, const Positions& x_t0, const Positions& x_t1) {
  Box3 box;
  for (Index v : mesh.face(f)) {
    box.grow(x_t0[v]);
    box.grow(x_t1[v]);
  }
  return box;
}

}  // namespace

BodyHierarchy::BodyHierarchy(const TriMesh& mesh, std::vector<Index> faces, bool self_collides, const Settings& settings)
    : mesh_(mesh),
      faces_(std::move(faces)),
      self_collides_(self_collides),
      settings_(settings),
      node_bvs_(make_bvs(settings.k)),
      node_wide_(make_wide_bvs(settings.k)) {}

void BodyHierarchy::build(const Positions& x_t0, const Positions& x_t1, const HierarchyBuilder& builder,
                          PhaseTrace& trace) {
  UninitializedVector<Box3> boxes(faces_.size());  // large: in huge pages (memory.hpp)
  parallel_chunks(faces_.size(), kFaceChunk, settings_.threads, trace, [&](std::size_t b, std::size_t e, int) {
    for (std::size_t i = b; i < e; ++i) boxes[i] = swept_box(mesh_, faces_[i], x_t0, x_t1);
  });
  bvh_ = builder.build(faces_, boxes, {settings_.threads, &trace});
  if (bvh_.nodes.empty()) return;
  const auto t0 = Clock::now();
  // Restructuring units, independent of the thread count.
  restructure_roots_.clear();
  const Index max_leaves = std::max<Index>(64, bvh_.num_leaves() / 64);
  std::vector<Index> stack{0};
  while (!stack.empty()) {
    const Index n = stack.back();
    stack.pop_back();
    if (bvh_.leaf_count[n] <= max_leaves) {
      if (bvh_.leaf_count[n] > 2) restructure_roots_.push_back(n);
    } else {
      stack.push_back(bvh_.nodes[n].right);
      stack.push_back(bvh_.nodes[n].left);
    }
  }
  quality_ref_.assign(restructure_roots_.size(), 0.0);  // set after the first refit
  trace.serial_ms += ms_since(t0);
  // The end boxes' pages are touched now, in the build step: the first step that keeps them would otherwise pay
  // their page faults, and the rule that measures that step would charge them to the end boxes.
  if (settings_.end_boxes) {
    node_ends_.resize(bvh_.nodes.size());
    parallel_chunks(node_ends_.size(), 2 * kFaceChunk, settings_.threads, trace, [&](std::size_t b, std::size_t e, int) {
      std::fill(node_ends_.begin() + std::ptrdiff_t(b), node_ends_.begin() + std::ptrdiff_t(e), EndBoxes::empty());
    });
  }
}

void BodyHierarchy::refit(const FeatureBounds& swept_dops, std::optional<double> end_reach, PhaseTrace& trace) {
  const BvhTopology& bvh = bvh_;
  std::visit(
      [&](auto& node_bvs) {
        using BV = typename std::decay_t<decltype(node_bvs)>::value_type;
        node_bvs.resize(bvh.nodes.size());  // uninitialised: the leaves' pass touches every page first, in parallel
        // The leaves first, in node order: their faces and vertex 26-DOPs are scattered reads, which the CPU
        // overlaps across independent iterations (a fused bottom-up sweep is slower: docs/pipeline.md, §2).
        const SweptFaceBv<BV> swept{mesh_, swept_dops};
        const bool ends = settings_.end_boxes && end_reach;
        if (ends) node_ends_.resize(bvh.nodes.size());
        const FramePoints* points = swept_dops.frame_points();
        const double r = end_reach.value_or(0) / 2;
        const PaddedDop* dops = swept_dops.dops();
        parallel_chunks(bvh.nodes.size(), 2 * kFaceChunk, settings_.threads, trace, [&](std::size_t b, std::size_t e, int) {
          for (std::size_t i = b; i < e; ++i) {
            // Ask early for the vertices of the leaf kLeafAhead nodes on: those reads miss the caches more often
            // than not (a face's vertices lie apart in memory), and their latency, not the arithmetic, sets the
            // pace of this loop.
            if (i + kLeafAhead < e && bvh.nodes[i + kLeafAhead].is_leaf())
              for (Index v : mesh_.face(bvh.nodes[i + kLeafAhead].face)) {
                __builtin_prefetch(&dops[v]);
                __builtin_prefetch(reinterpret_cast<const char*>(&dops[v]) + 64);
                if (ends) __builtin_prefetch(&points[v]);
              }
            if (bvh.nodes[i].is_leaf()) {
              node_bvs[i] = swept(bvh.nodes[i].face);
              if (ends) node_ends_[i] = face_end_boxes(points, mesh_.face(bvh.nodes[i].face), r);
            }
          }
        });
        const RefitPlan& plan = bvh.refit_plan();  // cut again whenever restructuring changed the topology
        const LeavesInPlace leaf_bv;
        parallel_chunks(plan.subtrees.size(), 1, settings_.threads, trace, [&](std::size_t b, std::size_t e, int) {
          for (std::size_t s = b; s < e; ++s) {
            const Index root = plan.subtrees[s];
            if (!ends) {
              refit_subtree(bvh, node_bvs, root, leaf_bv);
              continue;
            }
            for (Index i = bvh.subtree_end(root) - 1; i >= root; --i) {  // both volumes in one sweep of the nodes
              refit_node(bvh, node_bvs, i, leaf_bv);
              refit_node(bvh, node_ends_, i, leaf_bv);
            }
          }
        });
        const auto t0 = Clock::now();
        for (Index i : plan.top) {
          refit_node(bvh, node_bvs, i, leaf_bv);
          if (ends) refit_node(bvh, node_ends_, i, leaf_bv);
        }
        trace.serial_ms += ms_since(t0);
      },
      node_bvs_);
}

std::uint64_t BodyHierarchy::restructure(const Positions& x_t0, const Positions& x_t1, const FeatureBounds& swept_dops,
                                         std::optional<double> end_reach, const HierarchyBuilder& builder, PhaseTrace& trace) {
  std::uint64_t rebuilt = 0;
  std::visit(
      [&](auto& node_bvs) {
        using BV = typename std::decay_t<decltype(node_bvs)>::value_type;
        const std::size_t units = restructure_roots_.size();
        std::vector<char> degraded(units, 0);
        std::vector<BvhTopology> replacement(units);
        parallel_chunks(units, 1, settings_.threads, trace, [&](std::size_t u, std::size_t, int) {
          const Index r = restructure_roots_[u];
          const double q = subtree_quality(bvh_, node_bvs, r);
          if (quality_ref_[u] == 0) {
            quality_ref_[u] = q;  // first refit after a (re)build
            return;
          }
          if (q <= settings_.restructure_threshold * quality_ref_[u]) return;
          // Degraded: rebuild this sub-tree over its faces from their current swept boxes.
          std::vector<Index> faces = subtree_faces(bvh_, r);
          std::vector<Box3> boxes(faces.size());
          for (std::size_t i = 0; i < faces.size(); ++i) boxes[i] = swept_box(mesh_, faces[i], x_t0, x_t1);
          replacement[u] = builder.build(faces, boxes);
          degraded[u] = 1;
        });
        const auto t0 = Clock::now();
        for (std::size_t u = 0; u < units; ++u) {
          if (!degraded[u]) continue;
          const Index r = restructure_roots_[u];
          // A new topology version: the refit plan, wide layout, normal cones and fronts are cut again from it.
          replace_subtree(bvh_, r, replacement[u]);
          // Its leaves now hold other faces: their swept volumes are computed again.
          refit_subtree(bvh_, node_bvs, r, SweptFaceBv<BV>{mesh_, swept_dops});
          for (Index p = bvh_.nodes[r].parent; p >= 0; p = bvh_.nodes[p].parent) refit_node(bvh_, node_bvs, p, LeavesInPlace{});
          if (settings_.end_boxes && end_reach) {
            refit_subtree(bvh_, node_ends_, r, [&](Index f) { return face_end_boxes(swept_dops.frame_points(), mesh_.face(f), *end_reach / 2); });
            for (Index p = bvh_.nodes[r].parent; p >= 0; p = bvh_.nodes[p].parent) refit_node(bvh_, node_ends_, p, LeavesInPlace{});
          }
          quality_ref_[u] = subtree_quality(bvh_, node_bvs, r);
          ++rebuilt;
        }
        trace.serial_ms += ms_since(t0);
      },
      node_bvs_);
  return rebuilt;
}

void BodyHierarchy::follow_topology() {
  if (settings_.width == 4) {
    wide_layout_ = WideLayout::of(bvh_, mesh_.faces());
    wide_lanes_stale_ = true;
    if (settings_.end_boxes && wide_ends_.size() < wide_layout_.lanes.size()) {  // touched now, as in build()
      const std::size_t before = wide_ends_.size();
      wide_ends_.resize(wide_layout_.lanes.size());
      std::fill(wide_ends_.begin() + std::ptrdiff_t(before), wide_ends_.end(), WideEnds{});
    }
  }
  if (settings_.normal_cones && self_collides_ && !bvh_.nodes.empty())
    cones_ = std::make_unique<NormalConeCuller>(mesh_, bvh_, settings_.threads);  // which patches are disks
  followed_version_ = bvh_.version;
}

void BodyHierarchy::refit_wide(bool ends, PhaseTrace& trace) {
  const WideLayout& layout = wide_layout_;
  const bool copy_lanes = wide_lanes_stale_;
  ends = ends && settings_.end_boxes;
  std::visit(
      [&](auto& node_wide) {
        using Bounds = typename std::decay_t<decltype(node_wide)>::value_type;
        using Vec = BvArray<typename Bounds::Volume>;
        const Vec& bvs = std::get<Vec>(node_bvs_);
        node_wide.resize(layout.lanes.size());
        if (ends) wide_ends_.resize(layout.lanes.size());
        parallel_chunks(layout.lanes.size(), 4096, settings_.threads, trace, [&](std::size_t b, std::size_t e, int) {
          for (std::size_t w = b; w < e; ++w) {
            // The lanes are scattered over the binary array: ask for the next nodes' early (memory-bound loop).
            if (w + 8 < e)
              for (Index c : layout.lanes[w + 8].node)
                if (c >= 0) {
                  __builtin_prefetch(&bvs[c]);
                  if (ends) __builtin_prefetch(&node_ends_[c]);
                }
            if (copy_lanes) node_wide[w].lanes = layout.lanes[w];  // the LaneIds: fixed until the topology changes
            refit_wide_bounds(layout, bvs, Index(w), node_wide[w]);
            if (ends) refit_wide_ends(layout, node_ends_, Index(w), wide_ends_[w]);
          }
        });
      },
      node_wide_);
  wide_lanes_stale_ = false;
}

std::uint64_t BodyHierarchy::update_cones(const Positions& x_t0, const Positions& x_t1, PhaseTrace& trace) {
  if (!cones_) return 0;
  const std::uint64_t skipped = cones_->update(x_t0, x_t1, settings_.threads, trace);
  skip_root_ = cones_->skip_root();
  return skipped;
}

void BodyHierarchy::mark_skipped_patches(std::vector<Index>& face_patch) const {
  if (!cones_) return;
  for (Index i = 0; i < bvh_.size(); ++i)
    if (bvh_.nodes[i].is_leaf()) face_patch[bvh_.nodes[i].face] = skip_root_[i];
}

std::size_t BodyHierarchy::memory_bytes() const {
  return bvh_.memory_bytes() + std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, node_bvs_) +
         wide_layout_.memory_bytes() + std::visit([](const auto& v) { return v.size() * sizeof(v[0]); }, node_wide_) +
         node_ends_.size() * sizeof(EndBoxes) + wide_ends_.size() * sizeof(WideEnds);
}

}  // namespace ccdlab

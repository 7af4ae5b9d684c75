#include "framework/hierarchy/topdown_build.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <utility>

namespace ccdlab {
namespace {

/// Ranges of at most this many faces (or 1/256 of the tree, if larger) become one parallel task each.
constexpr std::size_t kBuildTaskItems = 2048;

/// items[begin, end) becomes node `id` (and its sub-tree).
struct Range {
  std::size_t begin, end;
  Index id, parent;
};

}  // namespace

BvhTopology build_top_down(std::span<const Index> faces, std::span<const Box3> face_boxes, BuildExecution exec,
                           const SplitRule& split) {
  BvhTopology bvh;
  if (faces.empty()) return bvh;
  const auto t_start = std::chrono::steady_clock::now();
  UninitializedVector<BuildItem> items(faces.size());  // large: in huge pages (memory.hpp)
  for (std::size_t i = 0; i < faces.size(); ++i) items[i] = {face_boxes[i].center(), faces[i], Index(i)};
  bvh.nodes.assign(2 * faces.size() - 1, BvhNode{});

  // Writes range r's node; returns its children's ranges (none for a leaf). Each node is written by the one
  // call that owns its range, so sub-trees can be built concurrently.
  auto place = [&](const Range& r, Range (&children)[2]) {
    BvhNode& node = bvh.nodes[std::size_t(r.id)];
    node.parent = r.parent;
    if (r.end - r.begin == 1) {
      node.face = items[r.begin].face;
      return false;
    }
    const std::size_t mid = r.begin + split(std::span<BuildItem>(items.data() + r.begin, r.end - r.begin));
    node.left = r.id + 1;
    node.right = r.id + Index(2 * (mid - r.begin));
    children[0] = {r.begin, mid, node.left, r.id};
    children[1] = {mid, r.end, node.right, r.id};
    return true;
  };
  auto build_subtree = [&](const Range& root) {
    std::vector<Range> stack{root};
    Range children[2];
    while (!stack.empty()) {
      const Range r = stack.back();
      stack.pop_back();
      if (place(r, children)) stack.insert(stack.end(), {children[1], children[0]});
    }
  };

  // Level by level, the large ranges split in parallel with each other; ranges of at most task_items faces
  // are set aside and built as whole sub-trees, in parallel, at the end.
  const int threads = std::max(1, exec.threads);
  const std::size_t task_items = std::max(kBuildTaskItems, faces.size() / 256);
  PhaseTrace part;
  std::vector<Range> level{{0, items.size(), 0, -1}}, tasks, large;
  std::vector<std::array<Range, 2>> children;
  std::vector<std::uint8_t> inner;
  while (!level.empty()) {
    large.clear();
    for (const Range& r : level) (r.end - r.begin <= task_items ? tasks : large).push_back(r);
    children.resize(large.size());
    inner.resize(large.size());
    parallel_tasks(large.size(), threads, Distribution::dynamic, part, [&](std::size_t i, int) {
      Range two[2]{};  // a leaf has no children: copied, never read
      inner[i] = place(large[i], two);
      children[i] = {two[0], two[1]};
    });
    level.clear();
    for (std::size_t i = 0; i < large.size(); ++i)
      if (inner[i]) level.insert(level.end(), {children[i][0], children[i][1]});
  }
  const auto t_tasks = std::chrono::steady_clock::now();
  PhaseTrace& trace = exec.trace ? *exec.trace : part;
  parallel_tasks(tasks.size(), threads, Distribution::dynamic, trace, [&](std::size_t i, int) { build_subtree(tasks[i]); });
  const auto t_counts = std::chrono::steady_clock::now();
  compute_leaf_counts(bvh);
  // For the simulated cores (schedule_sim.hpp) the levels count as serial: each waits for the one before, and
  // the first is a single split. An overestimate of the serial part, never an underestimate.
  trace.serial_ms += ms_between(t_start, t_tasks) + ms_between(t_counts, std::chrono::steady_clock::now());
  return bvh;
}

std::size_t median_split(std::span<BuildItem> items, int axis) {
  const std::size_t mid = items.size() / 2;
  std::nth_element(items.begin(), items.begin() + std::ptrdiff_t(mid), items.end(),
                   [axis](const BuildItem& a, const BuildItem& b) {
                     return a.centroid[axis] != b.centroid[axis] ? a.centroid[axis] < b.centroid[axis]
                                                                 : a.face < b.face;
                   });
  return mid;
}

Box3 centroid_bounds(std::span<const BuildItem> items) {
  Box3 b;
  for (const BuildItem& it : items) b.grow(it.centroid);
  return b;
}

}  // namespace ccdlab

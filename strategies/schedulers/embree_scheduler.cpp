#include "strategies/schedulers/embree_scheduler.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <mutex>

#include "framework/util/error.hpp"

namespace ccdlab {
namespace {

/// One BVH's leaves as Embree user primitives: primitive i is leaf node leaf_node[i].
struct Side {
  RTCScene scene = nullptr;
  RTCGeometry geometry = nullptr;
  std::vector<Index> leaf_node;
  std::vector<RTCBounds> bounds;  ///< this step's boxes, read by the bounds callback
};

void bounds_of(const RTCBoundsFunctionArguments* args) {
  const auto* side = static_cast<const Side*>(args->geometryUserPtr);
  *args->bounds_o = side->bounds[args->primID];
}

struct Collisions {
  std::mutex mutex;
  std::vector<std::pair<unsigned, unsigned>> pairs;
};

void collect_pairs(void* user, RTCCollision* collisions, unsigned count) {
  auto* out = static_cast<Collisions*>(user);
  const std::lock_guard<std::mutex> lock(out->mutex);
  for (unsigned i = 0; i < count; ++i) out->pairs.emplace_back(collisions[i].primID0, collisions[i].primID1);
}

}  // namespace

struct EmbreeScheduler::State {
  RTCDevice device = nullptr;
  int threads = 0;
  std::map<int, std::pair<Side, Side>> passes;  ///< per pass id: side a, side b (b unused in self passes)

  void release(Side& s) {
    if (s.geometry) rtcReleaseGeometry(s.geometry);
    if (s.scene) rtcReleaseScene(s.scene);
    s = {};
  }
  void release_all() {
    for (auto& [id, sides] : passes) release(sides.first), release(sides.second);
    passes.clear();
  }
  ~State() {
    release_all();
    if (device) rtcReleaseDevice(device);
  }
  void ensure_device(int t) {
    if (device && threads == t) return;
    release_all();
    if (device) rtcReleaseDevice(device);
    const std::string cfg = "threads=" + std::to_string(t) + ",set_affinity=0";
    device = rtcNewDevice(cfg.c_str());
    if (!device) fail("scheduler embree: rtcNewDevice failed (error {})", int(rtcGetDeviceError(nullptr)));
    threads = t;
  }
  /// (Re)builds Embree's BVH over the leaves of `bvh`, boxed by their k-DOPs' first three slabs.
  template <class BV>
  void build(Side& s, const BvhTopology& bvh, const BvArray<BV>& bvs) {
    if (!s.scene) {
      s.scene = rtcNewScene(device);
      rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_LOW);  // rebuilt every step: a fast build
      s.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserData(s.geometry, &s);
      rtcSetGeometryBoundsFunction(s.geometry, bounds_of, nullptr);
      rtcAttachGeometry(s.scene, s.geometry);
    }
    s.leaf_node.clear();
    s.bounds.clear();
    for (Index i = 0; i < bvh.size(); ++i) {
      if (!bvh.nodes[i].is_leaf()) continue;
      const BV& v = bvs[i];
      s.leaf_node.push_back(i);
      s.bounds.push_back(RTCBounds{v.min(0), v.min(1), v.min(2), 0.f, v.max(0), v.max(1), v.max(2), 0.f});
    }
    rtcSetGeometryUserPrimitiveCount(s.geometry, unsigned(s.leaf_node.size()));
    rtcCommitGeometry(s.geometry);
    rtcCommitScene(s.scene);
    if (const RTCError e = rtcGetDeviceError(device); e != RTC_ERROR_NONE)
      fail("scheduler embree: building the scene failed (error {})", int(e));
  }
};

EmbreeScheduler::EmbreeScheduler() : state_(std::make_unique<State>()) {}
EmbreeScheduler::~EmbreeScheduler() = default;

void EmbreeScheduler::release(int pass_id) {
  if (auto it = state_->passes.find(pass_id); it != state_->passes.end()) {
    state_->release(it->second.first);
    state_->release(it->second.second);
    state_->passes.erase(it);
  }
}

void EmbreeScheduler::collect(const TraversalPass& pass, TraversalOutput& out, std::vector<PhaseTrace>& traces) {
  if (pass.side_a.bvh->nodes.empty() || pass.side_b.bvh->nodes.empty()) return;
  const auto t0 = std::chrono::steady_clock::now();
  const bool whole = pass.root.a == 0 && pass.root.b == 0;
  const bool culled = pass.skip_root && !pass.skip_root->empty();
  with_bvtt_view(pass, [&](const auto& view) {
    if (!whole || culled) {  // see the header: ccdlab's own traversal
      BvttStack stack;
      traverse_bvtt(view, pass.root, stack, out.pairs.part(0), out.bv_tests);
      return;
    }
    state_->ensure_device(pass.threads);
    auto& [a, b] = state_->passes[pass.id];
    state_->build(a, *view.side_a.bvh, *view.side_a.bv);
    if (!pass.self) state_->build(b, *view.side_b.bvh, *view.side_b.bv);
    const Side& other = pass.self ? a : b;
    Collisions found;
    rtcCollide(a.scene, other.scene, collect_pairs, &found);
    if (const RTCError e = rtcGetDeviceError(state_->device); e != RTC_ERROR_NONE)
      fail("scheduler embree: rtcCollide failed (error {})", int(e));
    // Exactly sequential's candidates: overlapping leaf k-DOPs, non-adjacent, each unordered pair once.
    FacePairs pairs;
    pairs.reserve(found.pairs.size());
    std::uint64_t tests = 0;
    for (auto [i, j] : found.pairs) {
      const Index na = a.leaf_node[i], nb = other.leaf_node[j];
      if (pass.self && na == nb) continue;
      ++tests;
      if (!view.nodes_overlap(na, nb)) continue;
      view.emit_leaf_pair(view.side_a.bvh->nodes[na], view.side_b.bvh->nodes[nb], pairs);
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    out.pairs.part(0).insert(out.pairs.part(0).end(), pairs.begin(), pairs.end());
    out.bv_tests += tests;
  });
  const double ms = ms_between(t0, std::chrono::steady_clock::now());
  out.stats.serial_ms += ms;  // Embree's own threads; ccdlab sees one call
  traces.push_back(PhaseTrace{"traverse", Distribution::dynamic, ms, {}, {}});
}

}  // namespace ccdlab

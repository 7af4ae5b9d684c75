#pragma once
// A hierarchy as a traversal pass reads it, whichever K it uses: its node bounds (AnyBvs), their 4-wide view
// (AnyWideBvs) and the end boxes, with its topology (PassSide). The pipeline keeps them per body
// (body_hierarchy.hpp); the traversal (framework/traversal/pass.hpp) reads them at their static type.
#include <variant>

#include "framework/geometry/kdop.hpp"
#include "framework/hierarchy/bvh.hpp"
#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/swept/end_boxes.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {

/// A hierarchy's node bounds, whichever K it uses (KdopKs).
using AnyBvs = KdopVariant<BvArray>;
/// The 4-wide bounds of the same hierarchy (bv.width: 4), same alternative as its AnyBvs.
using AnyWideBvs = KdopVariant<WideBvs>;

/// An AnyBvs / AnyWideBvs holding an empty array of KDop<k>; throws Error unless is_kdop_k(k).
inline AnyBvs make_bvs(int k) {
  if (auto v = empty_kdop_variant<BvArray>(k)) return std::move(*v);
  fail("bv.k: expected one of {}, got {}", kKdopKs, k);
}
inline AnyWideBvs make_wide_bvs(int k) {
  if (auto v = empty_kdop_variant<WideBvs>(k)) return std::move(*v);
  fail("bv.k: expected one of {}, got {}", kKdopKs, k);
}

/// One hierarchy of a pass as the pipeline hands it over: its topology and node volumes and, where the pipeline
/// keeps them, its 4-wide view (bv.width: 4, refit with the binary volumes) and end boxes (framework/swept/
/// end_boxes.hpp, of the nodes and of the wide records' lanes). BodyHierarchy::side fills one in.
struct PassSide {
  const BvhTopology* bvh = nullptr;
  const AnyBvs* bvs = nullptr;
  const WideLayout* wide_layout = nullptr;
  const AnyWideBvs* wide = nullptr;
  const BvArray<EndBoxes>* ends = nullptr;
  const WideEndsArray* wide_ends = nullptr;
};

}  // namespace ccdlab

#pragma once
// `median`: top-down; split at the median of the face centroids along the widest axis of the centroid
// bounds (the classic object-median split, balanced: depth ⌈log2 n⌉).
#include "framework/hierarchy/bvh.hpp"

namespace ccdlab {

class MedianBuilder final : public HierarchyBuilder {
 public:
  [[nodiscard]] std::string_view name() const override { return "median"; }
  [[nodiscard]] BvhTopology build(std::span<const Index> faces, std::span<const Box3> face_boxes,
                                  BuildExecution exec = {}) const override;
};

}  // namespace ccdlab

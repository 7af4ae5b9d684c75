#pragma once
// `sah`: top-down binned surface-area heuristic (Wald 2007): centroids binned along each axis, the split
// with the lowest  area(L)·n(L) + area(R)·n(R)  is taken; one face per leaf, so it always splits.
// Falls back to the median split when all centroids coincide.
#include "framework/hierarchy/bvh.hpp"

namespace ccdlab {

class SahBuilder final : public HierarchyBuilder {
 public:
  struct Params {
    int bins = 16;  ///< bins per axis, 2..256
  };
  SahBuilder() = default;
  explicit SahBuilder(Params p) : params_(p) {}
  [[nodiscard]] std::string_view name() const override { return "sah"; }
  [[nodiscard]] BvhTopology build(std::span<const Index> faces, std::span<const Box3> face_boxes,
                                  BuildExecution exec = {}) const override;

 private:
  Params params_{};
};

}  // namespace ccdlab

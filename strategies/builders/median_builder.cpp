#include "strategies/builders/median_builder.hpp"

#include "framework/hierarchy/topdown_build.hpp"

namespace ccdlab {

BvhTopology MedianBuilder::build(std::span<const Index> faces, std::span<const Box3> face_boxes,
                                 BuildExecution exec) const {
  return build_top_down(faces, face_boxes, exec, [](std::span<BuildItem> items) {
    int axis;
    centroid_bounds(items).extent().maxCoeff(&axis);
    return median_split(items, axis);
  });
}

}  // namespace ccdlab

#include "strategies/builders/median_builder.hpp"

#include <algorithm>

#include "framework/hierarchy/topdown_build.hpp"

namespace ccdlab {

BvhTopology MedianBuilder::build(std::span<const Index> faces, std::span<const Box3> face_boxes,
                                 BuildExecution exec) const {
  return build_top_down(faces, face_boxes, exec, [](std::span<BuildItem> items) {
    Box3 cb;
    for (const auto& it : items) cb.grow(it.centroid);
    int axis;
    cb.extent().maxCoeff(&axis);
    std::size_t mid = items.size() / 2;
    // Ties broken by face id: the tree does not depend on the sort implementation.
    std::nth_element(items.begin(), items.begin() + std::ptrdiff_t(mid), items.end(),
                     [axis](const BuildItem& a, const BuildItem& b) {
                       return a.centroid[axis] != b.centroid[axis] ? a.centroid[axis] < b.centroid[axis]
                                                                   : a.face < b.face;
                     });
    return mid;
  });
}

}  // namespace ccdlab

#include "strategies/builders/sah_builder.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include "framework/hierarchy/topdown_build.hpp"

namespace ccdlab {
namespace {

double half_area(const Box3& b) {
  if (b.lo.x() > b.hi.x()) return 0;
  Vec3 e = b.extent();
  return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

}  // namespace

BvhTopology SahBuilder::build(std::span<const Index> faces, std::span<const Box3> face_boxes,
                              BuildExecution exec) const {
  const int nb = params_.bins;
  return build_top_down(faces, face_boxes, exec, [nb, face_boxes](std::span<BuildItem> items) -> std::size_t {
    const Box3 cb = centroid_bounds(items);
    int widest;
    Vec3 ext = cb.extent();
    ext.maxCoeff(&widest);
    if (items.size() <= 4 || ext[widest] <= 0) return median_split(items, widest);

    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = -1;
    // Bin on all three axes in one pass over the items: each face's box is read once (by index, from face_boxes).
    std::array<std::vector<Box3>, 3> bin_box;
    std::array<std::vector<std::size_t>, 3> bin_count;
    Vec3 scale;
    for (int axis = 0; axis < 3; ++axis) {
      bin_box[axis].assign(std::size_t(nb), Box3{});
      bin_count[axis].assign(std::size_t(nb), 0);
      scale[axis] = ext[axis] > 0 ? nb / ext[axis] : 0.0;
    }
    for (const auto& it : items) {
      const Box3& box = face_boxes[std::size_t(it.box)];
      for (int axis = 0; axis < 3; ++axis) {
        const int b = std::min(nb - 1, int((it.centroid[axis] - cb.lo[axis]) * scale[axis]));
        bin_box[axis][std::size_t(b)].grow(box);
        ++bin_count[axis][std::size_t(b)];
      }
    }
    std::vector<double> right_area(nb);
    std::vector<std::size_t> right_count(nb);
    for (int axis = 0; axis < 3; ++axis) {
      if (ext[axis] <= 0) continue;
      Box3 acc;
      std::size_t cnt = 0;
      for (int b = nb - 1; b > 0; --b) {
        acc.grow(bin_box[axis][std::size_t(b)]);
        cnt += bin_count[axis][std::size_t(b)];
        right_area[b] = half_area(acc);
        right_count[b] = cnt;
      }
      acc = Box3{};
      cnt = 0;
      for (int b = 0; b < nb - 1; ++b) {  // split between bin b and b+1
        acc.grow(bin_box[axis][std::size_t(b)]);
        cnt += bin_count[axis][std::size_t(b)];
        if (cnt == 0 || right_count[b + 1] == 0) continue;
        double cost = half_area(acc) * double(cnt) + right_area[b + 1] * double(right_count[b + 1]);
        if (cost < best_cost) best_cost = cost, best_axis = axis, best_bin = b;
      }
    }
    if (best_axis < 0) return median_split(items, widest);
    auto it = std::partition(items.begin(), items.end(), [&](const BuildItem& item) {
      return std::min(nb - 1, int((item.centroid[best_axis] - cb.lo[best_axis]) * scale[best_axis])) <= best_bin;
    });
    return std::size_t(it - items.begin());
  });
}

}  // namespace ccdlab

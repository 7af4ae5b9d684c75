#include "strategies/builders/sah_builder.hpp"

#include <algorithm>
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
    std::vector<Box3> bin_box(nb);
    std::vector<std::size_t> bin_count(nb);
    std::vector<double> right_area(nb);
    std::vector<std::size_t> right_count(nb);
    for (int axis = 0; axis < 3; ++axis) {
      if (ext[axis] <= 0) continue;
      std::fill(bin_box.begin(), bin_box.end(), Box3{});
      std::fill(bin_count.begin(), bin_count.end(), 0);
      const double scale = nb / ext[axis];
      auto bin_of = [&](const BuildItem& it) {
        return std::min(nb - 1, int((it.centroid[axis] - cb.lo[axis]) * scale));
      };
      for (const auto& it : items) {
        int b = bin_of(it);
        bin_box[b].grow(face_boxes[std::size_t(it.box)]);
        ++bin_count[b];
      }
      Box3 acc;
      std::size_t cnt = 0;
      for (int b = nb - 1; b > 0; --b) {
        acc.grow(bin_box[b]);
        cnt += bin_count[b];
        right_area[b] = half_area(acc);
        right_count[b] = cnt;
      }
      acc = Box3{};
      cnt = 0;
      for (int b = 0; b < nb - 1; ++b) {  // split between bin b and b+1
        acc.grow(bin_box[b]);
        cnt += bin_count[b];
        if (cnt == 0 || right_count[b + 1] == 0) continue;
        double cost = half_area(acc) * double(cnt) + right_area[b + 1] * double(right_count[b + 1]);
        if (cost < best_cost) best_cost = cost, best_axis = axis, best_bin = b;
      }
    }
    if (best_axis < 0) return median_split(items, widest);
    const double scale = nb / ext[best_axis];
    auto it = std::partition(items.begin(), items.end(), [&](const BuildItem& item) {
      return std::min(nb - 1, int((item.centroid[best_axis] - cb.lo[best_axis]) * scale)) <= best_bin;
    });
    return std::size_t(it - items.begin());
  });
}

}  // namespace ccdlab

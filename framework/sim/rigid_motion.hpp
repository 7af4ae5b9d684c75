#pragma once
// Scripted rigid motion of an obstacle (or any kinematic body): a translation at constant velocity, a spin
// about an axis through a pivot starting at some time, and optional keyframes (time, offset, angle about the
// spin axis) interpolated linearly. Positions are exact functions of time, so every sub-step and every thread
// count sees the same obstacle. A motion may have a parent (a capsule chain: the shin moves with the thigh):
// its transform is then the parent's at t composed with its own, so a joint stays where the parent puts it.
#include <algorithm>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "framework/geometry/vec.hpp"

namespace ccdlab {

struct RigidKeyframe {
  double time = 0;       ///< seconds
  Vec3 offset = Vec3::Zero();
  double angle = 0;      ///< radians about the spin axis through the pivot
};

struct RigidMotion {
  Vec3 velocity = Vec3::Zero();  ///< translation per second, from `move_start` to `move_end`
  double move_start = 0, move_end = 1e300;
  Vec3 pivot = Vec3::Zero();     ///< the spin axis passes through it (moves with the translation)
  Vec3 axis = Vec3::UnitY();
  double spin_rate = 0;          ///< radians per second, from `spin_start`
  double spin_start = 0;
  std::vector<RigidKeyframe> keyframes;  ///< sorted by time; before the first / after the last: held
  std::shared_ptr<const RigidMotion> parent;  ///< applied after this motion (in the parent's frame), or none

  [[nodiscard]] bool moves() const {
    return velocity.squaredNorm() > 0 || spin_rate != 0 || !keyframes.empty() || (parent && parent->moves());
  }

  /// The rigid transform at time t: a rest point r goes to P(t) (R(t) (r − pivot) + pivot + offset(t)), P the
  /// parent's transform (identity without a parent).
  [[nodiscard]] Eigen::Isometry3d at(double t) const { return parent ? parent->at(t) * own_at(t) : own_at(t); }

 private:
  [[nodiscard]] Eigen::Isometry3d own_at(double t) const {
    Vec3 offset = velocity * (std::clamp(t, move_start, move_end) - move_start);
    double angle = spin_rate * std::max(0.0, t - spin_start);
    if (!keyframes.empty()) {
      const auto after = std::find_if(keyframes.begin(), keyframes.end(), [&](const RigidKeyframe& k) { return k.time > t; });
      if (after == keyframes.begin()) {
        offset += after->offset, angle += after->angle;
      } else if (after == keyframes.end()) {
        offset += keyframes.back().offset, angle += keyframes.back().angle;
      } else {
        const RigidKeyframe& a = *(after - 1);
        const double w = (t - a.time) / (after->time - a.time);
        offset += (1 - w) * a.offset + w * after->offset;
        angle += (1 - w) * a.angle + w * after->angle;
      }
    }
    Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
    m.translate(pivot + offset);
    m.rotate(Eigen::AngleAxisd(angle, axis.normalized()));
    m.translate(-pivot);
    return m;
  }
};

}  // namespace ccdlab

#include "strategies/effects/impact_zones.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <utility>

#include <Eigen/Eigenvalues>

#include "framework/pipeline/ccd_pipeline.hpp"

namespace ccdlab {

void ImpactZones::reset(std::size_t vertices) {
  parent_.resize(vertices);
  std::iota(parent_.begin(), parent_.end(), Index(0));
  touched_.clear();
}

ImpactZones::Outcome ImpactZones::resolve(CcdPipeline& crossing, const SimSetup& setup, SimState& s, double dt,
                                           int max_rounds, const Contacts* found) {
  reset(s.p.size());
  inelastic_ = false;
  Outcome out;
  StepResult r;
  int moves = 0;
  for (int round = 0;; ++round) {  // the last detection checks the last move
    if (round == 0 && found != nullptr) {
      r.contacts = *found;
    } else {
      r = crossing.step(s.x, s.p);
      ++out.detections;
    }
    out.left = r.contacts.size();
    if (out.left == 0 || round == max_rounds) break;
    // Contacts that keep cascading (a zone's motion runs into more cloth, round after round) escalate: from
    // round kEscalate on, everything in contact merges into one zone, so the zone grows by all of it at once.
    // Escalated zones also give up their momentum: a zone without scripted vertices stops for the sub-step (an
    // inelastic impact — still a rigid motion), so it cannot run into more cloth. From round kWholeBodies on,
    // the zone takes in every vertex of each cloth body it touches: a cloth turning with a spinning ball then
    // turns with it whole, instead of sweeping into the rest of itself round after round — with one scripted
    // motion in the zone (or none), the next round finds no contact.
    const bool into_one = round >= kEscalate;
    std::size_t joined = merge(r.contacts, into_one);
    if (round >= kWholeBodies) joined += merge_bodies(setup, r.contacts);
    if (joined == 0) break;
    escalated += round == kEscalate;
    whole_bodies += round == kWholeBodies;
    inelastic_ = into_one;
    out.handled += out.left;
    move(setup, s, dt);
    ++moves;
  }
  most_rounds = std::max<std::uint64_t>(most_rounds, std::uint64_t(moves));
  return out;
}

std::size_t ImpactZones::merge_bodies(const SimSetup& setup, const Contacts& contacts) {
  if (contacts.empty()) return 0;
  const Index root = find(contacts.front().vertices[0]);
  std::size_t joined = 0;
  for (const Body& b : setup.bodies) {
    if (b.kind != BodyKind::cloth) continue;
    const bool touched = std::any_of(contacts.begin(), contacts.end(), [&](const Contact& c) {
      return std::any_of(c.vertices.begin(), c.vertices.end(),
                         [&](Index v) { return v >= b.vertex_begin && v < b.vertex_end; });
    });
    if (!touched) continue;
    for (Index v = b.vertex_begin; v < b.vertex_end; ++v) {
      Index a = find(root), other = find(v);
      if (a == other) continue;
      if (other < a) std::swap(a, other);
      parent_[std::size_t(other)] = a;
      ++joined;
    }
  }
  refresh_members();
  return joined;
}

Index ImpactZones::find(Index v) {
  while (parent_[std::size_t(v)] != v) {
    parent_[std::size_t(v)] = parent_[std::size_t(parent_[std::size_t(v)])];  // path halving
    v = parent_[std::size_t(v)];
  }
  return v;
}

std::size_t ImpactZones::merge(const Contacts& contacts, bool into_one) {
  std::size_t joined = 0;
  for (const Contact& c : contacts) {
    bool new_zone = false;
    Index root = find(into_one ? contacts.front().vertices[0] : c.vertices[0]);
    for (std::size_t k = into_one ? 0 : 1; k < 4; ++k) {
      Index other = find(c.vertices[k]);
      if (other == root) continue;
      new_zone = true;
      if (other < root) std::swap(other, root);  // the smaller index is the root: the same zones whatever the order
      parent_[std::size_t(other)] = root;
    }
    if (new_zone) ++joined;
  }
  refresh_members();
  return joined;
}

void ImpactZones::refresh_members() {
  // The zones' members: every vertex that is not its own root, and the roots of those.
  touched_.clear();
  for (std::size_t v = 0; v < parent_.size(); ++v)
    if (parent_[v] != Index(v)) touched_.push_back(Index(v)), touched_.push_back(find(Index(v)));
  std::sort(touched_.begin(), touched_.end());
  touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
}

namespace {

/// Where a scripted vertex goes over the sub-step, as a rigid transform of its position at t: its obstacle's
/// motion, or (pins, handles) the translation its scripted motion gives it.
Eigen::Isometry3d scripted_motion(const SimSetup& setup, const SimState& s, std::size_t v, double dt) {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  if (v < setup.follows.size() && setup.follows[v] >= 0) {
    const RigidMotion& motion = setup.obstacles[std::size_t(setup.follows[v])].motion;
    return motion.at(s.time + dt) * motion.at(s.time).inverse();
  }
  m.translate(s.p[v] - s.x[v]);
  return m;
}

/// The rigid motion that keeps a free zone's linear and angular momentum (Bridson et al. 2002, §7.4).
Eigen::Isometry3d momentum_motion(const SimSetup& setup, const SimState& s, const std::vector<Index>& zone, double dt) {
  double mass = 0;
  Vec3 centre = Vec3::Zero(), momentum = Vec3::Zero();
  for (Index v : zone) {
    const double m = 1 / setup.inv_mass[std::size_t(v)];
    mass += m, centre += m * s.x[std::size_t(v)], momentum += m * s.v[std::size_t(v)];
  }
  centre /= mass;
  const Vec3 velocity = momentum / mass;
  Vec3 angular = Vec3::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (Index v : zone) {
    const double m = 1 / setup.inv_mass[std::size_t(v)];
    const Vec3 r = s.x[std::size_t(v)] - centre;
    angular += m * r.cross(s.v[std::size_t(v)] - velocity);
    inertia += m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  // ω = I⁻¹L, with a pseudo-inverse: a zone whose vertices are collinear cannot spin about its own line.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia);
  const Vec3 lambda = eigen.eigenvalues();
  Vec3 in_basis = eigen.eigenvectors().transpose() * angular;
  for (int k = 0; k < 3; ++k) in_basis[k] = lambda[k] > 1e-12 * lambda.maxCoeff() ? in_basis[k] / lambda[k] : 0;
  const Vec3 omega = eigen.eigenvectors() * in_basis;
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  m.translate(centre + dt * velocity);
  if (const double w = omega.norm(); w > 0) m.rotate(Eigen::AngleAxisd(w * dt, omega / w));
  m.translate(-centre);
  return m;
}

}  // namespace

void ImpactZones::move(const SimSetup& setup, SimState& s, double dt) {
  // Group the members by zone, in vertex order within each zone (deterministic sums).
  std::vector<std::pair<Index, Index>> by_zone;  // (root, vertex)
  by_zone.reserve(touched_.size());
  for (Index v : touched_) by_zone.emplace_back(find(v), v);
  std::sort(by_zone.begin(), by_zone.end());
  std::vector<Index> free, scripted;
  std::vector<Eigen::Isometry3d> motions;  // of the zone's scripted vertices
  std::vector<std::size_t> order;
  for (std::size_t begin = 0; begin < by_zone.size();) {
    std::size_t end = begin;
    free.clear(), scripted.clear();
    for (; end < by_zone.size() && by_zone[end].first == by_zone[begin].first; ++end) {
      const Index v = by_zone[end].second;
      (setup.inv_mass[std::size_t(v)] > 0 ? free : scripted).push_back(v);
    }
    begin = end;
    if (free.empty()) continue;
    largest_zone = std::max<std::uint64_t>(largest_zone, free.size() + scripted.size());
    ++zones_moved;
    auto place = [&](Index v, const Eigen::Isometry3d& motion) {
      const auto i = std::size_t(v);
      s.p[i] = motion * s.x[i];
      s.v[i] = (s.p[i] - s.x[i]) / dt;
    };
    if (scripted.empty()) {
      const Eigen::Isometry3d motion = inelastic_ ? Eigen::Isometry3d::Identity() : momentum_motion(setup, s, free, dt);
      for (Index v : free) place(v, motion);
      continue;
    }
    motions.clear();
    for (Index v : scripted) motions.push_back(scripted_motion(setup, s, std::size_t(v), dt));
    bool pinched = false;
    for (std::size_t k = 1; k < scripted.size() && !pinched; ++k) {
      const auto i = std::size_t(scripted[k]);
      pinched = (motions.front() * s.x[i] - s.p[i]).norm() > 1e-9 * (1 + s.p[i].norm());
    }
    if (!pinched) {
      for (Index v : free) place(v, motions.front());
      continue;
    }
    // No rigid motion follows two scripted motions. Each free vertex follows, of the zone's scripted vertices
    // nearest first, the first whose motion does not carry it into an obstacle's exact shape (sphere, capsule)
    // at t + dt — cloth on a knee follows whichever of thigh and shin keeps it outside both — else the nearest.
    // Counted: contacts this leaves are counted by the caller.
    ++pinched_zones;
    order.resize(scripted.size());
    for (Index v : free) {
      const auto i = std::size_t(v);
      std::iota(order.begin(), order.end(), std::size_t(0));
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const double da = (s.x[std::size_t(scripted[a])] - s.x[i]).squaredNorm();
        const double db = (s.x[std::size_t(scripted[b])] - s.x[i]).squaredNorm();
        return da < db || (da == db && a < b);
      });
      std::size_t chosen = order.front();
      for (std::size_t k : order) {
        const Vec3 p = motions[k] * s.x[i];
        if (std::none_of(setup.obstacles.begin(), setup.obstacles.end(),
                         [&](const SimObstacle& o) { return o.contains(p, s.time + dt); })) {
          chosen = k;
          break;
        }
      }
      place(v, motions[chosen]);
    }
  }
}

}  // namespace ccdlab

#include "framework/geometry/distance.hpp"

#include <algorithm>
#include <cmath>

namespace ccdlab {

SegmentSegmentClosest closest_segment_segment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a == 0 && e == 0) {
    s = t = 0;
  } else if (a == 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e == 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;  // >= 0; 0 when parallel
      s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
      if (!(denom > 1e-14 * a * e)) {
        // Parallel: also try the other segment's end points, the closest pair may be there.
        auto try_point = [&](const Vec3& p, const Vec3& o, const Vec3& d, double dd, bool on_p, double fixed) {
          double u = std::clamp((p - o).dot(d) / dd, 0.0, 1.0);
          double dist = (o + u * d - p).squaredNorm();
          return std::tuple(dist, on_p ? u : fixed, on_p ? fixed : u);
        };
        double best = ((p0 + s * d1) - (q0 + t * d2)).squaredNorm();
        for (auto cand : {try_point(q0, p0, d1, a, true, 0.0), try_point(q1, p0, d1, a, true, 1.0),
                          try_point(p0, q0, d2, e, false, 0.0), try_point(p1, q0, d2, e, false, 1.0)}) {
          auto [dist, cs, ct] = cand;
          if (dist < best) best = dist, s = cs, t = ct;
        }
      }
    }
  }
  return {((p0 + s * d1) - (q0 + t * d2)).squaredNorm(), s, t};
}

PointTriangleClosest closest_point_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  const Vec3 n = ab.cross(ac);
  const double scale = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
  if (n.squaredNorm() <= 1e-24 * scale * scale) {
    // Degenerate (collinear or point) triangle: closest of its three edges.
    PointTriangleClosest best{std::numeric_limits<double>::infinity(), {1, 0, 0}};
    const Vec3* v[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
      const Vec3& s0 = *v[i];
      const Vec3& s1 = *v[(i + 1) % 3];
      auto r = closest_segment_segment(s0, s1, p, p);
      if (r.distance_sq < best.distance_sq) {
        best.distance_sq = r.distance_sq;
        best.bary = {0, 0, 0};
        best.bary[i] += 1 - r.s;
        best.bary[(i + 1) % 3] += r.s;
      }
    }
    return best;
  }
  // Voronoi regions of the triangle (Ericson 5.1.5).
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {ap.squaredNorm(), {1, 0, 0}};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {bp.squaredNorm(), {0, 1, 0}};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    double w = d1 / (d1 - d3);
    return {(p - (a + w * ab)).squaredNorm(), {1 - w, w, 0}};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {cp.squaredNorm(), {0, 0, 1}};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    double w = d2 / (d2 - d6);
    return {(p - (a + w * ac)).squaredNorm(), {1 - w, 0, w}};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {(p - (b + w * (c - b))).squaredNorm(), {0, 1 - w, w}};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {(p - (a + v * ab + w * ac)).squaredNorm(), {1 - v - w, v, w}};
}

}  // namespace ccdlab

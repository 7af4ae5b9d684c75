#pragma once
// For the ladder tests (tests/strategies/): a tester's answer to a query of a set, exact's decision, and random
// elementary queries whose answers are unknown by construction (checked against `exact`).
#include <random>
#include <string>

#include "framework/queries/query_set.hpp"
#include "strategies/testers/exact_tester.hpp"

namespace ccdlab::test {

/// A tester's answer to query i of a set, whichever its kind.
inline CcdHit run(const PrimitiveTester& t, const QuerySet& s, std::size_t i) {
  return s.kind == ContactKind::vf ? t.vertex_face(s.vf[i]) : t.edge_edge(s.ee[i]);
}
/// exact's decision (with its time enclosure) on query i of a set.
inline ExactTester::Decision decide(const ExactTester& t, const QuerySet& s, std::size_t i) {
  return s.kind == ContactKind::vf ? t.decide(s.vf[i]) : t.decide(s.ee[i]);
}

/// Random queries around contact: a vertex (or edge b) aimed at a random point of the face (edge a), landing
/// at a random time, then nudged by up to `jitter` — many touch, many just miss.
inline QuerySet random_near_contacts(ContactKind kind, int n, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), w(0, 1);
  auto rv = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  QuerySet s;
  s.name = "random";
  s.kind = kind;
  for (int k = 0; k < n; ++k) {
    const Vec3 p0 = rv(), p1 = rv(), p2 = rv(), q0 = rv(), q1 = rv(), q2 = rv();
    const double a = w(rng), b = w(rng) * (1 - a), tc = w(rng);
    if (kind == ContactKind::vf) {
      // Where the face is at tc, and a vertex path through that point.
      const Vec3 hit_at = (p0 + tc * (q0 - p0)) + a * ((p1 + tc * (q1 - p1)) - (p0 + tc * (q0 - p0))) +
                          b * ((p2 + tc * (q2 - p2)) - (p0 + tc * (q0 - p0)));
      const Vec3 d = rv();
      const Vec3 v0 = hit_at - tc * d + jitter * rv(), v1 = hit_at + (1 - tc) * d;
      s.vf.push_back({v0, p0, p1, p2, v1, q0, q1, q2});
    } else {
      const Vec3 on_a = (p0 + tc * (q0 - p0)) + a * ((p1 + tc * (q1 - p1)) - (p0 + tc * (q0 - p0)));
      const Vec3 d0 = rv(), d1 = rv(), off = rv();
      const double s_b = w(rng);
      // Edge b passes through on_a at tc, at parameter s_b along it.
      const Vec3 b0_tc = on_a - s_b * off, b1_tc = on_a + (1 - s_b) * off;
      s.ee.push_back({p0, p1, b0_tc - tc * d0 + jitter * rv(), b1_tc - tc * d1, q0, q1, b0_tc + (1 - tc) * d0, b1_tc + (1 - tc) * d1});
    }
    s.truth.push_back(0);
    s.toi.push_back(std::nan(""));
    s.origin.push_back("random #" + std::to_string(k));
  }
  return s;
}

}  // namespace ccdlab::test

#include "framework/queries/evaluate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

namespace ccdlab {

std::vector<QueryOutcome> run_tester(const PrimitiveTester& tester, const QuerySet& set, int repeat) {
  using Clock = std::chrono::steady_clock;
  std::vector<QueryOutcome> out(set.size());
  for (std::size_t i = 0; i < set.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    CcdHit h;
    for (int r = 0; r < std::max(1, repeat); ++r) {
      const auto t0 = Clock::now();
      h = set.kind == ContactKind::vf ? tester.vertex_face(set.vf[i]) : tester.edge_edge(set.ee[i]);
      const auto t1 = Clock::now();
      best = std::min(best, std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
    out[i] = {h.hit, h.toi, h.route, best};
  }
  return out;
}

SetScore score(const QuerySet& set, const std::string& tester, const std::vector<QueryOutcome>& outcomes,
               const std::vector<ToiReference>& reference) {
  SetScore s;
  s.set = set.name;
  s.scene = set.scene;
  s.collection = set.collection;
  s.tester = tester;
  s.queries = set.size();
  std::vector<double> us;
  us.reserve(outcomes.size());
  std::size_t toi_count = 0;
  double toi_sum = 0;
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const QueryOutcome& o = outcomes[i];
    const bool truth = set.truth[i] != 0;
    s.positives += truth;
    if (truth && !o.hit) ++s.false_negatives, s.failures.push_back(i);
    if (!truth && o.hit) ++s.false_positives, s.failures.push_back(i);
    s.filtered += o.route == TestRoute::filter;
    s.fallbacks += o.route == TestRoute::fallback;
    us.push_back(o.us);
    if (o.hit && i < reference.size() && reference[i].hit) {
      const ToiReference& r = reference[i];
      const double err = o.toi < r.toi_lo ? r.toi_lo - o.toi : o.toi > r.toi_hi ? o.toi - r.toi_lo : r.toi_hi - r.toi_lo;
      s.toi_max_error = std::max(s.toi_max_error, err);
      toi_sum += err;
      ++toi_count;
      s.toi_late += o.toi > r.toi_hi;
    }
  }
  if (toi_count) s.toi_mean_error = toi_sum / double(toi_count);
  if (!us.empty()) {
    s.mean_us = std::accumulate(us.begin(), us.end(), 0.0) / double(us.size());
    std::sort(us.begin(), us.end());
    auto quantile = [&](double q) { return us[std::min(us.size() - 1, std::size_t(std::floor(q * double(us.size() - 1) + 0.5)))]; };
    s.median_us = quantile(0.5);
    s.p99_us = quantile(0.99);
    s.max_us = us.back();
  }
  return s;
}

}  // namespace ccdlab

#include "framework/pipeline/pipeline_settings.hpp"

#include <cmath>

#include "framework/util/error.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {

namespace setting_check {
std::string k(long long k) { return is_kdop_k(int(k)) && k == int(k) ? "" : fmt::format("one of {}", kKdopKs); }
std::string width(long long w) { return is_bvh_width(int(w)) && w == int(w) ? "" : kBvhWidths; }
std::string threads(long long t) {
  return t >= 1 && t <= kMaxThreads ? "" : fmt::format("an integer from 1 to {}", kMaxThreads);
}
std::string split_threads(long long t) {
  return t >= 0 && t <= kMaxThreads ? "" : fmt::format("0 (= threads) or an integer up to {}", kMaxThreads);
}
std::string restructure_threshold(double t) {
  return t == 0 || (t >= 1 && std::isfinite(t)) ? "" : "0 (off) or a finite number >= 1";
}
std::string candidate_limit(double c) { return c >= 0 && std::isfinite(c) ? "" : "0 (no limit) or a finite number > 0"; }
std::string time_limit(double s) { return s >= 0 && std::isfinite(s) ? "" : "0 (no limit) or a finite number of seconds > 0"; }
}  // namespace setting_check

void PipelineSettings::validate(const SettingName& name) const {
  const auto check = [&](std::string_view key, const std::string& expected, const auto& value) {
    if (!expected.empty()) fail("{}: expected {}, got {}", name ? name(key) : std::string(key), expected, value);
  };
  check("bv.k", setting_check::k(k), k);
  check("bv.width", setting_check::width(width), width);
  check("threads", setting_check::threads(threads), threads);
  check("split_threads", setting_check::split_threads(split_threads), split_threads);
  check("restructure.threshold", setting_check::restructure_threshold(restructure_threshold), restructure_threshold);
  check("candidate_limit", setting_check::candidate_limit(candidate_limit), candidate_limit);
  check("time_limit", setting_check::time_limit(time_limit), time_limit);
}

}  // namespace ccdlab

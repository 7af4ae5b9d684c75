#include "experiments/cli/report.hpp"

#include <algorithm>
#include <fstream>

#include <fmt/format.h>

namespace ccdlab::cli {

nlohmann::json step_json(const StepResult& r) {
  const StepCounters& c = r.counters;
  const StepTimings& t = r.timings;
  return {{"contacts", {{"vf", c.contacts_vf}, {"ee", c.contacts_ee}}},
          {"counters",
           {{"bv_tests", c.bv_tests},
            {"candidate_pairs", c.candidate_pairs},
            {"vf_pairs", c.vf_pairs},
            {"ee_pairs", c.ee_pairs},
            {"orphan_vf", c.orphan_vf},
            {"orphan_ee", c.orphan_ee},
            {"vf_tests", c.vf_tests},
            {"ee_tests", c.ee_tests},
            {"orphan_tests", c.orphan_tests},
            {"restructured", c.restructured},
            {"orphans_culled", c.orphans_culled},
            {"orphans_unmoved", c.orphans_unmoved},
            {"orphans_carried", c.orphans_carried},
            {"candidates_gathered", c.candidates_gathered},
            {"tests_filtered", c.tests_filtered},
            {"tests_fallback", c.tests_fallback}}},
          {"narrow_stages",  // pairs removed by each culling stage; thread-time of each stage
           {{"triangle_tested", c.triangle_tested}, {"triangle_fine", c.triangle_fine},
            {"triangle_culled", c.triangle_culled},
            {"triangle_ms", double(c.triangle_ns) * 1e-6},
            {"kdop_culled", c.kdop_culled},
            {"plane_culled", c.plane_culled},
            {"split_culled", c.split_culled},
            {"split_ms", double(c.split_ns + c.sixteenths_ns) * 1e-6},
            {"sixteenths_ms", double(c.sixteenths_ns) * 1e-6},
            {"sixteenths_tested", c.sixteenths_tested},
            {"sixteenths_culled", c.sixteenths_culled},
            {"proximity_tested", c.proximity_tested},
            {"proximity_culled", c.proximity_culled},
            {"proximity_ms", double(c.proximity_ns) * 1e-6},
            {"gather_ms", double(c.gather_ns) * 1e-6},
            {"kdop_ms", double(c.kdop_ns) * 1e-6},
            {"plane_ms", double(c.plane_ns) * 1e-6},
            {"test_ms", double(c.test_ns) * 1e-6},
            {"orphan_motion_ms", double(c.orphan_motion_ns) * 1e-6}}},
          {"traversal",
           {{"tasks", r.traversal.tasks},
            {"serial_ms", r.traversal.serial_ms},
            {"front_nodes", r.traversal.front_nodes},
            {"front_bytes", r.traversal.front_bytes},
            {"front_visited", r.traversal.front_visited},
            {"sprouted", r.traversal.sprouted},
            {"pruned", r.traversal.pruned},
            {"rebuilds", r.traversal.rebuilds},
            {"cone_culled", r.traversal.cone_culled},
            {"contour_edges", r.traversal.contour_edges}}},
          {"memory",
           {{"peak_rss_mb", double(r.memory.peak_rss_bytes) / (1 << 20)},
            {"limit_mb", double(r.memory.limit_bytes) / (1 << 20)},
            {"streamed_slices", r.memory.slices},
            {"page_faults", r.memory.page_faults}}},
          {"ms",
           {{"total", t.total_ms},
            {"build", t.build_ms},
            {"swept_bv", t.swept_bv_ms},
            {"refit", t.refit_ms},
            {"normal_cones", t.cones_ms},
            {"traverse", t.traverse_ms},
            {"narrow", t.narrow_ms},
            {"orphans", t.orphan_ms}}}};
}

std::string csv_header() {
  return "bv_tests,candidate_pairs,vf_pairs,ee_pairs,orphan_vf,orphan_ee,vf_tests,ee_tests,orphan_tests,tests_filtered,"
         "tests_fallback,kdop_culled,plane_culled,split_culled,contacts_vf,contacts_ee,"
         "build_ms,swept_bv_ms,refit_ms,cones_ms,traverse_ms,narrow_ms,orphan_ms,total_ms,peak_rss_mb,streamed_slices,page_faults,hash";
}

std::string csv_row(const StepResult& r, std::uint64_t step_hash) {
  const StepCounters& c = r.counters;
  const StepTimings& t = r.timings;
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.1f},{},{},{:016x}",
                     c.bv_tests, c.candidate_pairs, c.vf_pairs, c.ee_pairs, c.orphan_vf, c.orphan_ee, c.vf_tests,
                     c.ee_tests, c.orphan_tests, c.tests_filtered, c.tests_fallback, c.kdop_culled, c.plane_culled, c.split_culled,
                     c.contacts_vf, c.contacts_ee, t.build_ms, t.swept_bv_ms, t.refit_ms, t.cones_ms, t.traverse_ms, t.narrow_ms, t.orphan_ms,
                     t.total_ms, double(r.memory.peak_rss_bytes) / (1 << 20), r.memory.slices,
                     r.memory.page_faults, step_hash);
}

std::string contact_row(const Contact& c, const Positions& x_t0, const Positions& x_t1) {
  const Vec3 n = contact_normal(c, x_t0, x_t1);
  return fmt::format("{},{},{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", to_string(c.kind), c.vertices[0],
                     c.vertices[1], c.vertices[2], c.vertices[3], c.toi, c.coords[0], c.coords[1], n.x(), n.y(), n.z());
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

void print_table_header(std::FILE* out) {
  fmt::print(out, "{:>9} {:>10} {:>9} {:>9} {:>8} {:>8} {:>9} {:>9} | {:>8} {:>7} {:>7} {:>8} {:>8} {:>8}\n", "step",
             "bv_tests", "cand", "vf_tests", "ee_tests", "orphans", "vf_hits", "ee_hits", "total_ms", "bv_ms",
             "refit", "traverse", "narrow", "orphan");
}

void print_table_row(std::FILE* out, const std::string& step, const StepResult& r) {
  const StepCounters& c = r.counters;
  const StepTimings& t = r.timings;
  fmt::print(out, "{:>9} {:>10} {:>9} {:>9} {:>8} {:>8} {:>9} {:>9} | {:>8.2f} {:>7.2f} {:>7.2f} {:>8.2f} {:>8.2f} {:>8.2f}\n",
             step, c.bv_tests, c.candidate_pairs, c.vf_tests, c.ee_tests, c.orphan_vf + c.orphan_ee, c.contacts_vf,
             c.contacts_ee, t.total_ms, t.swept_bv_ms, t.refit_ms, t.traverse_ms, t.narrow_ms, t.orphan_ms);
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

}  // namespace ccdlab::cli

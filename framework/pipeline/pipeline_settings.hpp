#pragma once
// A pipeline's settings as plain values, each with its default (the pipeline's own Params) and its check
// (setting_check, validate). What a user may set, under which key, flag and keyword, is described once, in the
// settings table (framework/config/settings.def); every entry point — YAML and --set, the CLI's flags, the C++
// API's Options, the Python module's keywords — fills these in through it. The strategies themselves (builder,
// scheduler, tester) are chosen by name and made from their registries, whose parameter defaults are the
// strategies' own Params.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "framework/geometry/kdop.hpp"
#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/narrow/narrow_phase.hpp"
#include "framework/util/error.hpp"
#include "framework/util/named_values.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {

/// bv.end_boxes (framework/swept/end_boxes.hpp): test the nodes' boxes at both ends of the step in every
/// step (`on`), never (`off`), or in the steps where they pay (`automatic`, written `auto`: EndBoxRule).
enum class EndBoxMode { off, on, automatic };
/// bv.end_boxes's names (YAML's booleans true and false among them).
inline constexpr NamedValues<EndBoxMode, 5> kEndBoxModes{{{{"on", EndBoxMode::on},
                                                           {"off", EndBoxMode::off},
                                                           {"auto", EndBoxMode::automatic},
                                                           {"true", EndBoxMode::on},
                                                           {"false", EndBoxMode::off}}}};
[[nodiscard]] inline std::string_view to_string(EndBoxMode m) { return kEndBoxModes.name_of(m); }

/// The strategies a configuration names when it names none (their parameters: the registries' defaults), and the
/// memory limit's default text (parse_memory_size).
inline constexpr const char* kDefaultHierarchy = "median";
inline constexpr const char* kDefaultScheduler = "sequential";
inline constexpr const char* kDefaultTester = "float";
inline constexpr const char* kDefaultMemoryLimit = "80%";

/// How an entry point spells a setting in its messages, given its config key ("bv.k"): YAML writes the key, the
/// CLI its flag ("--k"), the C++ API its member ("Options::k"). Empty: the key.
using SettingName = std::function<std::string(std::string_view key)>;

struct PipelineSettings {
  int k = 18;                    ///< bv.k: the k-DOP (KdopKs)
  int width = kDefaultBvhWidth;  ///< bv.width: 2 (binary) or 4 (framework/hierarchy/wide_bvh.hpp)
  int threads = 1;               ///< threads for every stage
  /// The thread count the BVTT is split for (phc and static cut c·N tasks); 0 = `threads`. `ccdlab bench` runs
  /// 1 thread with split_threads = N to record the tasks N cores would get, so the simulator replays them.
  int split_threads = 0;
  /// restructure.threshold: rebuild a sub-tree when its quality (Σ sizes of inner nodes ÷ size of its root)
  /// exceeds this × its value at the last (re)build. 0 = off.
  double restructure_threshold = 0;
  /// normal_cones: continuous normal-cone culling of self tests (framework/hierarchy/normal_cones.hpp); thickness 0 only.
  bool normal_cones = false;
  /// bv.end_boxes: the traversal also drops node pairs apart on x, y or z at both ends of the step. Needs the
  /// tester's reach (PrimitiveTester::cull_reach); off for a tester without one.
  EndBoxMode end_boxes = EndBoxMode::automatic;
  /// Bytes the process may hold resident during a step (0 = no limit), resolved from memory_limit's text: above the
  /// predicted need, a step streams its candidates to the narrow phase slice by slice (memory_budget.hpp).
  std::uint64_t memory_limit_bytes = 0;
  /// Stream every step in (about) this many slices per pass, whatever the memory: to test streaming and to
  /// measure its cost. 0 = only when the memory limit asks for it.
  std::size_t stream_slices = 0;
  /// candidate_limit: a step estimated (framework/pipeline/work_estimate.hpp) to find more candidate triangle
  /// pairs per triangle than this is refused before its traversal, with the numbers that explain it. 0 = no limit.
  /// The default: 40× the densest real step we know (~26 candidate triangle pairs per triangle, a tangled
  /// 92K-triangle cloth), far below the thousands per triangle of a thickness in the wrong unit.
  double candidate_limit = 1000;
  /// time_limit: seconds a step may run (framework/pipeline/step_watch.hpp); past them its workers stop taking
  /// work and the step throws Error with what it had done. 0 = no limit.
  double time_limit = 0;
  /// narrow {mode, representative}: how the narrow phase runs (framework/narrow/).
  NarrowOptions narrow;

  /// The one check of the plain settings: throws Error "<name(key)>: expected …, got …" for the first wrong one.
  void validate(const SettingName& name = {}) const;
};

/// What is wrong with one setting's value, as the "expected …" text of a message; empty when it is valid.
/// PipelineSettings::validate and the settings table (framework/config/settings.def, whose readers add the
/// line or the flag) both ask these: each valid set is written here only.
namespace setting_check {
[[nodiscard]] inline std::string k(long long k) {
  return is_kdop_k(int(k)) && k == int(k) ? "" : fmt::format("one of {}", kKdopKs);
}
[[nodiscard]] inline std::string width(long long w) { return is_bvh_width(int(w)) && w == int(w) ? "" : kBvhWidths; }
[[nodiscard]] inline std::string threads(long long t) {
  return t >= 1 && t <= kMaxThreads ? "" : fmt::format("an integer from 1 to {}", kMaxThreads);
}
[[nodiscard]] inline std::string split_threads(long long t) {
  return t >= 0 && t <= kMaxThreads ? "" : fmt::format("0 (= threads) or an integer up to {}", kMaxThreads);
}
[[nodiscard]] inline std::string restructure_threshold(double t) {
  return t == 0 || (t >= 1 && std::isfinite(t)) ? "" : "0 (off) or a finite number >= 1";
}
[[nodiscard]] inline std::string candidate_limit(double c) {
  return c >= 0 && std::isfinite(c) ? "" : "0 (no limit) or a finite number > 0";
}
[[nodiscard]] inline std::string time_limit(double s) {
  return s >= 0 && std::isfinite(s) ? "" : "0 (no limit) or a finite number of seconds > 0";
}
/// A setting every value of its type is right for (a boolean).
[[nodiscard]] inline std::string any(bool) { return ""; }
}  // namespace setting_check

inline void PipelineSettings::validate(const SettingName& name) const {
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

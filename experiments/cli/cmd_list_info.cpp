// `ccdlab list`: the registered strategies with their parameters. `ccdlab info`: how this binary was built.
#include <omp.h>

#include "ccdlab/build_info.hpp"
#include "experiments/cli/commands.hpp"
#include "framework/config/settings.hpp"
#include "framework/geometry/kdop.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::cli {
namespace {

template <class R>
void print_registry(const R& registry, const std::string& title) {
  fmt::print("{}:\n", title);
  for (const auto& e : registry.entries()) {
    fmt::print("  {:<12} {}\n", e.name, e.description);
    for (const auto& p : e.params) {
      std::string range;
      if (p.type == ParamType::integer || p.type == ParamType::real)
        range = fmt::format(" in [{}, {}]", p.min, p.max);
      fmt::print("      {:<16} {} (default {}){} — {}\n", p.name, to_string(p.type), default_text(p), range, p.description);
    }
  }
  fmt::print("\n");
}

}  // namespace

int list_command(bool settings_table) {
  if (settings_table) {  // docs/config.md's table, as Markdown
    fmt::print("{}", settings_markdown(builtin_registries()));
    return 0;
  }
  fmt::print("settings (ccdlab list --settings: key, default, accepted values, flag, keyword):\n");
  for (const Setting& s : settings()) fmt::print("  {:<28} {}\n", s.key, s.doc);
  fmt::print("\nbv.k: {} (k-DOP axis tables in framework/geometry/kdop.hpp)\n\n", kKdopKs);
  print_registry(builder_registry(), "hierarchy");
  print_registry(scheduler_registry(), "scheduler");
  print_registry(tester_registry(), "tester");
  print_registry(scene_registry(), "scene.builtin");
  print_registry(effect_registry(), "effects (of simulated scenes: ccdlab simulate)");
  return 0;
}

int info_command() {
  fmt::print("ccdlab {}\n", build_info::git_revision);
  fmt::print("  compiler   {}\n", build_info::compiler);
  fmt::print("  build type {}\n", build_info::build_type);
  fmt::print("  flags      {}\n", build_info::cxx_flags);
#ifdef _OPENMP
  fmt::print("  OpenMP     {} (max threads {}, processors {})\n", _OPENMP, omp_get_max_threads(), omp_get_num_procs());
#else
  fmt::print("  OpenMP     off\n");
#endif
  return 0;
}

}  // namespace ccdlab::cli

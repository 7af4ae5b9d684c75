// `ccdlab step T0 T1 [--k K] [--scheduler S] [--threads N] [--tester NAME[:key=value,…]] [--narrow MODE]
//  [--representative RULE] [--contacts FILE.csv] [--json] [--earliest]`:
// one CCD step between two mesh files of the same topology (one self-colliding body); with --earliest, only
// its earliest time of contact.


#include <algorithm>

#include "experiments/cli/commands.hpp"
#include "experiments/cli/step_progress.hpp"
#include "framework/config/pipeline_config.hpp"
#include "framework/config/strategy_spec.hpp"
#include "experiments/cli/report.hpp"
#include "framework/mesh/mesh_io.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/util/memory.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::cli {
namespace {

template <class R>
StrategyChoice choose(const R& registry, const std::string& option, const std::string& name) {
  const auto* e = registry.find(name);
  if (!e) fail("--{}: expected one of {}, got '{}'", option, fmt::join(registry.names(), ", "), name);
  return {name, e->defaults()};
}

}  // namespace

std::string flag_of(std::string_view key) {
  if (key == "bv.width") return "--bv-width";
  if (key == "bv.end_boxes") return "--end-boxes";
  if (key == "narrow.mode") return "--narrow";
  if (key == "narrow.representative") return "--representative";
  std::string flag(key.substr(key.rfind('.') == std::string_view::npos ? 0 : key.rfind('.') + 1));
  std::replace(flag.begin(), flag.end(), '_', '-');
  return "--" + flag;
}

PipelineConfig pipeline_config(const PipelineFlags& o) {
  PipelineConfig c;
  c.k = o.k, c.width = o.width, c.threads = o.threads;
  c.end_boxes = kEndBoxModes.parse(o.end_boxes, "--end-boxes");
  c.memory_limit = o.memory_limit;
  c.memory_limit_bytes = parse_memory_size(o.memory_limit, "--memory-limit");
  c.candidate_limit = o.candidate_limit;
  c.time_limit = o.time_limit;
  c.narrow = {kNarrowModes.parse(o.narrow, "--narrow"), kRepresentativeRules.parse(o.representative, "--representative"), {}};
  c.hierarchy = choose(builder_registry(), "hierarchy", o.hierarchy);
  c.scheduler = choose(scheduler_registry(), "scheduler", o.scheduler);
  c.tester = parse_strategy_spec(o.tester, "--tester ", "tester", tester_registry(), kDefaultTester);
  return c;
}

int step_command(const StepOptions& o) {
  PipelineStrategies s = make_strategies(pipeline_config(o), builder_registry(), scheduler_registry(), tester_registry(), flag_of);
  const EndBoxMode end_boxes = s.end_boxes;

  MeshData m0 = read_mesh(o.mesh_t0);
  MeshData m1 = read_mesh(o.mesh_t1);
  if (m1.positions.size() != m0.positions.size())
    fail("{}: {} vertices, expected {} as in {}", o.mesh_t1, m1.positions.size(), m0.positions.size(), o.mesh_t0);
  if (m1.faces != m0.faces) fail("{}: faces differ from {} (the two frames must share one topology)", o.mesh_t1, o.mesh_t0);
  TriMesh mesh;
  try {
    mesh = TriMesh(m0.positions.size(), m0.faces);
  } catch (const Error& e) {
    fail("{}: {}", o.mesh_t0, e.what());
  }
  CcdPipeline pipeline(mesh, single_cloth_body(mesh), std::move(s));
  if (o.earliest && !o.contacts_csv.empty())
    fail("--contacts with --earliest: the earliest-time query skips pairs and has no full contact list; drop one");
  OutputFile contacts;  // opened before the step: an unwritable path is reported before the work
  if (!o.contacts_csv.empty()) contacts = OutputFile(o.contacts_csv, "--contacts");
  StepResult r;
  double earliest = 1.0;
  {
    StepProgressLine line(pipeline, o.progress);
    if (o.earliest) earliest = pipeline.earliest_toi(m0.positions, m1.positions, &r);
    else r = pipeline.step(m0.positions, m1.positions);
  }
  const std::uint64_t hash = contact_set_hash(r.contacts);

  if (!o.contacts_csv.empty()) {
    contacts << kContactColumns << "\n";
    for (const Contact& c : r.contacts) contacts << contact_row(c, m0.positions, m1.positions) << "\n";
    contacts.commit();
  }
  if (o.json) {
    nlohmann::json j = step_json(r);
    if (o.earliest) j["earliest_toi"] = earliest;
    else j["hash"] = fmt::format("{:016x}", hash);
    j["triangles"] = mesh.num_faces();
    j["vertices"] = mesh.num_vertices();
    j["orphans"] = {{"vf", pipeline.orphans().vf.size()}, {"ee", pipeline.orphans().ee.size()}};
    j["memory"]["estimate_mb"] =
        double(estimate_pipeline_bytes(mesh, o.k, o.width, pipeline.orphans().vf.size() + pipeline.orphans().ee.size(),
                                       pipeline.end_boxes_kept())) / (1 << 20);
    j["config"] = {{"k", o.k}, {"bv_width", o.width}, {"end_boxes", end_boxes_json(end_boxes)}, {"end_boxes_tested", pipeline.end_boxes_in_last_step()}, {"hierarchy", o.hierarchy}, {"scheduler", o.scheduler}, {"threads", o.threads}, {"tester", o.tester},
                   {"narrow", {{"mode", o.narrow}, {"representative", o.representative}}}, {"memory_limit", o.memory_limit}, {"candidate_limit", o.candidate_limit}, {"time_limit", o.time_limit},
                   {"simd_target", plane_filter_target()}};
    fmt::print("{}\n", j.dump(2));
  } else {
    fmt::print("ccdlab step {} -> {}: {} triangles, k={} width={} hierarchy={} scheduler={} tester={} narrow={}/{} ({})\n\n",
               o.mesh_t0, o.mesh_t1, mesh.num_faces(), o.k, o.width, o.hierarchy, o.scheduler, o.tester, o.narrow,
               o.representative, plane_filter_target());
    print_table_header(stdout);
    print_table_row(stdout, "0", r);
    if (o.earliest)
      fmt::print("\nearliest time of contact: {} ({} of the contacts found before the cut)\n", earliest,
                 r.counters.contacts_vf + r.counters.contacts_ee);
    else
      fmt::print("\ncontacts vf={} ee={}; hash {:016x}\n", r.counters.contacts_vf, r.counters.contacts_ee, hash);
  }
  return 0;
}

}  // namespace ccdlab::cli

// `ccdlab step T0 T1 [--k K] [--scheduler S] [--threads N] [--tester NAME[:key=value,…]] [--narrow MODE]
//  [--representative RULE] [--contacts FILE.csv] [--json] [--earliest]`:
// one CCD step between two mesh files of the same topology (one self-colliding body); with --earliest, only
// its earliest time of contact.


#include <CLI/CLI.hpp>

#include <algorithm>

#include "experiments/cli/commands.hpp"
#include "framework/util/simd_target.hpp"
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

SettingName flag_of() { return setting_name(SettingSpelling::flag); }

PipelineConfig pipeline_config(const PipelineFlags& f) {
  const Registries reg = builtin_registries();
  PipelineConfig c = default_config(reg);
  for (std::size_t i = 0; i < f.options.size(); ++i) {
    if (f.options[i].second->count() == 0) continue;
    const Setting& s = *f.options[i].first;
    const std::string name(s.flag_name());
    s.set(c, setting_value_of_text(s, f.texts[i], name), reg, name);
  }
  return c;
}

int step_command(const StepOptions& o) {
  const PipelineConfig c = pipeline_config(o);
  PipelineStrategies s = make_strategies(c, builder_registry(), scheduler_registry(), tester_registry(), flag_of());

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
        double(estimate_pipeline_bytes(mesh, c.k, c.width, pipeline.orphans().vf.size() + pipeline.orphans().ee.size(),
                                       pipeline.end_boxes_kept())) / (1 << 20);
    j["config"] = settings_json(c);
    j["config"]["end_boxes_tested"] = pipeline.end_boxes_in_last_step();
    j["config"]["simd_target"] = simd_target_name();
    fmt::print("{}\n", j.dump(2));
  } else {
    fmt::print("ccdlab step {} -> {}: {} triangles, k={} width={} hierarchy={} scheduler={} tester={} narrow={}/{} ({})\n\n",
               o.mesh_t0, o.mesh_t1, mesh.num_faces(), c.k, c.width, strategy_spec_text(c.hierarchy),
               strategy_spec_text(c.scheduler), strategy_spec_text(c.tester), to_string(c.narrow.mode),
               to_string(c.narrow.representative), simd_target_name());
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

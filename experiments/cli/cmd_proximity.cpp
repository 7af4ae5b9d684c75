// `ccdlab proximity MESH --dhat D [--relative] [--k K] [--scheduler S] [--threads N] … [--repeat N] [--check]
//  [--pairs OUT.csv] [--json]`: every vertex–face and edge–edge pair of one mesh file (one self-colliding body)
// closer than d̂, with its distance and closest-feature type (framework/pipeline/proximity/proximity_query.hpp).
#include <chrono>
#include <map>

#include "experiments/cli/commands.hpp"
#include "framework/util/simd_target.hpp"
#include "experiments/cli/report.hpp"
#include "experiments/cli/step_progress.hpp"
#include "framework/mesh/mesh_io.hpp"
#include "framework/pipeline/brute_force.hpp"
#include "framework/pipeline/proximity/proximity_query.hpp"
#include "framework/pipeline/proximity/sweep_proximity.hpp"
#include "framework/pipeline/work_estimate.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/config/strategy_spec.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::cli {

int proximity_command(const ProximityOptions& o) {
  if (o.repeat < 1) fail("--repeat {}: expected at least 1", o.repeat);
  if (!(o.dhat > 0) || !std::isfinite(o.dhat)) fail("--dhat {}: expected a finite distance > 0", o.dhat);
  PipelineConfig c = pipeline_config(o);
  c.normal_cones = false;
  PipelineStrategies s = make_strategies(c, builder_registry(), scheduler_registry(), tester_registry(), flag_of());
  const MeshData m = read_mesh(o.mesh);
  TriMesh mesh;
  try {
    mesh = TriMesh(m.positions.size(), m.faces);
  } catch (const Error& e) {
    fail("{}: {}", o.mesh, e.what());
  }
  const double diagonal = bounding_box_diagonal(m.positions);
  const double dhat = o.relative ? o.dhat * diagonal : o.dhat;
  if (!(dhat > 0)) fail("--dhat {} --relative: the mesh's bounding-box diagonal is {}", o.dhat, diagonal);
  OutputFile pairs;  // opened before the query: an unwritable path is reported before the work
  if (!o.pairs_csv.empty()) pairs = OutputFile(o.pairs_csv, "--pairs");

  ProximityQuery query(mesh, single_cloth_body(mesh), std::move(s), dhat);
  ProximityResult r;
  std::vector<double> refit_ms;
  double first_ms = 0;
  {
    StepProgressLine line(query.pipeline(), o.progress);
    for (int i = 0; i < o.repeat; ++i) {
      r = query.query(m.positions);
      (i == 0 ? first_ms : refit_ms.emplace_back()) = r.step.timings.total_ms;
      line.clear();
    }
  }
  // The reference, timed as the baseline: the same pairs or exit 1.
  std::uint64_t reference_hash = 0;
  double reference_ms = 0;
  if (o.check) {
    const auto start = std::chrono::steady_clock::now();
    reference_hash = contact_set_hash(sweep_proximity(mesh, CollisionRules(mesh, single_cloth_body(mesh)), m.positions, dhat));
    reference_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  const int rc = o.check && reference_hash != r.hash ? 1 : 0;
  std::size_t vf = 0;
  std::map<std::string_view, std::size_t> types;
  for (const ProximityPair& p : r.pairs) vf += p.kind == ContactKind::vf, ++types[to_string(p.type)];
  const std::size_t ee = r.pairs.size() - vf;

  if (pairs.is_open()) {
    pairs << "kind,a,b,c,d,distance,type,u,v\n";
    for (const ProximityPair& p : r.pairs)
      pairs << fmt::format("{},{},{},{},{},{:.17g},{},{:.17g},{:.17g}\n", to_string(p.kind), p.vertices[0], p.vertices[1],
                           p.vertices[2], p.vertices[3], p.distance, to_string(p.type), p.coords[0], p.coords[1]);
    pairs.commit();
  }
  if (o.json) {
    nlohmann::json j = step_json(r.step);
    j.erase("contacts");
    j["pairs"] = {{"vf", vf}, {"ee", ee}};
    j["types"] = nlohmann::json::object();
    for (const auto& [type, n] : types) j["types"][std::string(type)] = n;
    j["hash"] = fmt::format("{:016x}", r.hash);
    j["dhat"] = dhat;
    j["diagonal"] = diagonal;
    j["triangles"] = mesh.num_faces();
    j["vertices"] = mesh.num_vertices();
    j["decided_in_rationals"] = r.step.counters.tests_fallback;
    j["query_ms"] = {{"first", first_ms}, {"refit_median", refit_ms.empty() ? nlohmann::json() : nlohmann::json(median(refit_ms))}};
    if (o.check)
      j["reference"] = {{"hash", fmt::format("{:016x}", reference_hash)}, {"ms", reference_ms}, {"equal", rc == 0}};
    j["config"] = settings_json(c);
    j["config"].erase("tester");  // the query tests distances, not motion
    j["config"]["repeat"] = o.repeat;
    j["config"]["simd_target"] = simd_target_name();
    fmt::print("{}\n", j.dump(2));
    return rc;
  }
  fmt::print("ccdlab proximity {}: {} triangles, dhat {:g} ({:.3g} of the bounding-box diagonal), k={} width={} "
             "scheduler={} threads={}\n\n", o.mesh, mesh.num_faces(), dhat, dhat / diagonal, c.k, c.width,
             strategy_spec_text(c.scheduler), c.threads);
  fmt::print("pairs closer than dhat: vf={} ee={}; hash {:016x}\n", vf, ee, r.hash);
  std::string by_type;
  for (const auto& [type, n] : types) by_type += fmt::format(" {}={}", type, n);
  if (!by_type.empty()) fmt::print("by closest features:{}\n", by_type);
  fmt::print("{} candidate triangle pairs, {} pair tests ({} decided in rationals)\n", r.step.counters.candidate_pairs,
             r.step.counters.vf_tests + r.step.counters.ee_tests + r.step.counters.orphan_tests,
             r.step.counters.tests_fallback);
  fmt::print("ms: {:.2f} (hierarchy built){}\n", first_ms,
             refit_ms.empty() ? std::string() : fmt::format(", {:.2f} median of {} refit queries", median(refit_ms), refit_ms.size()));
  if (o.check)
    fmt::print("reference (a sweep over boxes, one thread): {:.2f} ms, hash {:016x}: {}\n", reference_ms, reference_hash,
               rc == 0 ? "the same pairs" : "DIFFERENT PAIRS");
  return rc;
}

}  // namespace ccdlab::cli

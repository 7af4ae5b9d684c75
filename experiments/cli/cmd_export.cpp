// `ccdlab export CONFIG.yaml [--set …] [--step N] [--levels L] [--out DIR] [--html FILE]`: VTK files of an experiment for
// ParaView and meshio (framework/export/): the mesh of every frame with per-triangle contact counts (mesh.pvd),
// and for one step — by default the one with the most contacts — the BVH levels as k-DOP polyhedra (bvh.pvd,
// one time value per depth), the BVTT front of every pass coloured by kept / sprouted / pruned, and the
// contacts at their time of contact. export.json lists the files with the resolved config and the revision.
//
// `--html OUT.html` writes the teaching page instead of (or besides) the VTK files: one self-contained file a
// browser opens from disk (framework/export/teaching_page.hpp, experiments/cli/export/teaching_data.hpp).
//
// The front is the `front` scheduler's (the config's scheduler is replaced by it for the export): every
// scheduler finds the same contacts, only `front` keeps a front to draw.
#include <filesystem>

#include "ccdlab/build_info.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/export/pass_fronts.hpp"
#include "experiments/cli/export/teaching_data.hpp"
#include "framework/export/ccd_pictures.hpp"
#include "framework/export/teaching_page.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/util/progress.hpp"
#include "strategies/registry.hpp"

namespace ccdlab::cli {

int export_command(const ExportOptions& o) {
  const Registries reg = builtin_registries();
  ExperimentConfig config = load_experiment(o.config, o.overrides, reg);
  if (config.scheduler.name != "front")
    config.scheduler = {"front", reg.schedulers.find("front")->defaults()};
  if (o.levels < 1 || o.levels > 64) fail("--levels: expected an integer from 1 to 64, got {}", o.levels);
  const MeshSequence scene = make_scene(config, reg);
  const int steps = scene.num_steps();
  if (o.step < -1 || o.step >= steps)
    fail("--step: expected a step from 0 to {} ({} has {} frames), got {}", steps - 1, config.source, steps + 1, o.step);
  if (o.out.empty() && o.html.empty()) fail("ccdlab export: give --out DIR (VTK files), --html FILE (the teaching page) or both");
  if (!o.html.empty()) {
    if (const auto parent = std::filesystem::path(o.html).parent_path(); !parent.empty())
      create_output_dir(parent.string(), "--html");
    Progress progress("ccdlab export --html", long(KdopKs::values.size()) * steps, o.progress);
    write_teaching_page(o.html, teaching_data(config, reg, scene, {o.levels, o.step}, progress), "--html");
    fmt::print("ccdlab export {} — {}, rev {}\nwrote {} ({:.1f} MB): open it in a browser, no server needed\n", config.name,
               scene.description(), build_info::git_revision, o.html, double(std::filesystem::file_size(o.html)) / 1e6);
    if (o.out.empty()) return 0;
  }
  const TriMesh& mesh = scene.topology();

  // Pass 1: every step, for the per-frame contact counts (and to find the busiest step).
  Progress progress("ccdlab export", 2L * steps, o.progress);
  std::vector<std::vector<int>> face_contacts(static_cast<std::size_t>(steps + 1));
  std::vector<std::size_t> contacts_per_step(static_cast<std::size_t>(steps));
  {
    CcdPipeline pipeline(mesh, scene.bodies(), make_strategies(config, reg));
    for (int s = 0; s < steps; ++s) {
      const StepResult r = pipeline.step(scene.frame(s), scene.frame(s + 1));
      face_contacts[std::size_t(s)] = contacts_per_face(mesh, r.contacts);
      contacts_per_step[std::size_t(s)] = r.contacts.size();
      progress.update(s + 1);
    }
  }
  int step = o.step;
  if (step < 0) step = int(std::max_element(contacts_per_step.begin(), contacts_per_step.end()) - contacts_per_step.begin());

  // Pass 2: up to the chosen step, keeping the front before it, then everything of that step.
  CcdPipeline pipeline(mesh, scene.bodies(), make_strategies(config, reg));
  Fronts before;
  StepResult detail;
  for (int s = 0; s <= step; ++s) {
    if (s == step && s > 0) before = fronts_of(pipeline);
    StepResult r = pipeline.step(scene.frame(s), scene.frame(s + 1));
    if (s == step) detail = std::move(r);
    progress.update(steps + s + 1);
  }
  const Fronts after = fronts_of(pipeline);

  namespace fs = std::filesystem;
  create_output_dir(o.out, "--out");
  for (const char* sub : {"mesh", "bvh"}) create_output_dir((fs::path(o.out) / sub).string(), "--out");
  auto path = [&](const std::string& name) { return (fs::path(o.out) / name).string(); };
  nlohmann::json files = nlohmann::json::array();

  std::vector<VtkSeriesEntry> frames;
  for (int f = 0; f <= steps; ++f) {
    const std::string name = fmt::format("mesh/frame_{:04d}.vtu", f);
    const Positions x = scene.frame(f);
    mesh_grid(mesh, scene.bodies(), x, f < steps ? scene.frame(f + 1) : x, face_contacts[std::size_t(f)])
        .write(path(name), "--out");
    frames.push_back({double(f), name});
  }
  write_vtk_series(path("mesh.pvd"), frames, "--out");
  files.push_back({{"file", "mesh.pvd"}, {"what", "the mesh per frame; cell arrays body, contacts (of the step from that frame); point array displacement"}});

  std::vector<VtkSeriesEntry> levels;
  int max_depth = 0;
  for (std::size_t b = 0; b < scene.bodies().size(); ++b) {
    const BvhTopology& bvh = pipeline.bvh(int(b));
    if (bvh.nodes.empty()) continue;
    const std::vector<int> depth = node_depths(bvh);
    const int deepest = *std::max_element(depth.begin(), depth.end());
    for (int d = 0; d < o.levels && d <= deepest; ++d) {
      const std::string name = fmt::format("bvh/body{}_depth{:02d}.vtu", b, d);
      bvh_level_grid(bvh, pipeline.node_bvs(int(b)), d, int(b)).write(path(name), "--out");
      levels.push_back({double(d), name});
      max_depth = std::max(max_depth, d);
    }
  }
  std::stable_sort(levels.begin(), levels.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  write_vtk_series(path("bvh.pvd"), levels, "--out");
  files.push_back({{"file", "bvh.pvd"}, {"what", fmt::format("k-DOP ({}-DOP) polyhedra of the BVH nodes by depth (time = depth 0..{}), swept over step {}; cell arrays node, depth, leaf, body", config.k, max_depth, step)}});

  nlohmann::json front_files = nlohmann::json::array();
  std::array<std::uint64_t, 3> changes{};
  for (std::size_t p = 0; p < pipeline.passes().size(); ++p) {
    const TraversalPass& pass = pipeline.passes()[p];
    const std::vector<FrontNode> none;
    const auto change = classify_front(*pass.side_a.bvh, *pass.side_b.bvh, before.empty() ? none : before[p], after[p]);
    for (FrontChange c : change) ++changes[std::size_t(c)];
    const std::string name = fmt::format("front_pass{}.vtu", p);
    front_grid(*pass.side_a.bvh, *pass.side_a.bvs, *pass.side_b.bvh, *pass.side_b.bvs,
               after[p], change)
        .write(path(name), "--out");
    front_files.push_back(name);
  }
  files.push_back({{"file", front_files}, {"what", fmt::format("the BVTT front after step {}, one file per pass (self passes first): a line between the centres of a node's two volumes (a point for a self node); cell arrays change (0 kept, 1 sprouted, 2 pruned), overlapping, depth_a, depth_b, self", step)}});

  const Positions x0 = scene.frame(step), x1 = scene.frame(step + 1);
  contacts_grid(detail.contacts, x0, x1).write(path("contacts.vtu"), "--out");
  files.push_back({{"file", "contacts.vtu"}, {"what", fmt::format("the {} contacts of step {} at their time of contact: a point (role 0) and the features (role 1: the face for VF, both edges for EE); cell arrays contact, kind (0 VF, 1 EE), toi, role", detail.contacts.size(), step)}});

  OutputFile index(path("export.json"), "--out");
  index << nlohmann::json{{"config", to_json(config)}, {"git_revision", build_info::git_revision},
                          {"scene", scene.description()}, {"triangles", mesh.num_faces()}, {"frames", steps + 1},
                          {"step", step}, {"contacts", detail.contacts.size()},
                          {"front", {{"kept", changes[0]}, {"sprouted", changes[1]}, {"pruned", changes[2]}}},
                          {"files", files}}
               .dump(2)
        << "\n";
  index.commit();
  fmt::print("ccdlab export {} — {}, rev {}\n", config.name, scene.description(), build_info::git_revision);
  fmt::print("step {} in detail: {} contacts, BVH depths 0..{} as {}-DOP polyhedra, front {} nodes ({} kept, {} sprouted, {} pruned)\n",
             step, detail.contacts.size(), max_depth, config.k, changes[0] + changes[1] + changes[2], changes[0],
             changes[1], changes[2]);
  fmt::print("wrote {}/: mesh.pvd ({} frames), bvh.pvd, {} front file(s), contacts.vtu, export.json\n", o.out, steps + 1,
             front_files.size());
  return 0;
}

}  // namespace ccdlab::cli

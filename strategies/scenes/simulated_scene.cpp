#include "strategies/scenes/simulated_scene.hpp"

#include <chrono>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "ccdlab/build_info.hpp"
#include "framework/mesh/mesh_io.hpp"
#include "framework/sim/quality.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/util/progress.hpp"
#include "strategies/registry.hpp"

namespace ccdlab {

std::string simulate_to_folder(const SimulateRequest& o, bool print) {
  namespace fs = std::filesystem;
  const SimScene scene = load_sim_scene(o.scene, o.overrides, effect_registry());
  const std::string hash = scene_hash(scene);
  const std::string out = o.out.empty() ? (fs::path("results/scenes") / (scene.name + "-" + hash)).string() : o.out;
  const fs::path meta_path = fs::path(out) / "meta.json";
  if (!o.force && fs::exists(meta_path)) {
    try {
      const nlohmann::json meta = nlohmann::json::parse(read_file(meta_path.string()));
      if (meta.value("scene_hash", "") == hash && meta.value("complete", false)) {
        if (print) fmt::print("ccdlab simulate {}: cached in {}/ (scene hash {}); --force simulates again\n", scene.name, out, hash);
        // The key is the scene, not the simulator: frames of another revision are reused — say so, every time.
        const std::string made_by = meta.value("git_revision", "?");
        if (made_by != build_info::git_revision)
          fmt::print(stderr, "ccdlab: warning: {}/ holds frames simulated by revision {}, not by this one ({}); "
                     "--force simulates them again\n", out, made_by, build_info::git_revision);
        return out;
      }
    } catch (const nlohmann::json::exception&) {
      // not ours or cut short: simulate again
    }
  }
  create_output_dir(out, "--out");
  remove_stale_output(meta_path.string(), "--out");

  const TriMesh mesh(Index(scene.mesh.positions.size()), scene.mesh.faces);
  Simulator sim = make_simulator(scene, mesh);
  QualityMeter quality(mesh, scene.setup.bodies, contact_strategies(18, "phc", scene.setup.threads, scene.setup.thickness),
                       scene.setup.thickness);

  if (print) {
    fmt::print("ccdlab simulate {} — {} triangles ({} vertices), {} frames of {:.4g} s × {} sub-steps, {} iterations, "
               "resolution {}, {} thread(s), rev {}\n", scene.name, mesh.num_faces(), mesh.num_vertices(), scene.frames,
               scene.options.frame_time, scene.options.substeps, scene.options.iterations, scene.resolution,
               scene.setup.threads, build_info::git_revision);
    std::string header = fmt::format("{:>6} {:>9}", "frame", "sim ms");
    for (const auto& e : sim.effects()) header += fmt::format(" {:>16}", std::string(e->name()) + " ms");
    fmt::print("{} {:>8} {:>8} {:>12}\n", header, "crossing", "close", "kinetic");
  }
  Progress progress("ccdlab simulate", scene.frames, o.progress && !print);
  nlohmann::json frames = nlohmann::json::array();
  std::vector<EffectCounters> before(sim.effects().size());
  for (int f = 0; f < scene.frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    if (f > 0) sim.advance_frame();
    const double sim_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const std::string file = fmt::format("frame_{:04d}.ply", f);
    write_ply((fs::path(out) / file).string(), sim.positions(), scene.mesh.faces);
    const FrameQuality q = quality.measure(sim.positions());
    nlohmann::json per_effect = nlohmann::json::object();
    std::string row = fmt::format("{:>6} {:>9.1f}", f, sim_ms);
    for (std::size_t e = 0; e < sim.effects().size(); ++e) {
      const EffectCounters& now = sim.counters()[e];
      const double ms = now.ms - before[e].ms;
      per_effect[fmt::format("{}:{}", e, sim.effects()[e]->name())] = {
          {"ms", ms}, {"calls", now.calls - before[e].calls}, {"work", now.work - before[e].work},
          {"work_is", sim.effects()[e]->work_name()}};
      row += fmt::format(" {:>16.1f}", ms);
      before[e] = now;
    }
    frames.push_back({{"frame", f}, {"file", file}, {"time_s", sim.time()}, {"sim_ms", sim_ms}, {"effects", per_effect},
                      {"intersecting_pairs", q.intersecting_pairs},
                      {"intersecting_obstacle_pairs", q.intersecting_obstacle_pairs}, {"close_pairs", q.close_pairs},
                      {"kinetic_energy", sim.kinetic_energy()}});
    if (print) fmt::print("{} {:>8} {:>8} {:>12.4g}\n", row, q.intersecting_pairs, q.close_pairs, sim.kinetic_energy());
    progress.update(f + 1);
  }
  nlohmann::json totals = nlohmann::json::object();
  for (std::size_t e = 0; e < sim.effects().size(); ++e)
    totals[fmt::format("{}:{}", e, sim.effects()[e]->name())] = {{"ms", sim.counters()[e].ms}, {"calls", sim.counters()[e].calls},
                                                                  {"work", sim.counters()[e].work},
                                                                  {"stats", sim.effects()[e]->stats()}};
  OutputFile meta(meta_path.string(), "--out");
  meta << nlohmann::json{{"scene", scene.name}, {"source", scene.source}, {"scene_hash", hash}, {"resolved", scene.resolved},
                         {"git_revision", build_info::git_revision}, {"triangles", mesh.num_faces()},
                         {"bodies", [&] {
                            nlohmann::json b = nlohmann::json::array();
                            for (const Body& body : scene.setup.bodies)
                              b.push_back({{"name", body.name}, {"kind", body.kind == BodyKind::cloth ? "cloth" : "obstacle"},
                                           {"self_collision", body.self_collision}, {"vertices", {body.vertex_begin, body.vertex_end}},
                                           {"faces", {body.face_begin, body.face_end}}});
                            return b;
                          }()},
                         {"effects_total", totals}, {"frames", frames}, {"complete", true}}
              .dump(1)
       << "\n";
  meta.commit();
  if (print) fmt::print("wrote {} frames and meta.json to {}/ (scene hash {})\n", scene.frames, out, hash);
  return out;
}


MeshSequence load_simulated_frames(const std::string& folder, int first_frame, int last_frame) {
  namespace fs = std::filesystem;
  const std::string meta_path = (fs::path(folder) / "meta.json").string();
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(read_file(meta_path));
  } catch (const nlohmann::json::exception& e) {
    fail("{}: not a simulated scene's metadata: {}", meta_path, e.what());
  }
  if (!meta.value("complete", false)) fail("{}: the simulation did not complete", meta_path);
  std::vector<std::string> files, labels;
  const auto& frames = meta.at("frames");
  const int last = last_frame > 0 ? last_frame : int(frames.size()) - 1;
  if (last >= int(frames.size()))
    fail("scene.last_frame: expected at most {} (the frames of {}), got {}", int(frames.size()) - 1, folder, last_frame);
  if (first_frame < 0 || first_frame + 1 > last)
    fail("scene.first_frame: expected 0 … {} (two frames at least for one step) for {}, got {}", last - 1, folder, first_frame);
  for (const auto& f : frames) {
    if (const int i = f.at("frame").get<int>(); i < first_frame || i > last) continue;
    files.push_back((fs::path(folder) / f.at("file").get<std::string>()).string());
    labels.push_back(std::to_string(f.at("frame").get<int>()));
  }
  const MeshData first = read_mesh(files.front());
  std::vector<Body> bodies;
  for (const auto& b : meta.at("bodies"))
    bodies.push_back({b.at("name"), b.at("kind") == "cloth" ? BodyKind::cloth : BodyKind::obstacle,
                      b.at("self_collision").get<bool>(), b.at("vertices")[0].get<Index>(), b.at("vertices")[1].get<Index>(),
                      b.at("faces")[0].get<Index>(), b.at("faces")[1].get<Index>()});
  TriMesh mesh(first.positions.size(), first.faces);
  auto source = [files](int i) { return read_mesh(files[std::size_t(i)]).positions; };
  return MeshSequence(std::move(mesh), std::move(bodies), std::move(labels), std::move(source),
                      fmt::format("simulated {}: {} triangles, {} frames ({})", meta.at("scene").get<std::string>(),
                                  first.faces.size(), files.size(), folder));
}

}  // namespace ccdlab

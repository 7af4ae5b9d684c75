#include "strategies/scenes/barrier_newton_scene.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include <ccdlab/barrier_solver.hpp>
#include <ccdlab/ccdlab.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "ccdlab/build_info.hpp"
#include "framework/mesh/mesh_io.hpp"
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"
#include "framework/util/progress.hpp"

namespace ccdlab {
namespace {

/// Bump when the solver or the scene changes what it records: cached recordings of another version are redone.
constexpr int kRecordingVersion = 2;

std::string params_key(const BarrierNewtonParams& p) {
  return fmt::format("v{} cells={} pleats={} frames={} iterations={} drop={} slide={} wrinkle={}", kRecordingVersion,
                     p.cells, p.pleats, p.frames, p.max_iterations, p.drop_speed, p.slide_speed, p.wrinkle);
}

std::string fnv_hex(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (const unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return fmt::format("{:016x}", h).substr(0, 12);
}

}  // namespace

std::string record_barrier_newton(const BarrierNewtonParams& p, bool progress) {
  namespace fs = std::filesystem;
  namespace bc = barrier;
  const std::string key = params_key(p), hash = fnv_hex(key);
  const std::string out = p.dir.empty() ? (fs::path("results/scenes") / ("barrier_newton-" + hash)).string() : p.dir;
  const fs::path meta_path = fs::path(out) / "meta.json";
  if (fs::exists(meta_path)) {
    try {
      const nlohmann::json meta = nlohmann::json::parse(read_file(meta_path.string()));
      if (meta.value("scene_hash", "") == hash && meta.value("complete", false)) return out;
    } catch (const nlohmann::json::exception&) {
      // not ours or cut short: record again
    }
  }
  create_output_dir(out, "scene.dir");
  remove_stale_output(meta_path.string(), "scene.dir");

  // The sheet: side 1, layers one cell apart (waving by `wrinkle` of that); the barrier acts below 0.8 of that, the separation is a tenth of it.
  const double cell = 1.0 / (p.cells - 1), gap = cell, radius = 0.25;
  bc::ClothScene scene = bc::make_sheet_over_sphere(p.cells, radius + gap, radius, 16, 32, p.pleats, gap, p.wrinkle * gap);
  const int sphere_vertices = int(scene.x.size()) - scene.cloth_vertices - 4;
  const std::vector<Detector::Body> bodies{{scene.cloth, scene.cloth_vertices, false, true, "cloth"},
                                           {scene.sphere, sphere_vertices, true, false, "sphere"},
                                           {scene.floor, 4, true, false, "floor"}};
  Options options;
  options.threads = 2;
  Detector detector(bodies, options);
  bc::Solver<Detector> solver{scene, detector};
  solver.mass = 0.2 / scene.cloth_vertices;
  solver.dhat = 0.8 * gap;
  solver.separation = 0.1 * solver.dhat;
  solver.max_iterations = p.max_iterations;

  std::vector<Face> faces;  // the bodies' faces in one vertex numbering
  for (const auto& t : scene.cloth) faces.push_back({t[0], t[1], t[2]});
  for (const auto& t : scene.sphere)
    faces.push_back({t[0] + scene.cloth_vertices, t[1] + scene.cloth_vertices, t[2] + scene.cloth_vertices});
  const int floor_at = scene.cloth_vertices + sphere_vertices;
  for (const auto& t : scene.floor) faces.push_back({t[0] + floor_at, t[1] + floor_at, t[2] + floor_at});
  const auto positions = [](const std::vector<bc::Point>& x) {
    Positions out(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) out[i] = Vec3(x[i][0], x[i][1], x[i][2]);
    return out;
  };
  nlohmann::json frames = nlohmann::json::array();
  int frame = 0, query = 0;
  solver.on_newton_step = [&](const std::vector<bc::Point>& x, const std::vector<bc::Point>& target) {
    for (const auto* y : {&x, &target}) {
      const std::string file = fmt::format("frame_{:04d}.ply", int(frames.size()));
      write_ply((fs::path(out) / file).string(), positions(*y), faces);
      frames.push_back({{"frame", int(frames.size())}, {"file", file}, {"solver_frame", frame}, {"query", query},
                        {"role", y == &x ? "x" : "x + dx"}});
    }
    ++query;
  };
  std::vector<bc::Point> x = scene.x;
  // The lowest layer starts at rest just above the sphere, each one above it faster (the top one at drop_speed):
  // the stack closes onto itself, and the Newton steps carry upper layers through the ones below. The layers also
  // slide along the folds, each against its neighbours (slide_speed, alternating in sign), as folded cloth does.
  std::vector<bc::Vec3> v(scene.cloth_vertices, bc::Vec3::Zero());
  const int per_layer = std::max(1, (p.cells + p.pleats - 1) / p.pleats);
  for (int i = 0; i < scene.cloth_vertices; ++i) {
    const int layer = (i % p.cells) / per_layer;
    const double height = double(layer) / double(std::max(1, p.pleats - 1));
    v[i] = bc::Vec3(0, (layer % 2 == 0 ? 1 : -1) * p.slide_speed, -p.drop_speed * height);
  }
  Progress bar("ccdlab: recording barrier_newton's queries (once)", p.frames, progress);
  const auto started = std::chrono::steady_clock::now();
  nlohmann::json per_frame = nlohmann::json::array();
  for (frame = 0; frame < p.frames; ++frame) {
    const auto r = solver.step(x, v);
    per_frame.push_back({{"frame", frame}, {"iterations", r.iterations}, {"barrier_pairs", r.active}});
    bar.update(frame + 1);
  }
  if (frames.size() < 2) fail("scene barrier_newton: the solver asked no CCD query in {} frames", p.frames);
  const Index cloth_faces = Index(scene.cloth.size()), all_faces = Index(faces.size());
  OutputFile meta(meta_path.string(), "scene.dir");
  meta << nlohmann::json{{"scene", "barrier_newton"}, {"source", key}, {"scene_hash", hash},
                         {"git_revision", build_info::git_revision}, {"triangles", all_faces},
                         {"dhat", solver.dhat}, {"separation", solver.separation},
                         {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()},
                         {"solver_frames", per_frame},
                         {"bodies",
                          {{{"name", "cloth"}, {"kind", "cloth"}, {"self_collision", true}, {"vertices", {0, scene.cloth_vertices}}, {"faces", {0, cloth_faces}}},
                           {{"name", "sphere"}, {"kind", "obstacle"}, {"self_collision", false}, {"vertices", {scene.cloth_vertices, floor_at}},
                            {"faces", {cloth_faces, cloth_faces + Index(scene.sphere.size())}}},
                           {{"name", "floor"}, {"kind", "obstacle"}, {"self_collision", false}, {"vertices", {floor_at, floor_at + 4}},
                            {"faces", {cloth_faces + Index(scene.sphere.size()), all_faces}}}}},
                         {"frames", frames}, {"complete", true}}
              .dump(1)
       << "\n";
  meta.commit();
  return out;
}

}  // namespace ccdlab

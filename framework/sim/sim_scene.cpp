#include "framework/sim/sim_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <memory>

#include "framework/config/yaml_reader.hpp"
#include "framework/mesh/shapes.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {
namespace fs = std::filesystem;
namespace {

Vec3 vec3(const YamlReader& r, const YAML::Node& node, const std::string& path) {
  if (!node.IsSequence() || node.size() != 3) r.error(node, path, "a list of 3 numbers [x, y, z]");
  return Vec3(r.real(node[0], path + "[0]", -1e9, 1e9), r.real(node[1], path + "[1]", -1e9, 1e9),
              r.real(node[2], path + "[2]", -1e9, 1e9));
}

double real_or(const YamlReader& r, const YAML::Node& map, const char* key, const std::string& path, double fallback,
               double lo, double hi) {
  return map[key] ? r.real(map[key], path + "." + key, lo, hi) : fallback;
}

Vec3 vec3_or(const YamlReader& r, const YAML::Node& map, const char* key, const std::string& path, Vec3 fallback) {
  return map[key] ? vec3(r, map[key], path + "." + key) : fallback;
}

/// Cells scaled by √resolution (so triangles scale with resolution), at least 2.
int scaled(double cells, double resolution) { return std::max(2, int(std::lround(cells * std::sqrt(resolution)))); }

RigidMotion read_motion(const YamlReader& r, const YAML::Node& node, const std::string& path, const Vec3& pivot) {
  r.require_map(node, path);
  r.check_keys(node, path, {"velocity", "move_start", "move_end", "pivot", "axis", "spin_rate", "spin_start", "keyframes"});
  RigidMotion m;
  m.velocity = vec3_or(r, node, "velocity", path, Vec3::Zero());
  m.move_start = real_or(r, node, "move_start", path, 0, 0, 1e9);
  m.move_end = real_or(r, node, "move_end", path, 1e300, 0, 1e300);
  m.pivot = vec3_or(r, node, "pivot", path, pivot);
  m.axis = vec3_or(r, node, "axis", path, Vec3::UnitY());
  if (m.axis.norm() == 0) r.error(node["axis"], path + ".axis", "a non-zero axis");
  m.spin_rate = real_or(r, node, "spin_rate", path, 0, -1e6, 1e6);
  m.spin_start = real_or(r, node, "spin_start", path, 0, 0, 1e9);
  if (node["keyframes"]) {
    const YAML::Node& ks = node["keyframes"];
    if (!ks.IsSequence()) r.error(ks, path + ".keyframes", "a list of {time, offset, angle_deg}");
    for (std::size_t i = 0; i < ks.size(); ++i) {
      const std::string kp = fmt::format("{}.keyframes[{}]", path, i);
      r.require_map(ks[i], kp);
      r.check_keys(ks[i], kp, {"time", "offset", "angle_deg"});
      RigidKeyframe k;
      k.time = real_or(r, ks[i], "time", kp, 0, 0, 1e9);
      k.offset = vec3_or(r, ks[i], "offset", kp, Vec3::Zero());
      k.angle = real_or(r, ks[i], "angle_deg", kp, 0, -1e6, 1e6) * M_PI / 180;
      if (!m.keyframes.empty() && k.time <= m.keyframes.back().time) r.error(ks[i]["time"], kp + ".time", "times in increasing order");
      m.keyframes.push_back(k);
    }
  }
  return m;
}

/// A motion's own keys, resolved (the scene hash covers them).
nlohmann::json motion_json(const RigidMotion& m) {
  auto v = [](const Vec3& x) { return std::array<double, 3>{x.x(), x.y(), x.z()}; };
  nlohmann::json keys = nlohmann::json::array();
  for (const RigidKeyframe& k : m.keyframes) keys.push_back({{"time", k.time}, {"offset", v(k.offset)}, {"angle", k.angle}});
  return {{"velocity", v(m.velocity)}, {"move_start", m.move_start}, {"move_end", m.move_end}, {"pivot", v(m.pivot)},
          {"axis", v(m.axis)},         {"spin_rate", m.spin_rate},   {"spin_start", m.spin_start}, {"keyframes", keys}};
}

/// Appends one body's mesh; returns its resolved keys.
nlohmann::json read_shape(const YamlReader& r, const YAML::Node& node, const std::string& path, bool cloth,
                          double resolution, const std::string& dir, MeshData& mesh, SimObstacle& ob) {
  const std::string shape = node["shape"] ? r.string(node["shape"], path + ".shape") : "";
  nlohmann::json j = {{"shape", shape}};
  if (shape == "sheet") {
    r.check_keys(node, path, {"name", "shape", "size", "cells", "centre", "self_collision"});
    if (!node["size"] || !node["cells"]) fail("{}: sheet needs size: [x, z] and cells: [nx, nz]", r.where(node, path));
    const YAML::Node &size = node["size"], &cells = node["cells"];
    if (!size.IsSequence() || size.size() != 2) r.error(size, path + ".size", "[x, z]");
    if (!cells.IsSequence() || cells.size() != 2) r.error(cells, path + ".cells", "[nx, nz] at resolution 1");
    const double sx = r.real(size[0], path + ".size[0]", 1e-6, 1e6), sz = r.real(size[1], path + ".size[1]", 1e-6, 1e6);
    const int nx = scaled(double(r.integer(cells[0], path + ".cells[0]", 1, 100000)), resolution);
    const int nz = scaled(double(r.integer(cells[1], path + ".cells[1]", 1, 100000)), resolution);
    const Vec3 c = vec3_or(r, node, "centre", path, Vec3::Zero());
    append_sheet(mesh, c, sx, sz, nx, nz);
    j.update({{"size", {sx, sz}}, {"cells_scaled", {nx, nz}}, {"centre", {c.x(), c.y(), c.z()}}});
  } else if (shape == "frustum") {
    r.check_keys(node, path, {"name", "shape", "centre", "r_top", "r_bottom", "height", "segments", "rows", "self_collision", "motion", "parent"});
    const Vec3 c = vec3_or(r, node, "centre", path, Vec3::Zero());
    const double rt = real_or(r, node, "r_top", path, 1, 1e-6, 1e6), rb = real_or(r, node, "r_bottom", path, 1, 1e-6, 1e6);
    const double h = real_or(r, node, "height", path, 1, 1e-6, 1e6);
    int segments = node["segments"] ? int(r.integer(node["segments"], path + ".segments", 3, 100000)) : 32;
    int rows = node["rows"] ? int(r.integer(node["rows"], path + ".rows", 1, 100000)) : 8;
    if (cloth) segments = scaled(segments, resolution), rows = scaled(rows, resolution);
    append_frustum(mesh, c, rt, rb, h, segments, rows);
    j.update({{"centre", {c.x(), c.y(), c.z()}}, {"r_top", rt}, {"r_bottom", rb}, {"height", h}, {"segments", segments}, {"rows", rows}});
  } else if (!cloth && shape == "sphere") {
    r.check_keys(node, path, {"name", "shape", "centre", "radius", "segments", "motion", "parent"});
    ob.shape = SimObstacle::Shape::sphere;
    ob.a = vec3_or(r, node, "centre", path, Vec3::Zero());
    ob.radius = real_or(r, node, "radius", path, 0.5, 1e-6, 1e6);
    const int segments = node["segments"] ? int(r.integer(node["segments"], path + ".segments", 4, 4096)) : 20;
    append_sphere(mesh, ob.a, ob.radius, segments);
    j.update({{"centre", {ob.a.x(), ob.a.y(), ob.a.z()}}, {"radius", ob.radius}, {"segments", segments}});
  } else if (!cloth && shape == "capsule") {
    r.check_keys(node, path, {"name", "shape", "a", "b", "radius", "segments", "motion", "parent"});
    ob.shape = SimObstacle::Shape::capsule;
    ob.a = vec3_or(r, node, "a", path, Vec3::Zero());
    ob.b = vec3_or(r, node, "b", path, Vec3::UnitY());
    ob.radius = real_or(r, node, "radius", path, 0.2, 1e-6, 1e6);
    const int segments = node["segments"] ? int(r.integer(node["segments"], path + ".segments", 4, 4096)) : 16;
    append_capsule(mesh, ob.a, ob.b, ob.radius, segments);
    j.update({{"a", {ob.a.x(), ob.a.y(), ob.a.z()}}, {"b", {ob.b.x(), ob.b.y(), ob.b.z()}}, {"radius", ob.radius}, {"segments", segments}});
  } else if (!cloth && shape == "mesh") {
    r.check_keys(node, path, {"name", "shape", "file", "motion", "parent"});
    if (!node["file"]) fail("{}: a mesh obstacle needs file: PATH (OBJ or PLY)", r.where(node, path));
    std::string file = r.string(node["file"], path + ".file");
    if (fs::path(file).is_relative() && !r.from_command_line(path + ".file")) file = (fs::path(dir) / file).string();
    const MeshData m = read_mesh(file);
    const Index base = Index(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), m.positions.begin(), m.positions.end());
    for (Face f : m.faces) mesh.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
    j["file"] = file;
  } else {
    r.error(node["shape"] ? node["shape"] : node, path + ".shape",
            cloth ? "one of sheet, frustum" : "one of sphere, capsule, frustum, mesh");
  }
  return j;
}

SimScene load_checked(const std::string& path, const std::vector<std::string>& overrides, const EffectRegistry& effects) {
  YAML::Node root = load_yaml_file(path);
  if (!root.IsMap()) fail("{}:{}: expected a mapping of scene keys (name, frames, cloth, effects …)", path, root.Mark().line + 1);
  std::set<std::string> overridden;
  for (const auto& o : overrides) overridden.insert(apply_override(root, o));
  YamlReader r(path, overridden);
  r.check_keys(root, "", {"name", "frames", "resolution", "threads", "seed", "frame_time", "substeps", "iterations",
                          "thickness", "cloth", "obstacles", "effects"});
  SimScene s;
  s.source = path;
  s.name = root["name"] ? r.string(root["name"], "name") : fs::path(path).stem().string();
  for (const char* key : {"frames", "resolution", "threads", "cloth", "effects"})
    if (!root[key]) fail("{}: {}: required key missing (every scene has frames, resolution, threads, cloth and effects)", path, key);
  s.frames = int(r.integer(root["frames"], "frames", 1, 1000000));
  s.resolution = r.real(root["resolution"], "resolution", 1e-4, 100);
  s.setup.threads = int(r.integer(root["threads"], "threads", 1, 1024));
  s.setup.seed = root["seed"] ? std::uint64_t(r.integer(root["seed"], "seed", 0, 1e15)) : 1;
  s.options.frame_time = real_or(r, root, "frame_time", "", 1.0 / 30, 1e-6, 10);
  s.options.substeps = root["substeps"] ? int(r.integer(root["substeps"], "substeps", 1, 10000)) : 4;
  s.options.iterations = root["iterations"] ? int(r.integer(root["iterations"], "iterations", 1, 10000)) : 8;
  s.setup.thickness = real_or(r, root, "thickness", "", 0.005, 0, 10);
  const std::string dir = fs::path(path).parent_path().string();

  nlohmann::json pieces = nlohmann::json::array(), obstacles = nlohmann::json::array();
  auto add_body = [&](const std::string& name, BodyKind kind, bool self, Index v0, Index f0) {
    s.setup.bodies.push_back({name, kind, self, v0, Index(s.mesh.positions.size()), f0, Index(s.mesh.faces.size())});
  };
  const YAML::Node& cloth = root["cloth"];
  if (!cloth.IsSequence() || cloth.size() == 0) r.error(cloth, "cloth", "a list of cloth pieces ({name, shape: sheet, …})");
  for (std::size_t i = 0; i < cloth.size(); ++i) {
    const std::string p = fmt::format("cloth[{}]", i);
    r.require_map(cloth[i], p);
    const Index v0 = Index(s.mesh.positions.size()), f0 = Index(s.mesh.faces.size());
    SimObstacle unused;
    nlohmann::json j = read_shape(r, cloth[i], p, true, s.resolution, dir, s.mesh, unused);
    const std::string name = cloth[i]["name"] ? r.string(cloth[i]["name"], p + ".name") : fmt::format("cloth{}", i);
    const bool self = cloth[i]["self_collision"] ? r.boolean(cloth[i]["self_collision"], p + ".self_collision") : true;
    add_body(name, BodyKind::cloth, self, v0, f0);
    j.update({{"name", name}, {"self_collision", self}});
    pieces.push_back(j);
  }
  if (root["obstacles"]) {
    const YAML::Node& obs = root["obstacles"];
    if (!obs.IsSequence()) r.error(obs, "obstacles", "a list of obstacles ({name, shape: sphere, …})");
    for (std::size_t i = 0; i < obs.size(); ++i) {
      const std::string p = fmt::format("obstacles[{}]", i);
      r.require_map(obs[i], p);
      const Index v0 = Index(s.mesh.positions.size()), f0 = Index(s.mesh.faces.size());
      SimObstacle ob;
      nlohmann::json j = read_shape(r, obs[i], p, false, s.resolution, dir, s.mesh, ob);
      ob.name = obs[i]["name"] ? r.string(obs[i]["name"], p + ".name") : fmt::format("obstacle{}", i);
      ob.body = int(s.setup.bodies.size());
      const Vec3 pivot = ob.shape == SimObstacle::Shape::capsule ? Vec3((ob.a + ob.b) / 2) : ob.a;
      if (obs[i]["motion"]) ob.motion = read_motion(r, obs[i]["motion"], p + ".motion", pivot);
      std::string parent;
      if (obs[i]["parent"]) {  // a chain: this obstacle's motion happens in its parent's moving frame
        parent = r.string(obs[i]["parent"], p + ".parent");
        const auto earlier = std::find_if(s.setup.obstacles.begin(), s.setup.obstacles.end(),
                                          [&](const SimObstacle& o) { return o.name == parent; });
        if (earlier == s.setup.obstacles.end()) r.error(obs[i]["parent"], p + ".parent", "the name of an obstacle listed before this one");
        ob.motion.parent = std::make_shared<const RigidMotion>(earlier->motion);
      }
      add_body(ob.name, BodyKind::obstacle, false, v0, f0);
      j.update({{"name", ob.name}, {"moves", ob.motion.moves()}, {"parent", parent}});
      if (obs[i]["motion"]) j["motion"] = motion_json(ob.motion);  // in the hash: a changed motion is a new scene
      s.setup.obstacles.push_back(ob);
      obstacles.push_back(j);
    }
  }
  const YAML::Node& effs = root["effects"];
  if (!effs.IsSequence()) r.error(effs, "effects", "a list of effects ({name: gravity}, {name: stretch, compliance: …})");
  nlohmann::json effect_json = nlohmann::json::array();
  for (std::size_t i = 0; i < effs.size(); ++i) {
    const std::string p = fmt::format("effects[{}]", i);
    s.effects.push_back(r.strategy(effs[i], p, effects, ""));
    nlohmann::json j = {{"name", s.effects.back().name}};
    for (const auto& [key, v] : s.effects.back().params.all()) {
      const std::string& k = key;  // a structured binding cannot be captured by clang 14
      std::visit([&](const auto& x) { j[k] = x; }, v);
    }
    effect_json.push_back(j);
  }
  s.setup.rest = s.mesh.positions;
  s.setup.follows.assign(s.mesh.positions.size(), -1);
  for (std::size_t o = 0; o < s.setup.obstacles.size(); ++o) {
    const Body& b = s.setup.bodies[std::size_t(s.setup.obstacles[o].body)];
    std::fill(s.setup.follows.begin() + b.vertex_begin, s.setup.follows.begin() + b.vertex_end, int(o));
  }
  s.setup.inv_mass.assign(s.mesh.positions.size(), 0.0);
  for (const Body& b : s.setup.bodies)
    if (b.kind == BodyKind::cloth)
      for (Index v = b.vertex_begin; v < b.vertex_end; ++v) s.setup.inv_mass[std::size_t(v)] = 1.0;
  s.resolved = {{"name", s.name}, {"frames", s.frames}, {"resolution", s.resolution}, {"threads", s.setup.threads},
                {"seed", s.setup.seed}, {"frame_time", s.options.frame_time}, {"substeps", s.options.substeps},
                {"iterations", s.options.iterations}, {"thickness", s.setup.thickness}, {"cloth", pieces},
                {"obstacles", obstacles}, {"effects", effect_json},
                {"triangles", s.mesh.faces.size()}, {"vertices", s.mesh.positions.size()}};
  return s;
}

}  // namespace

SimScene load_sim_scene(const std::string& path, const std::vector<std::string>& overrides, const EffectRegistry& effects) {
  try {
    return load_checked(path, overrides, effects);
  } catch (const YAML::Exception& e) {
    fail("{}:{}: {}", path, e.mark.line + 1, e.msg);
  }
}

std::string scene_hash(const SimScene& scene) {
  nlohmann::json j = scene.resolved;
  j.erase("threads");  // frames do not depend on the thread count (tested), so neither does the cache key
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : j.dump()) h = (h ^ c) * 1099511628211ull;
  return fmt::format("{:016x}", h);
}

}  // namespace ccdlab

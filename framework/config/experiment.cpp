#include "framework/config/experiment.hpp"

#include <filesystem>

#include <yaml-cpp/yaml.h>

#include "framework/config/settings.hpp"
#include "framework/config/strategy_spec.hpp"
#include "framework/config/yaml_reader.hpp"
#include "framework/geometry/kdop.hpp"
#include "framework/hierarchy/wide_bvh.hpp"
#include "framework/pipeline/memory_budget.hpp"
#include "framework/util/memory.hpp"
#include "framework/util/parallel.hpp"

namespace ccdlab {
namespace {

namespace fs = std::filesystem;

/// A path from the config file is relative to the file's folder; one from --set to the working directory.
std::string resolve_path(const std::string& p, const std::string& config_path, bool from_command_line) {
  fs::path path(p);
  if (path.is_absolute() || from_command_line) return path.lexically_normal().string();
  return (fs::path(config_path).parent_path() / path).lexically_normal().string();
}

/// The frame files of `node` (keys frames, first, last; `where` is its key path): a list, a pattern with
/// first..last, or (when `one_allowed`, a body that does not move) a single file.
std::vector<std::string> read_frame_files(const YamlReader& r, const YAML::Node& node, const std::string& where,
                                          const std::string& config_path, bool one_allowed) {
  const YAML::Node frames = node["frames"];
  if (!frames) r.error(node, where, "a map with 'frames' (a list of files, or a pattern with first and last)");
  const bool cli = r.from_command_line(where + ".frames");
  std::vector<std::string> files;
  if (frames.IsSequence()) {
    if (node["first"] || node["last"]) r.error(node, where, "'first'/'last' only with a frame pattern");
    for (std::size_t i = 0; i < frames.size(); ++i)
      files.push_back(resolve_path(r.string(frames[i], fmt::format("{}.frames[{}]", where, i)), config_path, cli));
  } else if (one_allowed && !node["first"] && !node["last"] &&
             r.string(frames, where + ".frames").find('%') == std::string::npos) {
    files.push_back(resolve_path(r.string(frames, where + ".frames"), config_path, cli));
  } else {
    std::string pattern = resolve_path(r.string(frames, where + ".frames"), config_path, cli);
    if (!node["first"] || !node["last"]) r.error(node, where, "keys 'first' and 'last' with a frame pattern");
    int first = int(r.integer(node["first"], where + ".first", 0, 1e9));
    int last = int(r.integer(node["last"], where + ".last", 0, 1e9));
    if (last <= first) r.error(node["last"], where + ".last", fmt::format("an integer > first ({})", first));
    files = expand_frame_pattern(pattern, first, last);
  }
  if (files.size() < (one_allowed ? 1u : 2u))
    r.error(frames, where + ".frames", one_allowed ? "at least 1 frame" : "at least 2 frames");
  return files;
}

SceneConfig read_scene(const YamlReader& r, const YAML::Node& node, const std::string& config_path,
                       const Registries& reg) {
  SceneConfig scene;
  r.require_map(node, "scene");
  const int kinds = int(bool(node["builtin"])) + int(bool(node["frames"])) + int(bool(node["bodies"]));
  if (kinds > 1)
    r.error(node, "scene", "one of 'builtin' (a generated scene), 'frames' (mesh files) or 'bodies' (several bodies)");
  if (node["frames"]) {
    scene.builtin = false;
    r.check_keys(node, "scene", {"frames", "first", "last", "self_collision"});
    scene.files = read_frame_files(r, node, "scene", config_path, false);
    if (node["self_collision"]) scene.self_collision = r.boolean(node["self_collision"], "scene.self_collision");
    return scene;
  }
  if (const YAML::Node bodies = node["bodies"]) {
    scene.builtin = false;
    r.check_keys(node, "scene", {"bodies"});
    if (!bodies.IsSequence() || bodies.size() == 0)
      r.error(bodies, "scene.bodies", "a list of bodies ({name, frames, self_collision, kinematic})");
    std::size_t frames = 1;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const std::string where = fmt::format("scene.bodies[{}]", i);
      const YAML::Node b = bodies[i];
      r.require_map(b, where);
      r.check_keys(b, where, {"name", "frames", "first", "last", "self_collision", "kinematic"});
      BodyFiles body;
      body.name = b["name"] ? r.string(b["name"], where + ".name") : fmt::format("body{}", i);
      body.files = read_frame_files(r, b, where, config_path, true);
      if (b["self_collision"]) body.self_collision = r.boolean(b["self_collision"], where + ".self_collision");
      if (b["kinematic"]) body.kinematic = r.boolean(b["kinematic"], where + ".kinematic");
      if (body.kinematic && b["self_collision"] && body.self_collision)
        r.error(b["self_collision"], where + ".self_collision", "false or absent for a kinematic body (obstacles never self-collide)");
      if (body.files.size() > 1) {
        if (frames > 1 && body.files.size() != frames)
          r.error(b["frames"], where + ".frames",
                  fmt::format("{} frames like the bodies before it (one file per frame), or one file (a still body)", frames));
        frames = body.files.size();
      }
      scene.bodies.push_back(std::move(body));
    }
    if (frames < 2) r.error(bodies, "scene.bodies", "at least one body with 2 or more frames");
    return scene;
  }
  if (!node["builtin"]) r.error(node, "scene", "a map with 'builtin: NAME', 'frames: PATTERN' or 'bodies: […]'");
  // Built-in scene: its parameters sit beside 'builtin' in the same map.
  const std::string generator = r.string(node["builtin"], "scene.builtin");
  if (const auto* entry = reg.scenes.find(generator)) {
    std::vector<std::string> allowed{"builtin"};
    for (const auto& p : entry->params) allowed.push_back(p.name);
    r.check_keys(node, "scene", allowed);
  }
  YAML::Node as_strategy(YAML::NodeType::Map);
  for (const auto& kv : node) as_strategy[kv.first.as<std::string>() == "builtin" ? "name" : kv.first.as<std::string>()] = kv.second;
  try {
    scene.generator = r.strategy(as_strategy, "scene", reg.scenes, generator);
  } catch (const Error& e) {
    // Name the key as the user wrote it.
    std::string msg = e.what();
    if (auto pos = msg.find("scene.name"); pos != std::string::npos) msg.replace(pos, 10, "scene.builtin");
    throw Error(msg);
  }
  return scene;
}

void emit(YAML::Emitter& out, const nlohmann::json& j) {
  if (j.is_object()) {
    out << YAML::BeginMap;
    for (const auto& [k, v] : j.items()) {
      out << YAML::Key << k << YAML::Value;
      emit(out, v);
    }
    out << YAML::EndMap;
  } else if (j.is_array()) {
    out << YAML::BeginSeq;
    for (const auto& v : j) emit(out, v);
    out << YAML::EndSeq;
  } else if (j.is_string()) {
    out << j.get<std::string>();
  } else if (j.is_boolean()) {
    out << j.get<bool>();
  } else if (j.is_number_integer()) {
    out << j.get<long long>();
  } else if (j.is_number()) {
    out << fmt::format("{}", j.get<double>());
  } else {
    out << YAML::Null;
  }
}

}  // namespace

namespace {
ExperimentConfig load_experiment_checked(const std::string& path, const std::vector<std::string>& overrides,
                                         const Registries& reg, bool sweep_allowed);
}  // namespace

ExperimentConfig load_experiment(const std::string& path, const std::vector<std::string>& overrides,
                                 const Registries& reg, bool sweep_allowed) {
  try {
    return load_experiment_checked(path, overrides, reg, sweep_allowed);
  } catch (const YAML::Exception& e) {
    // Whatever yaml-cpp still refuses (a node of an unexpected kind deep inside) is the file's fault, located.
    fail("{}:{}: {}", path, e.mark.line + 1, e.msg);
  }
}

namespace {
ExperimentConfig load_experiment_checked(const std::string& path, const std::vector<std::string>& overrides,
                                         const Registries& reg, bool sweep_allowed) {
  YAML::Node root = load_yaml_file(path);
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap())
    fail("{}:{}: expected a mapping of config keys (name: …, scene: …), got {}", path, root.Mark().line + 1,
         root.IsSequence() ? "a list" : "a single value");
  if (root["sweep"]) {
    if (!sweep_allowed)
      for (const auto& kv : root)
        if (kv.first.Scalar() == "sweep")
          fail("{}:{}: sweep: this file describes a sweep of runs; run it with `ccdlab sweep {}`", path,
               kv.first.Mark().line + 1, path);
    root.remove("sweep");  // read by framework/config/sweep.cpp; every run is this config plus its overrides
  }
  std::set<std::string> overridden;
  for (const auto& o : overrides)
    if (!overridden.insert(apply_override(root, o)).second)
      fail("--set {}: {} is set twice; give each key once", o, o.substr(0, o.find('=')));
  YamlReader r(path, overridden);
  std::vector<std::string> keys{"name", "scene"};
  for (const std::string& k : setting_roots()) keys.push_back(k);
  keys.insert(keys.end(), {"replay", "output"});
  r.check_keys(root, "", keys);

  ExperimentConfig c;
  static_cast<PipelineConfig&>(c) = default_config(reg);
  c.source = path;
  c.name = root["name"] ? r.string(root["name"], "name") : fs::path(path).stem().string();
  if (!root["scene"]) fail("{}: scene: required key missing (e.g. scene: {{builtin: drape_fold}})", path);
  c.scene = read_scene(r, root["scene"], path, reg);
  read_settings(r, root, reg, c);
  if (const YAML::Node n = root["replay"]) {
    r.check_keys(n, "replay", {"step", "frames"});
    if (!n["step"])
      fail("{}:{}: replay.step: required key missing (e.g. replay: {{step: 19, frames: 11}})", path, n.Mark().line + 1);
    c.replay.step = int(r.integer(n["step"], "replay.step", 0, 1e6));
    if (n["frames"]) c.replay.frames = int(r.integer(n["frames"], "replay.frames", 2, 1e6));
  }
  c.output.dir = "results/" + c.name;
  if (const YAML::Node o = root["output"]) {
    r.check_keys(o, "output", {"dir", "csv", "jsonl", "contacts"});
    if (o["dir"]) c.output.dir = r.string(o["dir"], "output.dir");
    if (o["csv"]) c.output.csv = r.boolean(o["csv"], "output.csv");
    if (o["jsonl"]) c.output.jsonl = r.boolean(o["jsonl"], "output.jsonl");
    if (o["contacts"]) c.output.contacts = r.boolean(o["contacts"], "output.contacts");
  }
  return c;
}
}  // namespace

nlohmann::json to_json(const ExperimentConfig& c) {
  nlohmann::json j;
  j["name"] = c.name;
  if (c.scene.builtin) {
    nlohmann::json s = params_json(c.scene.generator);
    s["builtin"] = s["name"];
    s.erase("name");
    j["scene"] = s;
  } else {
    if (c.scene.bodies.empty()) {
      j["scene"] = {{"frames", c.scene.files}, {"self_collision", c.scene.self_collision}};
    } else {
      nlohmann::json bodies = nlohmann::json::array();
      for (const BodyFiles& b : c.scene.bodies)
        bodies.push_back({{"name", b.name}, {"frames", b.files}, {"self_collision", b.self_collision && !b.kinematic},
                          {"kinematic", b.kinematic}});
      j["scene"] = {{"bodies", bodies}};
    }
  }
  if (c.replay.step >= 0) j["replay"] = {{"step", c.replay.step}, {"frames", c.replay.frames}};
  j.update(settings_json(c));
  j["output"] = {{"dir", c.output.dir}, {"csv", c.output.csv}, {"jsonl", c.output.jsonl}, {"contacts", c.output.contacts}};
  return j;
}

std::string to_yaml(const nlohmann::json& j) {
  YAML::Emitter out;
  emit(out, j);
  return std::string(out.c_str()) + "\n";
}

namespace {
/// The scene's own frames, before any replay.
MeshSequence make_scene_frames(const ExperimentConfig& c, const Registries& reg) {
  if (c.scene.builtin) {
    const auto* entry = reg.scenes.find(c.scene.generator.name);
    if (entry && entry->triangles && c.memory_limit_bytes > 0) {
      const std::uint64_t triangles = entry->triangles(c.scene.generator.params),
                          need = triangles * MemoryBudget::kResidentBytesPerTriangle;
      if (need > c.memory_limit_bytes)
        fail("memory_limit {}: scene {} would have {} triangles, which need at least {} ({} bytes per triangle before "
             "the first step); lower the scene's resolution or raise memory_limit",
             format_bytes(c.memory_limit_bytes), c.scene.generator.name, triangles, format_bytes(need),
             MemoryBudget::kResidentBytesPerTriangle);
    }
    return reg.scenes.make(c.scene.generator);
  }
  if (!c.scene.bodies.empty()) return load_body_files(c.scene.bodies);
  return load_frame_files(c.scene.files, c.scene.self_collision);
}
}  // namespace

MeshSequence make_scene(const ExperimentConfig& c, const Registries& reg) {
  MeshSequence sequence = make_scene_frames(c, reg);
  return c.replay.step < 0 ? std::move(sequence) : replay_step(std::move(sequence), c.replay.step, c.replay.frames);
}

PipelineStrategies make_strategies(const PipelineConfig& c, const Registries& reg, const SettingName& name) {
  return make_strategies(c, reg.builders, reg.schedulers, reg.testers, name);
}

}  // namespace ccdlab

// The C++ API (ccdlab/ccdlab.hpp) over the framework: options → PipelineStrategies through the experiment
// config's own reader, bodies → one concatenated TriMesh, and the pipelines kept across calls: the CCD one, the
// proximity query's (per d̂) and the line search's (per separation).
#include "ccdlab/ccdlab.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "framework/config/experiment.hpp"
#include "framework/config/settings.hpp"
#include "framework/config/strategy_spec.hpp"
#include "framework/mesh/mesh_io.hpp"
#include "framework/pipeline/bodies.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/pipeline/proximity/proximity_query.hpp"
#include "framework/util/error.hpp"
#include "framework/util/memory.hpp"
#include "strategies/registry.hpp"

namespace ccdlab {
namespace {

/// Runs f; an Error it throws gets `call` in front of its message (the API names the call in every message).
template <class F>
auto named(std::string_view call, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", call, e.what()));
  }
}

/// How Options spells a setting in messages: "Options::member".
SettingName option_name() { return setting_name(SettingSpelling::member, "Options::"); }

/// Options → the pipeline's configuration: each member that is set goes through its row of the settings table
/// (framework/config/settings.hpp), checked as a YAML file's value is and spelled "Options::member" in messages.
PipelineConfig config_of(const Options& o) {
  const Registries reg = builtin_registries();
  PipelineConfig c = default_config(reg);
  const auto set = [&](std::string_view member, const auto& value) {
    if (!value) return;
    const Setting& s = *setting_of_member(member);
    if constexpr (std::is_same_v<std::decay_t<decltype(*value)>, int>) s.set(c, (long long)*value, reg, "Options::" + std::string(member));
    else s.set(c, *value, reg, "Options::" + std::string(member));
  };
#define CCDLAB_SETTING(kind, member, ...) set(#member, o.member);
#include "framework/config/settings.def"
#undef CCDLAB_SETTING
  c.validate(option_name());
  return c;
}

Positions positions_of(std::span<const Point> x, const char* name) {
  Positions p(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    p[i] = Vec3(x[i][0], x[i][1], x[i][2]);
    if (!p[i].allFinite()) fail("{}[{}] = ({}, {}, {}) is not finite", name, i, x[i][0], x[i][1], x[i][2]);
  }
  return p;
}

}  // namespace

MeshFile read_mesh(const std::filesystem::path& path) {
  return named("ccdlab::read_mesh", [&] {
    const MeshData m = read_mesh(path.string());
    MeshFile out;
    out.positions.reserve(m.positions.size());
    for (const Vec3& p : m.positions) out.positions.push_back({p.x(), p.y(), p.z()});
    out.faces.assign(m.faces.begin(), m.faces.end());
    return out;
  });
}

Options Options::from_yaml(std::string_view yaml, std::string_view source) {
  const std::string where(source);
  YAML::Node root = parse_yaml(std::string(yaml), where);
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);  // no text: every default
  if (!root.IsMap()) fail("{}: expected a mapping of option keys (scheduler: …, threads: …)", where);
  const YamlReader r(where, {});
  r.check_keys(root, "", setting_roots());
  const Registries reg = builtin_registries();
  PipelineConfig c = default_config(reg);
  try {
    read_settings(r, root, reg, c);
  } catch (const YAML::Exception& e) {
    fail("{}:{}: {}", where, e.mark.line + 1, e.msg);
  }
  Options o;
  const auto take = [&](std::string_view member, auto& out) {
    const SettingValue v = setting_of_member(member)->value(c);
    using T = typename std::decay_t<decltype(out)>::value_type;
    if constexpr (std::is_same_v<T, int>) out = int(std::get<long long>(v));
    else out = std::get<T>(v);
  };
#define CCDLAB_SETTING(kind, member, ...) take(#member, o.member);
#include "framework/config/settings.def"
#undef CCDLAB_SETTING
  return o;
}

struct Detector::Impl {
  PipelineConfig config;
  std::vector<Face> faces;
  Index vertices = 0;  // fixed once the mesh exists
  std::optional<TriMesh> mesh;
  std::vector<ccdlab::Body> bodies;  // the given ones, or one self-colliding cloth
  std::unique_ptr<CcdPipeline> pipeline;       // step, earliest_toi
  StepResult last_step;                        // step's result, its contact list's memory reused by the next
  std::vector<std::unique_ptr<ProximityQuery>> proximity;  // proximity, one per d̂ asked recently (kProximityQueries)
  std::unique_ptr<CcdPipeline> step_size;      // active_set_and_step at its separation
  double separation = -1;

  /// Builds the mesh (which validates the faces) and the CCD pipeline; no bodies: one self-colliding mesh.
  void start(Index vertex_count, std::vector<ccdlab::Body> given) {
    vertices = vertex_count;
    mesh.emplace(vertex_count, faces);
    bodies = given.empty() ? single_cloth_body(*mesh) : std::move(given);
    pipeline = std::make_unique<CcdPipeline>(*mesh, bodies, make_strategies(config, builtin_registries(), option_name()));
  }
  /// Checks a frame's size (fixing the vertex count on the first call) and its positions.
  Positions frame(std::span<const Point> x, const char* name) {
    if (!pipeline) start(Index(x.size()), {});  // validates the faces against the vertex count (TriMesh)
    if (x.size() != std::size_t(vertices))
      fail("{} has {} positions, but this detector's mesh has {} vertices (fixed by its first call or its bodies)", name,
           x.size(), vertices);
    return positions_of(x, name);
  }
  /// The two frames of a step, as the pipeline takes them.
  std::pair<Positions, Positions> frames(std::span<const Point> x0, std::span<const Point> x1) {
    if (x0.size() != x1.size()) fail("x0 has {} positions, x1 has {}", x0.size(), x1.size());
    return {frame(x0, "x0"), frame(x1, "x1")};
  }
  /// The pairs closer than dhat at x, by the proximity query kept for that d̂ (a solver asks at a few: its barrier's
  /// d̂ and the separation it checks; the least recently made goes when a new one would be one too many).
  static constexpr std::size_t kProximityQueries = 4;
  Proximities near(const Positions& x, double dhat) {
    if (!(dhat > 0) || !std::isfinite(dhat)) fail("dhat = {}: expected a finite distance > 0", dhat);
    auto kept = std::find_if(proximity.begin(), proximity.end(), [dhat](const auto& q) { return q->dhat() == dhat; });
    if (kept == proximity.end()) {
      PipelineConfig c = config;
      c.normal_cones = false;
      if (proximity.size() == kProximityQueries) proximity.erase(proximity.begin());
      proximity.push_back(std::make_unique<ProximityQuery>(*mesh, bodies, make_strategies(c, builtin_registries(), option_name()), dhat));
      kept = proximity.end() - 1;
    }
    Proximities out;
    for (const ProximityPair& p : (*kept)->query(x).pairs) {
      const Proximity q{{p.vertices[0], p.vertices[1], p.vertices[2], p.vertices[3]}, p.distance, to_string(p.type), p.coords};
      (p.kind == ContactKind::vf ? out.vf : out.ee).push_back(q);
    }
    return out;
  }
  /// The earliest time any pair comes within `s` on the step x0 → x1, by `conservative:thickness=s`.
  double first_approach(const Positions& x0, const Positions& x1, double s) {
    if (!(s >= 0) || !std::isfinite(s)) fail("separation = {}: expected a finite distance >= 0", s);
    if (!step_size || separation != s) {
      PipelineConfig c = config;
      c.normal_cones = false;
      c.tester = parse_strategy_spec(fmt::format("conservative:thickness={}", s), "separation: ", "tester",
                                     builtin_registries().testers, kDefaultTester);
      step_size = std::make_unique<CcdPipeline>(*mesh, bodies, make_strategies(c, builtin_registries(), option_name()));
      separation = s;
    }
    return step_size->earliest_toi(x0, x1);
  }
};

Detector::Detector(std::span<const Triangle> faces, const Options& options) : impl_(std::make_unique<Impl>()) {
  named("ccdlab::Detector", [&] {
    impl_->config = config_of(options);
    impl_->faces.reserve(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
      for (const int v : faces[f])
        if (v < 0) fail("faces[{}] = ({}, {}, {}): a negative vertex index", f, faces[f][0], faces[f][1], faces[f][2]);
      impl_->faces.push_back({faces[f][0], faces[f][1], faces[f][2]});
    }
  });
}

Detector::Detector(std::span<const Detector::Body> bodies, const Options& options) : impl_(std::make_unique<Impl>()) {
  named("ccdlab::Detector", [&] {
    impl_->config = config_of(options);
    if (bodies.empty()) fail("no bodies");
    std::vector<ccdlab::Body> ranges;
    Index vertex_begin = 0;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const Detector::Body& body = bodies[b];
      const std::string name = body.name.empty() ? fmt::format("bodies[{}]", b) : body.name;
      if (body.vertices < 3) fail("{}: vertices = {}: expected at least 3", name, body.vertices);
      ccdlab::Body range;
      range.name = name;
      range.kind = body.obstacle ? BodyKind::obstacle : BodyKind::cloth;
      range.self_collision = body.self_collision;
      range.vertex_begin = vertex_begin, range.vertex_end = vertex_begin + body.vertices;
      range.face_begin = Index(impl_->faces.size());
      for (std::size_t f = 0; f < body.faces.size(); ++f) {
        const Triangle& t = body.faces[f];
        for (const int v : t)
          if (v < 0 || v >= body.vertices)
            fail("{}: faces[{}] = ({}, {}, {}): vertex index {} out of range [0, {})", name, f, t[0], t[1], t[2], v, body.vertices);
        impl_->faces.push_back({vertex_begin + t[0], vertex_begin + t[1], vertex_begin + t[2]});
      }
      range.face_end = Index(impl_->faces.size());
      ranges.push_back(range);
      vertex_begin = range.vertex_end;
    }
    impl_->start(vertex_begin, std::move(ranges));
  });
}

Detector::~Detector() = default;
Detector::Detector(Detector&&) noexcept = default;
Detector& Detector::operator=(Detector&&) noexcept = default;

Detector::Contacts Detector::step(std::span<const Point> x0, std::span<const Point> x1) {
  return named("ccdlab::Detector::step", [&] {
    const auto [p0, p1] = impl_->frames(x0, x1);
    impl_->pipeline->step(p0, p1, impl_->last_step);
    const StepResult& r = impl_->last_step;
    Contacts out;
    for (const ccdlab::Contact& c : r.contacts) {
      const Vec3 n = contact_normal(c, p0, p1);
      Detector::Contact k{{c.vertices[0], c.vertices[1], c.vertices[2], c.vertices[3]}, c.toi, c.coords, {n.x(), n.y(), n.z()}};
      (c.kind == ContactKind::vf ? out.vf : out.ee).push_back(k);
    }
    return out;
  });
}

double Detector::earliest_toi(std::span<const Point> x0, std::span<const Point> x1) {
  return named("ccdlab::Detector::earliest_toi", [&] {
    const auto [p0, p1] = impl_->frames(x0, x1);
    return impl_->pipeline->earliest_toi(p0, p1);
  });
}

Detector::Proximities Detector::proximity(std::span<const Point> x, double dhat) {
  return named("ccdlab::Detector::proximity", [&] { return impl_->near(impl_->frame(x, "x"), dhat); });
}

Detector::ActiveSetAndStep Detector::active_set_and_step(std::span<const Point> x0, std::span<const Point> x1, double dhat,
                                                         double separation) {
  return named("ccdlab::Detector::active_set_and_step", [&] {
    const auto [p0, p1] = impl_->frames(x0, x1);
    ActiveSetAndStep out;
    out.active = impl_->near(p0, dhat);
    out.step_size = impl_->first_approach(p0, p1, separation);
    return out;
  });
}

std::string Detector::resolved_options() const {
  return to_yaml(settings_json(impl_->config));
}

}  // namespace ccdlab

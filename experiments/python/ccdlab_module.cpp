// The compiled part of the `ccdlab` Python package (pybind11; built into build/python/ccdlab/, re-exported by
// python/ccdlab/__init__.py): CCD steps and proximity queries on NumPy arrays, with the strategies chosen by name
// and parameters as in YAML.
//
//   import ccdlab
//   r = ccdlab.step(x0, x1, faces, k=18, scheduler="phc", threads=2, tester="conservative")
//   r["vf"]   (N×4 int: v, f0, f1, f2)     r["vf_toi"] (N)   r["vf_coords"] (N×2: weights of f1, f2)
//   r["ee"]   (M×4 int: a0, a1, b0, b1)   r["ee_toi"] (M)   r["ee_coords"] (M×2: parameters on a, b)
//   r["vf_normal"], r["ee_normal"] (unit normals at the time of contact), r["hash"], r["counters"], r["ms"]
//   t = ccdlab.earliest_toi(x0, x1, faces, tester="exact")   (the step's earliest time of contact, 1.0 if none)
//   p = ccdlab.proximity(x, faces, dhat)   (every VF / EE pair closer than dhat: p["vf"], p["vf_distance"],
//       p["vf_type"] ("p_t", "p_e0", …), p["vf_coords"], the same for ee; docs/proximity.md)
//   a = ccdlab.active_set_and_step(x0, x1, faces, dhat, separation)   (proximity at x0, and a["step_size"])
//   rows = ccdlab.validate(["../shared/data/ccd-queries", "hard-cases"], testers=["float", "exact"])
//
// Rows are sorted by feature identity, like the CLI's contacts CSV (same vertex ids, same order).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <string_view>

#include "ccdlab/build_info.hpp"
#include "ccdlab/ccdlab.hpp"
#include "framework/config/pipeline_config.hpp"
#include "framework/config/settings.hpp"
#include "framework/config/strategy_spec.hpp"
#include "framework/pipeline/bodies.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/pipeline/proximity/proximity_query.hpp"
#include "framework/queries/evaluate.hpp"
#include "framework/queries/hard_cases.hpp"
#include "framework/util/error.hpp"
#include "strategies/registry.hpp"
#include "strategies/testers/exact_tester.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace ccdlab {
namespace {

// Arrays arrive as any array-like — a NumPy array of any numeric dtype, order or strides, a list, a tuple — and
// are converted here (a copy where needed); what NumPy cannot convert is refused with ccdlab.Error naming the
// call, the argument, the expected shape and what came, never with a binding's TypeError.
using Points = py::object;     // N×3 positions, converted to C-ordered float64
using Triangles = py::object;  // F×3 vertex indices: integers, or floats that hold integers (checked, never cut)
using Float64 = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// What came, for a message: its type, and its dtype and shape where it is an array.
std::string described(const py::handle& value) {
  if (py::isinstance<py::array>(value)) {
    const auto a = py::reinterpret_borrow<py::array>(value);
    std::string shape;
    for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += (d ? "×" : "") + std::to_string(a.shape(d));
    return fmt::format("an array of dtype {} and shape {}", std::string(py::str(a.dtype())), a.ndim() ? shape : "()");
  }
  return fmt::format("{}", std::string(py::str(py::type::of(value).attr("__name__"))));
}

/// `value` as a C-ordered float64 array, or Error "<call>: <name> must be <expected>, got …".
Float64 as_float64(const py::handle& value, const char* call, const std::string& name, const char* expected) {
  if (value.is_none() || py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value))
    fail("{}: {} must be {}, got {}", call, name, expected, described(value));
  Float64 a = Float64::ensure(value);  // null, the Python error cleared, where NumPy cannot convert it
  if (!a) fail("{}: {} must be {}, got {} that NumPy cannot read as float64 numbers", call, name, expected, described(value));
  return a;
}

// Every message starts with the call it comes from (`call`: "ccdlab.step", "ccdlab.sequence", …).
Positions to_positions(const Points& value, const char* call, const std::string& name) {
  constexpr const char* kExpected = "an N×3 array-like of positions";
  const Float64 a = as_float64(value, call, name, kExpected);
  if (a.ndim() != 2 || a.shape(1) != 3) fail("{}: {} must be {}, got {}", call, name, kExpected, described(a));
  Positions p(std::size_t(a.shape(0)));
  const auto r = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    p[std::size_t(i)] = Vec3(r(i, 0), r(i, 1), r(i, 2));
    if (!p[std::size_t(i)].allFinite()) fail("{}: {}[{}] is not finite", call, name, i);
  }
  return p;
}

std::vector<Face> to_faces(const Triangles& value, std::size_t vertices, const char* call) {
  constexpr const char* kExpected = "an F×3 array-like of integer vertex indices";
  if (value.is_none() || py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value))
    fail("{}: faces must be {}, got {}", call, kExpected, described(value));
  const py::array a = py::array::ensure(value);
  if (!a) fail("{}: faces must be {}, got {} that NumPy cannot read as an array", call, kExpected, described(value));
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u' && kind != 'f') fail("{}: faces must be {}, got {}", call, kExpected, described(a));
  if (a.ndim() != 2 || a.shape(1) != 3) fail("{}: faces must be {}, got {}", call, kExpected, described(a));
  // As doubles: every int64 index this library can hold (< 2^31) is exact, and a float that is not an integer shows.
  const Float64 d = as_float64(a, call, "faces", kExpected);
  std::vector<Face> f(std::size_t(a.shape(0)));
  const auto r = d.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (int j = 0; j < 3; ++j) {
      const double v = r(i, j);
      if (v != std::floor(v)) fail("{}: faces[{}][{}] = {} is not an integer vertex index", call, i, j, v);
      if (v < 0 || v >= double(vertices))
        fail("{}: faces[{}][{}] = {} is not a vertex index (0…{})", call, i, j, v, vertices - 1);
      f[std::size_t(i)][std::size_t(j)] = Index(v);
    }
  return f;
}

/// The mesh of a call: its faces checked against the vertex count, degenerate ones refused, named by the call.
TriMesh to_mesh(std::size_t vertices, const Triangles& faces, const char* call) {
  try {
    return TriMesh(Index(vertices), to_faces(faces, vertices, call));
  } catch (const Error& e) {
    if (std::string_view(e.what()).starts_with(call)) throw;
    fail("{}: faces: {}", call, e.what());
  }
}

/// A keyword's value as its row of the settings table reads it (framework/config/settings.hpp): a bool, an int, a
/// float, a str, or for a strategy a dict {"name": …, key: value} (written as "name:key=value,…").
SettingValue setting_value(const Setting& s, const py::handle& value, const char* call) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();  // before int: a bool is an int to Python
  if (py::isinstance<py::int_>(value)) return value.cast<long long>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (s.kind == SettingKind::strategy && py::isinstance<py::dict>(value)) {
    const auto d = value.cast<py::dict>();
    std::string spec = d.contains("name") ? py::str(d["name"]).cast<std::string>() : std::string();
    char sep = ':';
    for (const auto& [k, v] : d) {
      const std::string key = py::str(k);
      if (key == "name") continue;
      spec += sep + key + "=" +
              (py::isinstance<py::bool_>(v) ? std::string(v.cast<bool>() ? "true" : "false") : std::string(py::str(v)));
      sep = ',';
    }
    return spec;
  }
  fail("{}: {}: expected {}, got {}", call, s.member, s.kind == SettingKind::strategy ? "a name, 'name:key=value,…' or a dict" : "a bool, int, float or str", described(value));
}

/// The row of a keyword; an unknown one is an error that lists them all.
const Setting& setting_of_keyword(const std::string& key, const char* call) {
  if (const Setting* s = setting_of_member(key)) return *s;
  fail("{}: unknown option '{}' ({})", call, key, setting_members());
}

/// kwargs → the pipeline's strategies and settings: the defaults, each keyword set through its row, spelled
/// "<call>: keyword" in messages.
PipelineStrategies strategies_from(const py::kwargs& options, const char* call) {
  const Registries reg = builtin_registries();
  PipelineConfig c = default_config(reg);
  for (const auto& [key_handle, value] : options) {
    const Setting& s = setting_of_keyword(py::str(key_handle), call);
    s.set(c, setting_value(s, value, call), reg, fmt::format("{}: {}", call, s.member));
  }
  return make_strategies(c, reg.builders, reg.schedulers, reg.testers,
                         setting_name(SettingSpelling::member, std::string(call) + ": "));
}

py::dict result_dict(const StepResult& r, const Positions& x0, const Positions& x1) {
  std::size_t nvf = 0;
  for (const Contact& c : r.contacts) nvf += c.kind == ContactKind::vf;
  const std::size_t nee = r.contacts.size() - nvf;
  py::array_t<std::int64_t> vf({py::ssize_t(nvf), py::ssize_t(4)}), ee({py::ssize_t(nee), py::ssize_t(4)});
  py::array_t<double> vf_toi(static_cast<py::ssize_t>(nvf)), ee_toi(static_cast<py::ssize_t>(nee));
  py::array_t<double> vf_coords({py::ssize_t(nvf), py::ssize_t(2)}), ee_coords({py::ssize_t(nee), py::ssize_t(2)});
  py::array_t<double> vf_normal({py::ssize_t(nvf), py::ssize_t(3)}), ee_normal({py::ssize_t(nee), py::ssize_t(3)});
  auto vfi = vf.mutable_unchecked<2>(), eei = ee.mutable_unchecked<2>();
  auto vft = vf_toi.mutable_unchecked<1>(), eet = ee_toi.mutable_unchecked<1>();
  auto vfc = vf_coords.mutable_unchecked<2>(), eec = ee_coords.mutable_unchecked<2>();
  auto vfn = vf_normal.mutable_unchecked<2>(), een = ee_normal.mutable_unchecked<2>();
  py::ssize_t i = 0, j = 0;
  for (const Contact& c : r.contacts) {
    const Vec3 n = contact_normal(c, x0, x1);
    if (c.kind == ContactKind::vf) {
      for (int k = 0; k < 4; ++k) vfi(i, k) = c.vertices[std::size_t(k)];
      vft(i) = c.toi;
      for (int k = 0; k < 2; ++k) vfc(i, k) = c.coords[std::size_t(k)];
      for (int k = 0; k < 3; ++k) vfn(i, k) = n[k];
      ++i;
    } else {
      for (int k = 0; k < 4; ++k) eei(j, k) = c.vertices[std::size_t(k)];
      eet(j) = c.toi;
      for (int k = 0; k < 2; ++k) eec(j, k) = c.coords[std::size_t(k)];
      for (int k = 0; k < 3; ++k) een(j, k) = n[k];
      ++j;
    }
  }
  const StepCounters& k = r.counters;
  const StepTimings& t = r.timings;
  py::dict counters, ms;
  for (const auto& [name, value] : {std::pair{"bv_tests", k.bv_tests}, {"candidate_pairs", k.candidate_pairs},
                                    {"vf_pairs", k.vf_pairs}, {"ee_pairs", k.ee_pairs}, {"vf_tests", k.vf_tests},
                                    {"ee_tests", k.ee_tests}, {"orphan_vf", k.orphan_vf}, {"orphan_ee", k.orphan_ee}})
    counters[name] = value;
  for (const auto& [name, value] : {std::pair{"total", t.total_ms}, {"build", t.build_ms}, {"refit", t.refit_ms},
                                    {"traverse", t.traverse_ms}, {"narrow", t.narrow_ms}, {"orphans", t.orphan_ms}})
    ms[name] = value;
  py::dict d;
  d["vf"] = vf;
  d["vf_toi"] = vf_toi;
  d["vf_coords"] = vf_coords;
  d["vf_normal"] = vf_normal;
  d["ee"] = ee;
  d["ee_toi"] = ee_toi;
  d["ee_coords"] = ee_coords;
  d["ee_normal"] = ee_normal;
  d["hash"] = fmt::format("{:016x}", contact_set_hash(r.contacts));
  d["counters"] = counters;
  d["ms"] = ms;
  return d;
}

/// Rows of `n` values each, from `get(i, j)`.
template <class T, class Get>
py::array_t<T> rows(std::size_t count, py::ssize_t n, Get&& get) {
  py::array_t<T> a = n == 1 ? py::array_t<T>(py::ssize_t(count)) : py::array_t<T>({py::ssize_t(count), n});
  T* d = a.mutable_data();
  for (std::size_t i = 0; i < count; ++i)
    for (py::ssize_t j = 0; j < n; ++j) d[std::size_t(i) * std::size_t(n) + std::size_t(j)] = get(i, j);
  return a;
}

/// One kind's proximity pairs (`k`: "vf" or "ee") as arrays: k (ids), k_distance, k_type, k_coords; any pair type with
/// vertices, distance and coords, its type's name from `type_of` (the framework's ProximityPair, the API's Proximity).
template <class P, class TypeOf>
void put_proximities(py::dict& d, const std::string& k, const std::vector<const P*>& l, TypeOf&& type_of) {
  d[py::str(k)] = rows<std::int64_t>(l.size(), 4, [&](std::size_t i, py::ssize_t j) { return l[i]->vertices[std::size_t(j)]; });
  d[py::str(k + "_distance")] = rows<double>(l.size(), 1, [&](std::size_t i, py::ssize_t) { return l[i]->distance; });
  py::list types;
  for (const P* q : l) types.append(py::str(std::string(type_of(*q))));
  d[py::str(k + "_type")] = py::module_::import("numpy").attr("array")(types, "dtype"_a = "U7");
  d[py::str(k + "_coords")] = rows<double>(l.size(), 2, [&](std::size_t i, py::ssize_t j) { return l[i]->coords[std::size_t(j)]; });
}

/// A proximity query's pairs as NumPy arrays, split by kind (as step's contacts).
py::dict proximity_dict(const ProximityResult& r) {
  py::dict d;
  for (const ContactKind kind : {ContactKind::vf, ContactKind::ee}) {
    std::vector<const ProximityPair*> l;
    for (const ProximityPair& p : r.pairs)
      if (p.kind == kind) l.push_back(&p);
    put_proximities(d, std::string(to_string(kind)), l, [](const ProximityPair& p) { return to_string(p.type); });
  }
  const StepCounters& k = r.step.counters;
  const StepTimings& t = r.step.timings;
  py::dict counters, ms;
  for (const auto& [name, value] : {std::pair{"bv_tests", k.bv_tests}, {"candidate_pairs", k.candidate_pairs},
                                    {"vf_tests", k.vf_tests}, {"ee_tests", k.ee_tests}, {"orphan_tests", k.orphan_tests},
                                    {"decided_in_rationals", k.tests_fallback}})
    counters[name] = value;
  for (const auto& [name, value] : {std::pair{"total", t.total_ms}, {"build", t.build_ms}, {"refit", t.refit_ms},
                                    {"traverse", t.traverse_ms}, {"narrow", t.narrow_ms}, {"orphans", t.orphan_ms}})
    ms[name] = value;
  d["hash"] = fmt::format("{:016x}", r.hash);
  d["counters"] = counters;
  d["ms"] = ms;
  return d;
}

/// The proximity query at x0 (and, with x1, the step size for `separation`): one mesh, options as step()'s less
/// `tester` (the query's test is its own, exact).
py::dict near_pairs(const Points& x0, const Points* x1, const Triangles& faces, double dhat, double separation,
                    const py::kwargs& options, const char* call) {
  if (options.contains("tester")) fail("{}: tester: not an option here (the proximity test is exact, its own)", call);
  if (!(dhat > 0) || !std::isfinite(dhat)) fail("{}: dhat = {}: expected a finite distance > 0", call, dhat);
  const Positions p0 = to_positions(x0, call, x1 ? "x0" : "x");
  Positions p1;
  if (x1) {
    if (!(separation >= 0) || !std::isfinite(separation))
      fail("{}: separation = {}: expected a finite distance >= 0", call, separation);
    p1 = to_positions(*x1, call, "x1");
    if (p1.size() != p0.size()) fail("{}: x1 has {} vertices, x0 has {}", call, p1.size(), p0.size());
  }
  const TriMesh mesh = to_mesh(p0.size(), faces, call);
  ProximityQuery query(mesh, single_cloth_body(mesh), strategies_from(options, call), dhat);
  std::unique_ptr<CcdPipeline> approach;  // the step size's: conservative at thickness `separation`
  if (x1) {
    PipelineStrategies s = strategies_from(options, call);
    s.normal_cones = false;
    s.tester = tester_registry().make(parse_strategy_spec(fmt::format("conservative:thickness={}", separation),
                                                          fmt::format("{}: separation: ", call), "tester",
                                                          tester_registry(), kDefaultTester));
    approach = std::make_unique<CcdPipeline>(mesh, single_cloth_body(mesh), std::move(s));
  }
  ProximityResult r;
  double step_size = 1;
  try {
    py::gil_scoped_release release;
    r = query.query(p0);
    if (approach) step_size = approach->earliest_toi(p0, p1);
  } catch (const Error& e) {  // a refusal of the work (d̂, time, memory): named by the call, as the arguments' errors
    fail("{}: {}", call, e.what());
  }
  py::dict d = proximity_dict(r);
  if (x1) d["step_size"] = step_size;
  return d;
}

/// kwargs → the C++ API's Options (the Detector's): the same keywords as the functions' (strategies_from).
Options options_from(const py::kwargs& options, const char* call) {
  Options o;
  for (const auto& [key_handle, value] : options) {
    const Setting& s = setting_of_keyword(py::str(key_handle), call);
    const SettingValue v = setting_value(s, value, call);
    const auto put = [&](auto& member) {
      using T = typename std::decay_t<decltype(member)>::value_type;
      if constexpr (std::is_same_v<T, int>) {
        if (const long long* i = std::get_if<long long>(&v); i && *i == int(*i)) return void(member = int(*i));
      } else if constexpr (std::is_same_v<T, double>) {
        if (const long long* i = std::get_if<long long>(&v)) return void(member = double(*i));
        if (const double* d = std::get_if<double>(&v)) return void(member = *d);
      } else if constexpr (std::is_same_v<T, bool>) {
        if (const bool* b = std::get_if<bool>(&v)) return void(member = *b);
      } else {
        if (const std::string* t = std::get_if<std::string>(&v)) return void(member = *t);
        if (const bool* b = std::get_if<bool>(&v)) return void(member = *b ? "true" : "false");
      }
      fail("{}: {}: expected {}, got {}", call, s.member, s.type, describe(v));
    };
#define CCDLAB_SETTING(kind, name, ...) if (s.member == #name) put(o.name);
#include "framework/config/settings.def"
#undef CCDLAB_SETTING
  }
  return o;
}

std::vector<Point> to_points(const Points& value, const char* call, const char* name) {
  const Positions p = to_positions(value, call, name);
  std::vector<Point> out(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) out[i] = {p[i].x(), p[i].y(), p[i].z()};
  return out;
}

py::dict contacts_dict(const Detector::Contacts& c) {
  py::dict d;
  for (const auto& [name, list] : {std::pair{"vf", &c.vf}, std::pair{"ee", &c.ee}}) {
    const std::string k(name);
    const auto& l = *list;
    d[py::str(k)] = rows<std::int64_t>(l.size(), 4, [&](std::size_t i, py::ssize_t j) { return l[i].vertices[std::size_t(j)]; });
    d[py::str(k + "_toi")] = rows<double>(l.size(), 1, [&](std::size_t i, py::ssize_t) { return l[i].toi; });
    d[py::str(k + "_coords")] = rows<double>(l.size(), 2, [&](std::size_t i, py::ssize_t j) { return l[i].coords[std::size_t(j)]; });
    d[py::str(k + "_normal")] = rows<double>(l.size(), 3, [&](std::size_t i, py::ssize_t j) { return l[i].normal[std::size_t(j)]; });
  }
  return d;
}

py::dict proximities_dict(const Detector::Proximities& p) {
  py::dict d;
  for (const auto& [name, list] : {std::pair{"vf", &p.vf}, std::pair{"ee", &p.ee}}) {
    std::vector<const Detector::Proximity*> l;
    for (const Detector::Proximity& q : *list) l.push_back(&q);
    put_proximities(d, name, l, [](const Detector::Proximity& q) { return q.type; });
  }
  return d;
}

/// ccdlab.Detector: the C++ API's Detector from Python — its hierarchies built on the first call and refit on later
/// ones, what a simulation loop or a solver's Newton iterations want. One call at a time per Detector (a lock).
class PyDetector {
  /// Runs f without the GIL (the Detector runs its own threads), one call at a time; the API's messages in Python's
  /// spelling ("ccdlab::Detector::step: …" → "ccdlab.Detector.step: …").
  template <class F>
  auto locked(F&& f) {
    try {
      py::gil_scoped_release release;
      const std::lock_guard<std::mutex> lock(mutex_);
      return f();
    } catch (const Error& e) {
      throw Error(python_spelling(e.what()));
    }
  }
  static std::string python_spelling(std::string m) {
    for (const auto& [from, to] : {std::pair{"ccdlab::Detector::", "ccdlab.Detector."}, {"ccdlab::Detector", "ccdlab.Detector"},
                                   {"Options::", ""}})
      for (std::size_t at = m.find(from); at != std::string::npos; at = m.find(from, at + std::strlen(to)))
        m.replace(at, std::strlen(from), to);
    return m;
  }

 public:
  PyDetector(const py::object& faces, const py::object& bodies, const py::kwargs& options) {
    const char* call = "ccdlab.Detector";
    const Options o = options_from(options, call);
    if (faces.is_none() == bodies.is_none()) fail("{}: give faces (one self-colliding mesh) or bodies=[…], not both", call);
    if (!faces.is_none()) {
      std::vector<Triangle> f;
      for (const Face& t : to_faces(faces, std::size_t(std::numeric_limits<int>::max()), call)) f.push_back({t[0], t[1], t[2]});
      detector_ = locked([&] { return std::make_unique<Detector>(f, o); });
      return;
    }
    if (!py::isinstance<py::sequence>(bodies) || py::isinstance<py::str>(bodies))
      fail("{}: bodies must be a list of dicts {{faces, vertices, obstacle, self_collision, name}}, got {}", call, described(bodies));
    std::vector<Detector::Body> list;
    for (const py::handle b : bodies) {
      if (!py::isinstance<py::dict>(b)) fail("{}: bodies[{}] must be a dict, got {}", call, list.size(), described(b));
      const py::dict d = py::reinterpret_borrow<py::dict>(b);
      for (const auto& [k, v] : d) {
        const std::string key = py::str(k);
        if (key != "faces" && key != "vertices" && key != "obstacle" && key != "self_collision" && key != "name")
          fail("{}: bodies[{}]: unknown key '{}' (faces, vertices, obstacle, self_collision, name)", call, list.size(), key);
      }
      if (!d.contains("faces") || !d.contains("vertices")) fail("{}: bodies[{}]: faces and vertices are required", call, list.size());
      Detector::Body body;
      body.vertices = d["vertices"].cast<int>();
      if (body.vertices < 0) fail("{}: bodies[{}]: vertices = {}: expected a count", call, list.size(), body.vertices);
      for (const Face& t : to_faces(d["faces"], std::size_t(body.vertices), call)) body.faces.push_back({t[0], t[1], t[2]});
      body.obstacle = d.contains("obstacle") && d["obstacle"].cast<bool>();
      body.self_collision = !d.contains("self_collision") || d["self_collision"].cast<bool>();
      body.name = d.contains("name") ? d["name"].cast<std::string>() : std::string();
      list.push_back(std::move(body));
    }
    detector_ = locked([&] { return std::make_unique<Detector>(std::span<const Detector::Body>(list), o); });
  }

  py::dict step(const Points& x0, const Points& x1) {
    const auto p0 = to_points(x0, "ccdlab.Detector.step", "x0"), p1 = to_points(x1, "ccdlab.Detector.step", "x1");
    return contacts_dict(locked([&] { return detector_->step(p0, p1); }));
  }
  double earliest_toi(const Points& x0, const Points& x1) {
    const auto p0 = to_points(x0, "ccdlab.Detector.earliest_toi", "x0"), p1 = to_points(x1, "ccdlab.Detector.earliest_toi", "x1");
    return locked([&] { return detector_->earliest_toi(p0, p1); });
  }
  py::dict proximity(const Points& x, double dhat) {
    const auto p = to_points(x, "ccdlab.Detector.proximity", "x");
    return proximities_dict(locked([&] { return detector_->proximity(p, dhat); }));
  }
  py::dict active_set_and_step(const Points& x0, const Points& x1, double dhat, double separation) {
    const char* call = "ccdlab.Detector.active_set_and_step";
    const auto p0 = to_points(x0, call, "x0"), p1 = to_points(x1, call, "x1");
    const Detector::ActiveSetAndStep r = locked([&] { return detector_->active_set_and_step(p0, p1, dhat, separation); });
    py::dict d = proximities_dict(r.active);
    d["step_size"] = r.step_size;
    return d;
  }
  [[nodiscard]] std::string options() const { return detector_->resolved_options(); }

 private:
  std::unique_ptr<Detector> detector_;
  std::mutex mutex_;
};

/// Runs the pipeline over consecutive frames (one BVH, refit each step, as `ccdlab run`).
py::list run_frames(const std::vector<py::object>& frames, const Triangles& faces, const py::kwargs& options,
                    const char* call = "ccdlab.sequence") {
  if (frames.size() < 2) fail("{}: expected at least two frames, got {}", call, frames.size());
  const bool two = std::string_view(call) != "ccdlab.sequence";  // step / earliest_toi: x0 and x1
  std::vector<Positions> x;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    x.push_back(to_positions(frames[i], call, two ? fmt::format("x{}", i) : fmt::format("frames[{}]", i)));
    if (x.back().size() != x.front().size())
      fail("{}: {} has {} vertices, {} has {}", call, two ? "x1" : fmt::format("frames[{}]", i), x.back().size(),
           two ? "x0" : "frames[0]", x.front().size());
  }
  const TriMesh mesh = to_mesh(x.front().size(), faces, call);
  CcdPipeline pipeline(mesh, single_cloth_body(mesh), strategies_from(options, call));
  py::list out;
  StepResult r;  // one for every step: its contact list's memory reused
  for (std::size_t s = 0; s + 1 < x.size(); ++s) {
    {
      py::gil_scoped_release release;  // the step runs its own threads; other Python threads may run meanwhile
      pipeline.step(x[s], x[s + 1], r);
    }
    out.append(result_dict(r, x[s], x[s + 1]));
  }
  return out;
}

/// `ccdlab validate` from Python: every tester over every query set, scored against the truth and the exact
/// times; one dict per set × tester with the columns of validate.csv.
py::list validate(const std::vector<std::string>& paths, const std::vector<std::string>& testers, int repeat) {
  if (repeat < 1) fail("ccdlab.validate: repeat: expected an integer >= 1, got {}", repeat);
  std::vector<std::unique_ptr<PrimitiveTester>> made;
  for (const auto& spec : testers)
    made.push_back(tester_registry().make(parse_strategy_spec(spec, "ccdlab.validate: testers: ", "tester", tester_registry(), "float")));
  std::vector<QuerySet> sets;
  for (const auto& path : paths)
    for (auto& s : path == "hard-cases" ? hard_case_sets() : load_query_sets(path)) sets.push_back(std::move(s));
  std::vector<SetScore> scores;
  {
    py::gil_scoped_release release;
    for (const QuerySet& set : sets) {
      const std::vector<ToiReference> reference = exact_reference(set);
      for (std::size_t t = 0; t < made.size(); ++t)
        scores.push_back(score(set, testers[t], run_tester(*made[t], set, repeat), reference));
    }
  }
  py::list out;
  for (const SetScore& s : scores) {
    py::dict d;
    d["set"] = s.set, d["scene"] = s.scene, d["collection"] = s.collection, d["tester"] = s.tester;
    d["queries"] = s.queries, d["positives"] = s.positives;
    d["false_negatives"] = s.false_negatives, d["false_positives"] = s.false_positives;
    d["filtered"] = s.filtered, d["fallbacks"] = s.fallbacks;
    d["mean_us"] = s.mean_us, d["median_us"] = s.median_us, d["p99_us"] = s.p99_us, d["max_us"] = s.max_us;
    d["toi_max_error"] = s.toi_max_error, d["toi_mean_error"] = s.toi_mean_error, d["toi_late"] = s.toi_late;
    out.append(d);
  }
  return out;
}

}  // namespace
}  // namespace ccdlab

PYBIND11_MODULE(_ccdlab, m) {
  using namespace ccdlab;
  m.doc() = "ccdlab: continuous collision detection for deforming triangle meshes (k-DOP BVHs, BVTT traversal, "
            "exact elementary tests). Options are the YAML strategies by name: k, width, hierarchy, scheduler, "
            "threads, tester, narrow, representative, normal_cones.";
  m.attr("__version__") = build_info::git_revision;
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  m.def(
      "step",
      [](const Points& x0, const Points& x1, const Triangles& faces, const py::kwargs& options) {
        return run_frames({x0, x1}, faces, options, "ccdlab.step")[0].cast<py::dict>();
      },
      py::arg("x0"), py::arg("x1"), py::arg("faces"),
      "One CCD step of a self-colliding mesh from positions x0 (N×3) to x1 (N×3), faces F×3. Returns a dict: vf "
      "(v, f0, f1, f2) and ee (a0, a1, b0, b1) vertex ids, their toi, coords and normal, hash, counters, ms.");
  m.def(
      "earliest_toi",
      [](const Points& x0, const Points& x1, const Triangles& faces, const py::kwargs& options) {
        const char* call = "ccdlab.earliest_toi";
        const Positions p0 = to_positions(x0, call, "x0"), p1 = to_positions(x1, call, "x1");
        if (p1.size() != p0.size()) fail("{}: x1 has {} vertices, x0 has {}", call, p1.size(), p0.size());
        const TriMesh mesh = to_mesh(p0.size(), faces, call);
        CcdPipeline pipeline(mesh, single_cloth_body(mesh), strategies_from(options, call));
        py::gil_scoped_release release;
        return pipeline.earliest_toi(p0, p1);
      },
      py::arg("x0"), py::arg("x1"), py::arg("faces"),
      "The earliest time of contact in [0, 1] of one step (1.0 when none), without solving the pairs that cannot "
      "beat the best time found so far; options as step(). Never later than the truth with tester='conservative' "
      "(within 1e-9 of it) or 'exact'.");
  m.def(
      "proximity",
      [](const Points& x, const Triangles& faces, double dhat, const py::kwargs& options) {
        return near_pairs(x, nullptr, faces, dhat, 0, options, "ccdlab.proximity");
      },
      py::arg("x"), py::arg("faces"), py::arg("dhat"),
      "Every non-adjacent vertex-face and edge-edge pair of a self-colliding mesh (positions x N×3, faces F×3) whose "
      "exact distance is below dhat (none missed, none farther reported). Returns a dict: vf (v, f0, f1, f2) and ee "
      "(a0, a1, b0, b1) vertex ids, their distance, type (closest features: p_t, p_e0..p_e2, p_t0..p_t2; ea_eb, "
      "ea0_eb, ..., ea1_eb1) and coords (VF: weights of f1, f2; EE: parameters on a, b), hash, counters, ms. "
      "Options as step() less tester.");
  m.def(
      "active_set_and_step",
      [](const Points& x0, const Points& x1, const Triangles& faces, double dhat, double separation,
         const py::kwargs& options) {
        return near_pairs(x0, &x1, faces, dhat, separation, options, "ccdlab.active_set_and_step");
      },
      py::arg("x0"), py::arg("x1"), py::arg("faces"), py::arg("dhat"), py::arg("separation"),
      "What a barrier solver's line search asks: proximity(x0, faces, dhat), plus step_size: the largest fraction t "
      "of the step x0 -> x1 such that no pair comes closer than separation before x0 + t (x1 - x0) (1.0 when none; "
      "never later than the truth).");
  m.def("sequence", [](const py::object& frames, const Triangles& faces, const py::kwargs& options) {
          const char* call = "ccdlab.sequence";
          if (!py::isinstance<py::sequence>(frames) || py::isinstance<py::str>(frames))
            fail("{}: frames must be a list of N×3 array-likes of positions, got {}", call, described(frames));
          return run_frames(frames.cast<std::vector<py::object>>(), faces, options, call);
        }, py::arg("frames"), py::arg("faces"),
        "CCD over consecutive frames (a list of N×3 arrays) of one mesh: a list of step dicts (as step()).");
  m.def("validate", &validate, py::arg("paths"), py::arg("testers") = tester_registry().names(),
        py::arg("repeat") = 1,
        "Testers (names or 'name:key=value,…'; default: every tester of the ladder) over elementary query sets with known answers — CSV files or folders "
        "of the shared format, or 'hard-cases' — as `ccdlab validate`: a list of dicts, one per set and tester "
        "(set, scene, collection, tester, queries, positives, false_negatives, false_positives, filtered, "
        "fallbacks, mean/median/p99/max_us, toi_max_error, toi_mean_error, toi_late).");
  py::class_<PyDetector>(m, "Detector",
                         "A detector kept across calls (the C++ API's ccdlab::Detector): Detector(faces, **options) for "
                         "one self-colliding mesh, or Detector(bodies=[{faces, vertices, obstacle, self_collision, name}, "
                         "...], **options). Its hierarchies are built on the first call and refit on later ones; options "
                         "as step()'s, plus memory_limit.")
      .def(py::init<const py::object&, const py::object&, const py::kwargs&>(), py::arg("faces") = py::none(),
           py::arg("bodies") = py::none())
      .def("step", &PyDetector::step, py::arg("x0"), py::arg("x1"),
           "Every contact while the vertices move linearly from x0 to x1: vf, ee (vertex ids), *_toi, *_coords, *_normal.")
      .def("earliest_toi", &PyDetector::earliest_toi, py::arg("x0"), py::arg("x1"),
           "The step's earliest time of contact (1.0 when none).")
      .def("proximity", &PyDetector::proximity, py::arg("x"), py::arg("dhat"),
           "Every pair closer than dhat at x, as ccdlab.proximity (no hash, counters or ms); the queries of the last four "
           "dhat values are kept and refit.")
      .def("active_set_and_step", &PyDetector::active_set_and_step, py::arg("x0"), py::arg("x1"), py::arg("dhat"),
           py::arg("separation"), "proximity(x0, dhat) and step_size: how far towards x1 before any pair comes within separation.")
      .def_property_readonly("options", &PyDetector::options, "the options in effect, every default filled in (YAML)");
  m.def("schedulers", [] { return scheduler_registry().names(); }, "the registered traversal schedulers");
  m.def("testers", [] { return tester_registry().names(); }, "the registered elementary testers");
  m.def("settings", [] {
    // The settings table (framework/config/settings.def): what every function and Detector takes by keyword.
    const PipelineConfig defaults = default_config(builtin_registries());
    py::list rows;
    for (const Setting& s : settings()) {
      py::dict row;
      row["keyword"] = std::string(s.member);
      row["type"] = s.kind == SettingKind::strategy ? "Strategy"
                    : s.type == "int"              ? "int"
                    : s.type == "double"           ? "float"
                    : s.type == "bool"             ? "bool"
                                                   : "str";
      row["key"] = std::string(s.key);
      row["flag"] = std::string(s.flag_name());
      row["default"] = std::visit([](const auto& v) { return py::cast(v); }, s.value(defaults));
      row["accepts"] = s.accepts(builtin_registries());
      row["doc"] = std::string(s.doc);
      rows.append(row);
    }
    return rows;
  }, "the settings every function takes by keyword: keyword, type, key, flag, default, accepts, doc");
}

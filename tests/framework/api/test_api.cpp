// The C++ API (ccdlab/ccdlab.hpp): options from YAML with located errors, a Detector's contacts equal to the
// pipeline's on the same step for every scheduler, several bodies with an obstacle, and every bad input refused
// with a ccdlab::Error that names the call.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "ccdlab/ccdlab.hpp"
#include "framework/config/settings.hpp"
#include "framework/config/pipeline_config.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "framework/pipeline/proximity/proximity_query.hpp"
#include "strategies/registry.hpp"
#include "support/registries.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

/// The message of the Error f throws ("" when it throws none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::vector<Point> points(const Positions& x) {
  std::vector<Point> p;
  for (const Vec3& v : x) p.push_back({v.x(), v.y(), v.z()});
  return p;
}

TEST(Api, OptionsFromYamlTakeTheStrategyKeys) {
  const Options o = Options::from_yaml("bv: {k: 26, width: 2}\nscheduler: phc\nthreads: 2\ntester: {name: conservative, delta: 1e-6}\n"
                                       "narrow: {mode: scalar, representative: first_free}\nnormal_cones: true\nmemory_limit: 1GiB\n"
                                       "candidate_limit: 50");
  EXPECT_EQ(o.k, 26);
  EXPECT_EQ(o.width, 2);
  EXPECT_EQ(o.scheduler->rfind("phc", 0), 0u) << *o.scheduler;  // with its parameters' defaults filled in
  EXPECT_EQ(o.threads, 2);
  EXPECT_EQ(o.tester->rfind("conservative:", 0), 0u) << *o.tester;
  EXPECT_NE(o.tester->find("delta=1e-06"), std::string::npos) << *o.tester;
  EXPECT_EQ(o.narrow, "scalar");
  EXPECT_EQ(o.representative, "first_free");
  EXPECT_TRUE(o.normal_cones);
  EXPECT_EQ(o.memory_limit, "1GiB");
  EXPECT_EQ(o.candidate_limit, 50);
  EXPECT_EQ(Options::from_yaml("").scheduler, "sequential");
  EXPECT_EQ(Options::from_yaml("").end_boxes, "auto");
  EXPECT_EQ(Options::from_yaml("bv: {end_boxes: true}").end_boxes, "on");
  EXPECT_EQ(Options::from_yaml("bv: {end_boxes: false}").end_boxes, "off");
  const std::vector<Triangle> faces{{0, 1, 2}};
  EXPECT_NO_THROW(Detector(faces, o));  // the resolved "name:key=value" texts read back
}

TEST(Api, OptionErrorsAreLocated) {
  EXPECT_NE(error_of([] { (void)Options::from_yaml("threads: 2\nsheduler: phc", "opts"); }).find("opts:2"), std::string::npos);
  EXPECT_NE(error_of([] { (void)Options::from_yaml("threads: 2\nsheduler: phc"); }).find("scheduler"), std::string::npos);  // did you mean
  EXPECT_NE(error_of([] { (void)Options::from_yaml("threads: two"); }).find("threads"), std::string::npos);
  EXPECT_NE(error_of([] { (void)Options::from_yaml("scene: {builtin: drape_fold}"); }).find("scene"), std::string::npos);
  EXPECT_NE(error_of([] { (void)Options::from_yaml("tester: [float"); }).find("syntax"), std::string::npos);
  const std::vector<Triangle> faces{{0, 1, 2}};
  Options o;
  o.tester = "flaot";
  EXPECT_NE(error_of([&] { Detector d(faces, o); }).find("ccdlab::Detector: Options::tester"), std::string::npos);
  o = Options{};
  o.k = 7;
  EXPECT_NE(error_of([&] { Detector d(faces, o); }).find("Options::k"), std::string::npos);
  o = Options{};
  o.narrow = "fast";
  EXPECT_NE(error_of([&] { Detector d(faces, o); }).find("Options::narrow"), std::string::npos);
  o = Options{};
  o.end_boxes = "yes";
  EXPECT_NE(error_of([&] { Detector d(faces, o); }).find("Options::end_boxes: expected on, off, auto, true or false"), std::string::npos);
}

TEST(Api, OptionsFromYamlFillEveryMemberWithThePipelinesDefault) {
  // Options holds a member per row of the settings table (ccdlab/settings.def); from_yaml fills in those the text
  // leaves out with the pipeline's defaults (default_config: the fields' own), and a Detector made from it is the
  // default one.
  const Options o = Options::from_yaml("");
  const PipelineConfig c = default_config(builtin_registries());
  std::size_t members = 0;
  const auto same = [&](std::string_view member, const auto& value) {
    ++members;
    ASSERT_TRUE(value.has_value()) << member;
    const SettingValue want = setting_of_member(member)->value(c);
    if constexpr (std::is_same_v<std::decay_t<decltype(*value)>, int>) EXPECT_EQ(std::get<long long>(want), *value) << member;
    else EXPECT_EQ(std::get<std::decay_t<decltype(*value)>>(want), *value) << member;
  };
#define CCDLAB_SETTING(kind, member, ...) same(#member, o.member);
#include "framework/config/settings.def"
#undef CCDLAB_SETTING
  EXPECT_EQ(members, settings().size());
  EXPECT_EQ(c.k, PipelineSettings{}.k);
  EXPECT_EQ(c.narrow.mode, NarrowOptions{}.mode);
  EXPECT_EQ(c.tester.name, kDefaultTester);
}

TEST(Api, DetectorFindsThePipelinesContactsForEveryScheduler) {
  // A folded grid moving through itself, over three steps.
  const MeshData g = test::grid(24, 24);
  std::mt19937 rng(7);
  std::vector<Positions> frames;
  for (int i = 0; i < 4; ++i) frames.push_back(test::crumple(g.positions, rng, 0.02));
  std::vector<Triangle> faces;
  for (const Face& f : g.faces) faces.push_back({f[0], f[1], f[2]});
  const TriMesh mesh(Index(g.positions.size()), g.faces);
  CcdPipeline reference(mesh, single_cloth_body(mesh), contact_strategies(18, "sequential", 1, 0.0));
  struct {
    std::vector<Positions> frames;
  } seq{frames};
  for (const std::string& scheduler : test::bvtt_schedulers()) {
    Options o;
    o.scheduler = scheduler;
    o.threads = 2;
    Detector d(faces, o);
    std::size_t total = 0;
    for (std::size_t s = 0; s + 1 < seq.frames.size(); ++s) {
      const auto want = reference.step(seq.frames[s], seq.frames[s + 1]).contacts;
      const Detector::Contacts got = d.step(points(seq.frames[s]), points(seq.frames[s + 1]));
      ASSERT_EQ(got.vf.size() + got.ee.size(), want.size()) << scheduler << " step " << s;
      std::size_t vf = 0, ee = 0;
      for (const Contact& c : want) {
        const Detector::Contact& k = c.kind == ContactKind::vf ? got.vf[vf++] : got.ee[ee++];
        EXPECT_EQ(k.vertices[0], c.vertices[0]);
        EXPECT_EQ(k.vertices[3], c.vertices[3]);
        EXPECT_EQ(k.toi, c.toi);
        EXPECT_EQ(k.coords, c.coords);
        const double n = std::hypot(k.normal[0], k.normal[1], k.normal[2]);
        EXPECT_TRUE(n == 0 || std::abs(n - 1) < 1e-12);
      }
      total += want.size();
    }
    EXPECT_GT(total, 0u) << "the sequence must have contacts for the comparison to mean something";
  }
}

TEST(Api, BodiesWithAnObstacle) {
  // A cloth triangle falling through an obstacle triangle; the obstacle's own (crossing) pair is never tested.
  Detector::Body cloth{{{0, 1, 2}}, 3, false, true, "cloth"};
  Detector::Body floor{{{0, 1, 2}, {3, 4, 5}}, 6, true, true, "floor"};
  const std::vector<Detector::Body> bodies{cloth, floor};
  Detector d(bodies);
  const std::vector<Point> x0{{0.2, 0.2, 1}, {1.2, 0.2, 1}, {0.2, 1.2, 1},   // cloth
                              {-1, -1, 0}, {3, -1, 0}, {-1, 3, 0},         // floor
                              {-1, -1, 0.5}, {3, -1, -0.5}, {-1, 3, 0.5}};  // a second obstacle face through the first
  std::vector<Point> x1 = x0;
  for (int i = 0; i < 3; ++i) x1[i][2] = -1;
  const auto c = d.step(x0, x1);
  ASSERT_FALSE(c.vf.empty());
  for (const auto* list : {&c.vf, &c.ee})
    for (const Detector::Contact& k : *list) {
      bool touches_cloth = false;
      for (int v : k.vertices) touches_cloth |= v < 3;
      EXPECT_TRUE(touches_cloth) << "obstacle against obstacle reported";
    }
  EXPECT_NE(error_of([&] { (void)d.step(x0, std::vector<Point>(x1.begin(), x1.end() - 1)); }).find("ccdlab::Detector::step"), std::string::npos);
  Detector::Body bad{{{0, 1, 5}}, 3, false, true, "sheet"};
  EXPECT_NE(error_of([&] { Detector e(std::vector<Detector::Body>{bad}); }).find("sheet: faces[0]"), std::string::npos);
}

TEST(Api, ProximityIsTheQuerysForEveryScheduler) {
  const MeshData g = test::grid(16, 16);
  std::mt19937 rng(4);
  const Positions x = test::crumple(g.positions, rng, 0.02);
  std::vector<Triangle> faces;
  for (const Face& f : g.faces) faces.push_back({f[0], f[1], f[2]});
  const TriMesh mesh(Index(g.positions.size()), g.faces);
  ProximityQuery reference(mesh, single_cloth_body(mesh), contact_strategies(18, "sequential", 1, 0.0), 0.03);
  const ProximityResult want = reference.query(x);
  ASSERT_GT(want.pairs.size(), 20u);
  for (const std::string& scheduler : test::bvtt_schedulers()) {
    Options o;
    o.scheduler = scheduler, o.threads = 2;
    Detector d(faces, o);
    for (int call = 0; call < 2; ++call) {
      const Detector::Proximities got = d.proximity(points(x), 0.03);
      ASSERT_EQ(got.vf.size() + got.ee.size(), want.pairs.size()) << scheduler;
      std::size_t vf = 0, ee = 0;
      for (const ProximityPair& p : want.pairs) {
        const Detector::Proximity& k = p.kind == ContactKind::vf ? got.vf[vf++] : got.ee[ee++];
        EXPECT_EQ(k.vertices[0], p.vertices[0]);
        EXPECT_EQ(k.vertices[3], p.vertices[3]);
        EXPECT_EQ(k.distance, p.distance);
        EXPECT_EQ(k.type, to_string(p.type));
        EXPECT_LT(k.distance, 0.03 * (1 + 1e-9));
      }
    }
    EXPECT_TRUE(d.proximity(points(x), 1e-9).vf.empty()) << "a new dhat: a new query";
  }
  Detector d(faces);
  EXPECT_NE(error_of([&] { (void)d.proximity(points(x), 0); }).find("ccdlab::Detector::proximity: dhat = 0"), std::string::npos);
  EXPECT_NE(error_of([&] { (void)d.proximity(points(x), std::nan("")); }).find("dhat = nan"), std::string::npos);
  EXPECT_NE(error_of([&] { (void)d.proximity({points(x).data(), 5}, 0.1); }).find("x has 5 positions"), std::string::npos);
}

TEST(Api, ActiveSetAndStepKeepTheSeparation) {
  // A sheet 0.1 above a floor sheet, moving 0.2 down: with separation 0.01 it may go about (0.1 − 0.01) / 0.2 of
  // the step (never more); there it is still at least 0.01 from the floor, a little farther it is not.
  const MeshData g = test::grid(6, 6);
  std::vector<Triangle> tri;
  for (const Face& f : g.faces) tri.push_back({f[0], f[1], f[2]});
  const int n = int(g.positions.size());
  const std::vector<Detector::Body> bodies{{tri, n, false, false, "sheet"}, {tri, n, true, false, "floor"}};
  Detector d(bodies);
  std::vector<Point> x0, x1;
  for (const Vec3& p : g.positions) x0.push_back({p.x(), p.y(), 0.1}), x1.push_back({p.x(), p.y(), -0.1});
  for (const Vec3& p : g.positions) x0.push_back({p.x() - 0.05, p.y() - 0.05, 0}), x1.push_back({p.x() - 0.05, p.y() - 0.05, 0});
  const Detector::ActiveSetAndStep r = d.active_set_and_step(x0, x1, 0.15, 0.01);
  EXPECT_GT(r.active.vf.size() + r.active.ee.size(), 50u) << "the sheet is 0.1 above the floor, within 0.15";
  EXPECT_LE(r.step_size, 0.45);
  EXPECT_GT(r.step_size, 0.44);
  const auto at = [&](double t) {
    std::vector<Point> x = x0;
    for (std::size_t v = 0; v < x.size(); ++v)
      for (int i = 0; i < 3; ++i) x[v][i] += t * (x1[v][i] - x0[v][i]);
    return x;
  };
  const Detector::Proximities there = d.proximity(at(r.step_size), 0.01);
  EXPECT_EQ(there.vf.size() + there.ee.size(), 0u);
  const Detector::Proximities beyond = d.proximity(at(r.step_size + 0.01), 0.01);
  EXPECT_GT(beyond.vf.size() + beyond.ee.size(), 0u);
  EXPECT_EQ(d.active_set_and_step(x0, x0, 0.15, 0.01).step_size, 1.0) << "no motion: the whole step";
  EXPECT_NE(error_of([&] { (void)d.active_set_and_step(x0, x1, 0.15, -1); }).find("separation = -1"), std::string::npos);
}

TEST(Api, BadStepsAreRefusedNamingTheCall) {
  const std::vector<Triangle> faces{{0, 1, 2}, {1, 3, 2}};
  std::vector<Point> x0{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, x1 = x0;
  Detector d(faces);
  x1[3][2] = std::nan("");
  EXPECT_NE(error_of([&] { (void)d.step(x0, x1); }).find("ccdlab::Detector::step: x1[3]"), std::string::npos);
  x1 = x0;
  EXPECT_NO_THROW((void)d.step(x0, x1));
  x0.push_back({2, 2, 2}), x1.push_back({2, 2, 2});
  EXPECT_NE(error_of([&] { (void)d.step(x0, x1); }).find("4 vertices"), std::string::npos);
  const std::vector<Triangle> degenerate{{0, 1, 1}};
  Detector e(degenerate);
  EXPECT_NE(error_of([&] { (void)e.step({x0.data(), 3}, {x1.data(), 3}); }).find("ccdlab::Detector::step: face 0: degenerate"),
            std::string::npos);
  const std::vector<Triangle> out_of_range{{0, 1, 9}};
  Detector f(out_of_range);
  EXPECT_NE(error_of([&] { (void)f.step({x0.data(), 3}, {x1.data(), 3}); }).find("out of range"), std::string::npos);
  EXPECT_NE(error_of([] { (void)read_mesh(std::filesystem::path("/nonexistent/x.ply")); }).find("ccdlab::read_mesh: "), std::string::npos);
}

}  // namespace
}  // namespace ccdlab

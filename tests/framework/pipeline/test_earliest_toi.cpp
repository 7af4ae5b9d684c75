// The earliest-time query (CcdPipeline::earliest_toi, earliest_cut.hpp): bit for bit the minimum time of the
// full step's contacts, 1.0 when there are none, for every tester, scheduler, thread count and narrow mode —
// narrowed towards the exact time for the testers that tighten it (conservative within 1e-9, never later); it
// tests fewer pairs than the full step where contacts begin late; on the shared real steps too (skipped where
// ../shared/data is absent).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string_view>

#include "framework/mesh/mesh_io.hpp"
#include "framework/pipeline/ccd_pipeline.hpp"
#include "strategies/registry.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

PipelineStrategies strategies(const std::string& tester, const std::string& scheduler, int threads, NarrowMode mode,
                              double thickness = 0) {
  PipelineStrategies s = contact_strategies(18, scheduler, threads, 0.0);
  ParamValues params = tester_registry().find(tester)->defaults();
  if (thickness > 0) params.set("thickness", thickness);
  s.tester = tester_registry().make({tester, params});
  s.narrow.mode = mode;
  return s;
}

double min_toi(const StepResult& r) {
  double t = 1.0;
  for (const Contact& c : r.contacts) t = std::min(t, c.toi);
  return t;
}

/// A folded grid over four steps: contacts at various times, and one still step without any.
struct Sequence {
  MeshData grid = test::grid(20, 20);
  std::vector<Positions> frames;
  Sequence() {
    std::mt19937 rng(3);
    for (int i = 0; i < 4; ++i) frames.push_back(test::crumple(grid.positions, rng, 0.02));
    frames.push_back(frames.back());  // a step without motion
  }
};

/// Testers that narrow a hit's time for the earliest-time query (PrimitiveTester::tighten_toi).
bool tightens(std::string_view tester, double eta) { return (tester == "conservative" && eta == 0) || tester == "inclusion"; }

TEST(EarliestToi, EqualsTheFullStepsEarliestContactEverywhere) {
  const Sequence seq;
  const TriMesh mesh(Index(seq.grid.positions.size()), seq.grid.faces);
  // The exact earliest time of each step: what the narrowed times must approach from below.
  std::vector<double> exact;
  {
    CcdPipeline e(mesh, single_cloth_body(mesh), strategies("exact", "phc", 2, NarrowMode::batched));
    for (std::size_t s = 0; s + 1 < seq.frames.size(); ++s) exact.push_back(min_toi(e.step(seq.frames[s], seq.frames[s + 1])));
  }
  // At zero thickness for every scheduler; with a separation η (1/25 of an edge) for the testers that take one,
  // and the field's two methods, with phc ×2.
  for (const auto& [tester, eta] : {std::pair{"float", 0.0}, {"filtered", 0.0}, {"conservative", 0.0}, {"exact", 0.0},
                                    {"float", 0.002}, {"conservative", 0.002}, {"additive", 0.0}, {"inclusion", 0.0}})
    for (const NarrowMode mode : {NarrowMode::batched, NarrowMode::scalar}) {
      std::vector<double> first;  // the first scheduler's answers: every other must equal them
      for (const auto& [scheduler, threads] : {std::pair{"sequential", 1}, {"phc", 2}, {"front", 2}, {"static", 2}}) {
        const bool few = eta > 0 || std::string_view(tester) == "additive" || std::string_view(tester) == "inclusion";
        if (few && std::string_view(scheduler) != "phc") continue;
        CcdPipeline full(mesh, single_cloth_body(mesh), strategies(tester, scheduler, threads, mode, eta));
        CcdPipeline earliest(mesh, single_cloth_body(mesh), strategies(tester, scheduler, threads, mode, eta));
        int with_contacts = 0;
        for (std::size_t s = 0; s + 1 < seq.frames.size(); ++s) {
          const StepResult r = full.step(seq.frames[s], seq.frames[s + 1]);
          const double want = min_toi(r), got = earliest.earliest_toi(seq.frames[s], seq.frames[s + 1]);
          const std::string what = std::string(tester) + " eta " + std::to_string(eta) + " " + std::string(to_string(mode)) +
                                   " " + scheduler + " step " + std::to_string(s);
          if (tightens(tester, eta)) {
            // Narrowed: no earlier than the full step's lower bound, never later than the exact time.
            EXPECT_GE(got, want) << what;
            EXPECT_LE(got, exact[s]) << what;
            if (std::string_view(tester) == "conservative") {
              EXPECT_LE(exact[s] - got, 1e-9) << what;
            }
          } else {
            EXPECT_EQ(got, want) << what;
          }
          if (first.size() <= s) first.push_back(got);
          EXPECT_EQ(got, first[s]) << what << ": differs from the first scheduler's";
          with_contacts += !r.contacts.empty();
        }
        EXPECT_GE(with_contacts, 2) << "the sequence must have contacts for the comparison to mean something";
        // After an earliest-time query, a step is a whole one again.
        EXPECT_EQ(earliest.step(seq.frames[0], seq.frames[1]).contacts.size(), full.step(seq.frames[0], seq.frames[1]).contacts.size());
      }
    }
}

TEST(EarliestToi, SkipsPairsThatCannotBeatTheBestTime) {
  // Two sheets, the upper one tilted and falling through the lower: its points meet it from t = 0.5 (at x = 0) to
  // t = 1 (x = 1), so the pairs' first open windows spread over the second half and the cut spares most tests.
  const MeshData sheet = test::grid(16, 16);
  MeshData both = test::concat(sheet, sheet);
  Positions x0 = both.positions, x1 = both.positions;
  const std::size_t n = sheet.positions.size();
  for (std::size_t i = n; i < 2 * n; ++i) {
    x0[i].z() = 0.1 + 0.1 * x0[i].x();
    x1[i].z() = -0.1 + 0.1 * x1[i].x();
  }
  const TriMesh mesh(Index(x0.size()), both.faces);
  CcdPipeline full(mesh, single_cloth_body(mesh), strategies("float", "sequential", 1, NarrowMode::batched));
  CcdPipeline cut(mesh, single_cloth_body(mesh), strategies("float", "sequential", 1, NarrowMode::batched));
  const StepResult all = full.step(x0, x1);
  StepResult partial;
  EXPECT_EQ(cut.earliest_toi(x0, x1, &partial), min_toi(all));
  EXPECT_GT(min_toi(all), 0.45);
  const auto tests = [](const StepResult& r) { return r.counters.vf_tests + r.counters.ee_tests; };
  EXPECT_LT(2 * tests(partial), tests(all)) << tests(partial) << " of " << tests(all);
}

TEST(EarliestToi, SharedRealStepsAgreeWithTheirContacts) {
  const std::string root = test::shared_data();
  if (root.empty()) GTEST_SKIP() << "../shared/data not found: real steps skipped";
  for (const auto& [a, b] : {std::pair{"rod-twist/3036.ply", "rod-twist/3037.ply"}, {"cloth-funnel/227.ply", "cloth-funnel/228.ply"},
                             {"n-body-simulation/balls16_18.ply", "n-body-simulation/balls16_19.ply"}}) {
    const MeshData m0 = read_mesh(root + "/meshes/" + a), m1 = read_mesh(root + "/meshes/" + b);
    const TriMesh mesh(Index(m0.positions.size()), m0.faces);
    for (const char* tester : {"float", "exact"}) {
      CcdPipeline full(mesh, single_cloth_body(mesh), strategies(tester, "phc", 2, NarrowMode::batched));
      CcdPipeline cut(mesh, single_cloth_body(mesh), strategies(tester, "phc", 2, NarrowMode::batched));
      EXPECT_EQ(cut.earliest_toi(m0.positions, m1.positions), min_toi(full.step(m0.positions, m1.positions))) << a << " " << tester;
    }
    // `conservative` narrowed: within 1e-9 of exact's earliest time, never later.
    CcdPipeline exact(mesh, single_cloth_body(mesh), strategies("exact", "phc", 2, NarrowMode::batched));
    CcdPipeline conservative(mesh, single_cloth_body(mesh), strategies("conservative", "phc", 2, NarrowMode::batched));
    const double truth = exact.earliest_toi(m0.positions, m1.positions), got = conservative.earliest_toi(m0.positions, m1.positions);
    EXPECT_LE(got, truth) << a;
    EXPECT_LE(truth - got, 1e-9) << a;
  }
}

}  // namespace
}  // namespace ccdlab

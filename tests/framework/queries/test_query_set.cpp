// Reading the shared rational CSV query format: exact values, ground truth from the 7th column or the JSON
// beside `queries/`, and located errors for every kind of bad input.
#include <gtest/gtest.h>

#include <fstream>

#include "framework/queries/query_set.hpp"
#include "support/error_of.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

namespace fs = std::filesystem;

const char* kQuery7 =
    "0,1,0,1,1,1,0\n1,1,0,1,1,1,0\n0,1,1,1,1,1,0\n1,2,1,2,1,1,0\n"
    "0,1,0,1,1,1,0\n1,1,0,1,1,1,0\n0,1,1,1,1,1,0\n1,2,1,2,-1,1,0\n";

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

TEST(QuerySet, ReadsHandcraftedLayoutWithTruthColumn) {
  const fs::path dir = test::temp_dir("qs_hand");
  write(dir / "scene" / "edge-edge" / "data_0_0.csv", kQuery7);
  write(dir / "scene" / "edge-edge" / "data_0_1.csv", kQuery7);
  const auto sets = load_query_sets(dir);
  ASSERT_EQ(sets.size(), 1u);  // both files of one folder form one set
  EXPECT_EQ(sets[0].name, "scene/edge-edge");
  EXPECT_EQ(sets[0].kind, ContactKind::ee);
  ASSERT_EQ(sets[0].size(), 2u);
  EXPECT_EQ(sets[0].ee[0].eb1_t0, Vec3(0.5, 0.5, 1.0));
  EXPECT_EQ(sets[0].ee[0].eb1_t1, Vec3(0.5, 0.5, -1.0));
  EXPECT_NE(sets[0].origin[1].find("data_0_1.csv:1"), std::string::npos);
}

TEST(QuerySet, SetsAreNamedBySceneAndKindWhateverTheRoot) {
  const fs::path dir = test::temp_dir("qs_names");
  write(dir / "handcrafted" / "wedges" / "edge-edge" / "data_0_0.csv", kQuery7);
  for (const fs::path& root : {dir, dir / "handcrafted", dir / "handcrafted" / "wedges",
                               dir / "handcrafted" / "wedges" / "edge-edge",
                               dir / "handcrafted" / "wedges" / "edge-edge" / "data_0_0.csv"}) {
    const auto sets = load_query_sets(root);
    ASSERT_EQ(sets.size(), 1u) << root;
    EXPECT_EQ(sets[0].name, "wedges/edge-edge") << root;
    EXPECT_EQ(sets[0].scene, "wedges") << root;
    EXPECT_EQ(sets[0].collection, "handcrafted") << root;
  }
}

TEST(QuerySet, ReadsSimulationLayoutWithJsonTruth) {
  const fs::path dir = test::temp_dir("qs_sim");
  std::string six;
  for (int r = 0; r < 16; ++r) six += "3,4,-5,8,7,16\n";
  write(dir / "run" / "queries" / "12vf.csv", six);
  write(dir / "run" / "mma_bool" / "12vf_mma_bool.json", "[true, false]");
  const auto sets = load_query_sets(dir);
  ASSERT_EQ(sets.size(), 1u);
  EXPECT_EQ(sets[0].name, "run/12vf");
  EXPECT_EQ(sets[0].kind, ContactKind::vf);
  EXPECT_EQ(sets[0].truth, (std::vector<char>{1, 0}));
  EXPECT_EQ(sets[0].vf[1].f2_t1, Vec3(0.75, -0.625, 0.4375));
}

TEST(QuerySet, BadInputIsReportedWithFileLineAndColumn) {
  const fs::path dir = test::temp_dir("qs_bad");
  auto err = [&](const std::string& name, const std::string& text) {
    const fs::path p = dir / "edge-edge" / name;
    write(p, text);
    return test::error_of([&] { load_query_sets(p); });
  };
  const std::string f = (dir / "edge-edge").string() + "/";
  EXPECT_EQ(err("cols.csv", "1,1,1,1,1\n"), f + "cols.csv:1: expected 6 or 7 columns (x,y,z as num,den pairs [+ truth]), got 5");
  EXPECT_EQ(err("third.csv", "1,3,0,1,0,1,0\n"), f + "third.csv:1: column 1: 1/3 is not exactly representable as a double");
  EXPECT_EQ(err("zero.csv", "1,1,0,0,0,1,0\n"), f + "zero.csv:1: column 3: denominator: expected a non-zero integer, got 0");
  EXPECT_EQ(err("word.csv", "1,1,x,1,0,1,0\n"), f + "word.csv:1: column 3: numerator: expected an integer, got 'x'");
  const std::string q7 = kQuery7;
  std::size_t cut = 0;
  for (int line = 0; line < 4; ++line) cut = q7.find('\n', cut) + 1;
  EXPECT_EQ(err("trunc.csv", q7.substr(0, cut)),
            f + "trunc.csv: truncated: the last query has 4 of its 8 rows (query 1 starts at line 1)");
  std::string mixed = kQuery7;
  mixed[mixed.size() - 2] = '1';
  EXPECT_EQ(err("mixed.csv", mixed), f + "mixed.csv:8: column 7 (ground truth): differs from the query's first row");
  std::string six;
  for (int r = 0; r < 8; ++r) six += "1,1,0,1,0,1\n";
  write(dir / "s" / "queries" / "1ee.csv", six);
  EXPECT_NE(test::error_of([&] { load_query_sets(dir / "s" / "queries" / "1ee.csv"); }).find("no ground truth"), std::string::npos);
  write(dir / "s" / "mma_bool" / "1ee_mma_bool.json", "[true, true]");
  EXPECT_NE(test::error_of([&] { load_query_sets(dir / "s" / "queries" / "1ee.csv"); }).find("2 answers for the 1 queries"),
            std::string::npos);
  EXPECT_EQ(test::error_of([&] { load_query_sets(dir / "nothing-here"); }), (dir / "nothing-here").string() + ": no such file or directory");
}

}  // namespace
}  // namespace ccdlab

#include <gtest/gtest.h>

#include "framework/util/error.hpp"
#include "strategies/scenes/drape_fold_scene.hpp"
#include "support/error_of.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::error_of;

TEST(FramePattern, ExpandsPrintfPatterns) {
  EXPECT_EQ(expand_frame_pattern("d/%03d.ply", 8, 10), (std::vector<std::string>{"d/008.ply", "d/009.ply", "d/010.ply"}));
  EXPECT_EQ(expand_frame_pattern("f%d.obj", 227, 228), (std::vector<std::string>{"f227.obj", "f228.obj"}));
  EXPECT_NE(error_of([] { expand_frame_pattern("d/frame.ply", 0, 1); }).find("one %d"), std::string::npos);
  EXPECT_NE(error_of([] { expand_frame_pattern("d/%s.ply", 0, 1); }).find("%d"), std::string::npos);
}

TEST(FrameFiles, MismatchedFramesAreNamed) {
  auto dir = test::temp_dir("frames");
  MeshData g = test::grid(3, 3);
  write_ply((dir / "000.ply").string(), g.positions, g.faces);
  write_ply((dir / "001.ply").string(), g.positions, g.faces);
  Positions fewer(g.positions.begin(), g.positions.end() - 1);
  std::vector<Face> fewer_faces;
  for (Face f : g.faces)
    if (f[0] < Index(fewer.size()) && f[1] < Index(fewer.size()) && f[2] < Index(fewer.size())) fewer_faces.push_back(f);
  write_ply((dir / "002.ply").string(), fewer, fewer_faces);
  std::vector<Face> swapped = g.faces;
  std::swap(swapped[4], swapped[5]);
  write_ply((dir / "003.ply").string(), g.positions, swapped);

  // Every frame is checked when the sequence is loaded, before any step: the first bad one is named.
  MeshSequence seq = load_frame_files(expand_frame_pattern((dir / "%03d.ply").string(), 0, 1));
  EXPECT_EQ(seq.num_frames(), 2);
  EXPECT_EQ(seq.num_steps(), 1);
  EXPECT_EQ(seq.frame_label(1), "001");
  EXPECT_EQ(seq.frame(1).size(), g.positions.size());
  EXPECT_EQ(error_of([&] { (void)load_frame_files(expand_frame_pattern((dir / "%03d.ply").string(), 0, 3)); }),
            (dir / "002.ply").string() + ": frame 2 has 15 vertices, expected 16 (as in " + (dir / "000.ply").string() + ")");
  const std::vector<std::string> swapped_last{(dir / "000.ply").string(), (dir / "001.ply").string(), (dir / "003.ply").string()};
  const std::string e = error_of([&] { (void)load_frame_files(swapped_last); });
  EXPECT_NE(e.find("003.ply: frame 2: faces differ from"), std::string::npos) << e;
  EXPECT_NE(e.find("first difference at face 4"), std::string::npos) << e;
  std::filesystem::create_directories(dir / "folder.ply");
  EXPECT_EQ(error_of([&] { (void)load_frame_files({(dir / "000.ply").string(), (dir / "folder.ply").string()}); }),
            (dir / "folder.ply").string() + ": cannot open file (it is a directory, expected a file)");
}

TEST(DrapeFoldScene, SizeBodiesAndDeterminism) {
  DrapeFoldParams p;
  p.resolution = 20;
  p.frames = 5;
  MeshSequence s = make_drape_fold_scene(p);
  ASSERT_EQ(s.bodies().size(), 2u);
  EXPECT_EQ(s.bodies()[0].face_end, 2 * 20 * 20);
  EXPECT_EQ(s.bodies()[1].kind, BodyKind::obstacle);
  EXPECT_EQ(s.topology().num_components(), 2);
  EXPECT_EQ(s.num_frames(), 5);
  EXPECT_EQ(s.frame(3), s.frame(3));
  EXPECT_NE(s.frame(1), s.frame(3));
  // Effects a scene does not ask for are not there: no sphere body, a flat still sheet.
  p.sphere_radius = 0;
  p.fold_deg = 0;
  p.wrinkle = 0;
  MeshSequence flat = make_drape_fold_scene(p);
  ASSERT_EQ(flat.bodies().size(), 1u);
  EXPECT_EQ(flat.frame(0), flat.frame(4));
  for (const Vec3& x : flat.frame(2)) EXPECT_EQ(x.z(), 0.0);
}

TEST(DrapeFoldScene, DefaultRunIsBigEnough) {
  DrapeFoldParams p;  // what experiments/configs/default.yaml uses
  EXPECT_GE(2 * p.resolution * p.resolution, 20000);
}

}  // namespace
}  // namespace ccdlab

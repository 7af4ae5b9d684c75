#include <gtest/gtest.h>

#include <fstream>

#include "framework/util/error.hpp"
#include "support/error_of.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::error_of;

void write_text(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

class MeshIo : public ::testing::Test {
 protected:
  std::filesystem::path dir = test::temp_dir("mesh_io");
  MeshData mesh = [] {
    MeshData g = test::grid(3, 2);
    for (auto& p : g.positions) p += Vec3(0.1234567890123, -7.25, 1e-3 * p.x());
    return g;
  }();
};

TEST_F(MeshIo, PlyRoundTripsInEveryEncoding) {
  for (auto enc : {PlyEncoding::ascii, PlyEncoding::binary_little_endian, PlyEncoding::binary_big_endian})
    for (bool dbl : {true, false}) {
      auto path = (dir / "m.ply").string();
      write_ply(path, mesh.positions, mesh.faces, enc, dbl);
      MeshData back = read_ply(path);
      ASSERT_EQ(back.faces, mesh.faces);
      ASSERT_EQ(back.positions.size(), mesh.positions.size());
      for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        Vec3 expect = dbl ? mesh.positions[i] : mesh.positions[i].cast<float>().cast<double>();
        EXPECT_EQ(back.positions[i], expect) << "encoding " << int(enc) << " double " << dbl << " vertex " << i;
      }
    }
}

TEST_F(MeshIo, ObjRoundTripsExactly) {
  auto path = (dir / "m.obj").string();
  write_obj(path, mesh.positions, mesh.faces);
  MeshData back = read_mesh(path);
  EXPECT_EQ(back.faces, mesh.faces);
  EXPECT_EQ(back.positions, mesh.positions);  // shortest round-trip formatting
}

TEST_F(MeshIo, ObjPolygonsSlashesAndNegativeIndices) {
  auto path = (dir / "q.obj").string();
  write_text(path, "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\nf -4 -2 -1\n");
  MeshData m = read_obj(path);
  ASSERT_EQ(m.faces.size(), 3u);
  EXPECT_EQ(m.faces[0], (Face{0, 1, 2}));
  EXPECT_EQ(m.faces[1], (Face{0, 2, 3}));
  EXPECT_EQ(m.faces[2], (Face{0, 2, 3}));
}

TEST_F(MeshIo, TruncatedBinaryPlyNamesTheElement) {
  auto path = (dir / "t.ply").string();
  write_ply(path, mesh.positions, mesh.faces, PlyEncoding::binary_little_endian, true);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 7);
  EXPECT_EQ(error_of([&] { read_ply(path); }).rfind(path + ": element face 11: file truncated", 0), 0u)
      << error_of([&] { read_ply(path); });
}

TEST_F(MeshIo, TruncatedAsciiPlyNamesTheLine) {
  auto path = (dir / "t.ply").string();
  write_text(path, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1\n");
  EXPECT_EQ(error_of([&] { read_ply(path); }), path + ":12: element vertex 2: file truncated, property z missing");
}

TEST_F(MeshIo, NanAndInfAreRejectedWithTheirLocation) {
  auto ply = (dir / "n.ply").string();
  write_text(ply, "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(error_of([&] { read_ply(ply); }), ply + ":11: element vertex 1: non-finite coordinate (1 nan 0)");
  auto obj = (dir / "n.obj").string();
  write_text(obj, "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(error_of([&] { read_obj(obj); }), obj + ":2: vertex 1: non-finite coordinate (1 0 inf)");
  // Binary NaN too.
  Positions bad = mesh.positions;
  bad[4].y() = std::numeric_limits<double>::quiet_NaN();
  auto bin = (dir / "n_bin.ply").string();
  write_ply(bin, bad, mesh.faces);
  EXPECT_EQ(error_of([&] { read_ply(bin); }).rfind(bin + ": element vertex 4: non-finite", 0), 0u);
}

TEST_F(MeshIo, IndexOutOfRangeAndBadTokens) {
  auto obj = (dir / "r.obj").string();
  write_text(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  EXPECT_EQ(error_of([&] { read_obj(obj); }), obj + ":4: face: vertex index 3 out of range [0, 3)");
  write_text(obj, "v 0 0 0\nv 1 zero 0\n");
  EXPECT_EQ(error_of([&] { read_obj(obj); }), obj + ":2: y: expected a number, got 'zero'");
  auto ply = (dir / "r.ply").string();
  write_text(ply, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n");
  EXPECT_EQ(error_of([&] { read_ply(ply); }), ply + ":13: element face 0: vertex index 9 out of range [0, 3)");
}

TEST_F(MeshIo, MalformedHeadersAndFormats) {
  auto ply = (dir / "h.ply").string();
  write_text(ply, "ply\nformat binary_middle_endian 1.0\nend_header\n");
  EXPECT_EQ(error_of([&] { read_ply(ply); }),
            ply + ":2: format: expected ascii, binary_little_endian or binary_big_endian, got 'binary_middle_endian'");
  write_text(ply, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n");
  EXPECT_EQ(error_of([&] { read_ply(ply); }), ply + ":4: header truncated (no end_header)");
  write_text(ply, "not a ply\n");
  EXPECT_EQ(error_of([&] { read_ply(ply); }), ply + ":1: not a PLY file (first line must be 'ply', got 'not a ply')");
  write_text((dir / "x.stl").string(), "solid x\n");
  EXPECT_EQ(error_of([&] { read_mesh((dir / "x.stl").string()); }),
            (dir / "x.stl").string() + ": unknown mesh format '.stl', expected .obj or .ply");
  EXPECT_EQ(error_of([&] { read_mesh((dir / "absent.ply").string()); }),
            (dir / "absent.ply").string() + ": cannot open file (no such file)");
  EXPECT_EQ(error_of([&] { read_mesh(dir.string()); }), dir.string() + ": cannot open file (it is a directory, expected a file)");
  // A header's counts are claims: checked against the file's size before anything is allocated.
  write_text(ply, "ply\nformat ascii 1.0\nelement vertex 4000000000000\nproperty float x\nproperty float y\n"
                  "property float z\nend_header\n0 0 0\n");
  EXPECT_EQ(error_of([&] { read_ply(ply); }),
            ply + ": element vertex 4000000000000: the header declares more items than the file can hold (6 bytes after "
                  "the header, at least 2 per item)");
}

}  // namespace
}  // namespace ccdlab

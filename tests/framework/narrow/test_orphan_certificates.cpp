// Orphan certificates (orphan_certificates.hpp): a block's budget loses what the block bent, not its
// translation, nor a step backwards.
#include <gtest/gtest.h>

#include <limits>

#include "framework/narrow/narrow_phase.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

TEST(OrphanCertificates, ABudgetLosesTheBlocksBendingNotItsTranslationNorAStepBackwards) {
  // One block: a vertex and a face of a 3×3 grid, 0.5 apart in x; its budget as if it was measured at 0.4.
  MeshData g = test::grid(3, 3);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  OrphanSet set;
  set.vf.push_back({0, mesh.num_faces() - 1});
  OrphanCertificates cert(set, mesh);
  ASSERT_EQ(cert.blocks(), 1u);
  const Positions x0 = g.positions;
  Positions x1 = x0;
  for (Vec3& p : x1) p.z() += 0.01;
  cert.begin_step(x0, x1, 0);
  EXPECT_FALSE(cert.holds(0));  // the first step: nothing measured
  cert.certify(0, 0.4f);
  EXPECT_TRUE(cert.holds(0));
  auto moved = [](Positions x, const Vec3& by, Index only = -1) {
    for (std::size_t v = 0; v < x.size(); ++v)
      if (only < 0 || Index(v) == only) x[v] += by;
    return x;
  };
  cert.begin_step(moved(x0, {0.3, 0.2, 1}), moved(x1, {0.3, 0.2, 1}), 0);  // the whole mesh translated
  EXPECT_TRUE(cert.holds(0));
  cert.begin_step(moved(x1, {0.3, 0.2, 1}), moved(x0, {0.3, 0.2, 1}), 0);  // the same step backwards
  EXPECT_TRUE(cert.holds(0));
  cert.begin_step(moved(x1, {0.3, 0.2, 1}, 0), moved(x0, {0.3, 0.2, 1}), 0);  // vertex 0 alone moves by 0.1
  EXPECT_FALSE(cert.holds(0));  // 0.4 − |(0.3, 0.2, 1)| < 0
  cert.certify(0, 0.4f);
  cert.begin_step(moved(x1, {0.3, 0.2, 1}, 0), moved(x0, {0.3, 0.2, 1}), 0);  // unmoved since
  EXPECT_TRUE(cert.holds(0));
  cert.begin_step(moved(x1, {0.3, 0.2, 1.3}, 0), moved(x0, {0.3, 0.2, 1}), 0);  // bent by 0.3: 0.1 left
  EXPECT_TRUE(cert.holds(0));
  cert.begin_step(moved(x1, {0.3, 0.2, 1.45}, 0), moved(x0, {0.3, 0.2, 1}), 0);  // 0.15 more: spent
  EXPECT_FALSE(cert.holds(0));
  cert.certify(0, 0.4f);
  Positions nan = moved(x1, {0.3, 0.2, 1.45}, 0);
  nan[5].x() = std::numeric_limits<double>::quiet_NaN();
  cert.begin_step(nan, moved(x0, {0.3, 0.2, 1}), 0);  // a NaN anywhere: nothing holds
  EXPECT_FALSE(cert.holds(0));
  cert.certify(0, -0.1f);  // a block with an overlapping pair never holds
  cert.begin_step(moved(x1, {0.3, 0.2, 1.45}, 0), moved(x0, {0.3, 0.2, 1}), 0);
  EXPECT_FALSE(cert.holds(0));
}

}  // namespace CCDLAB_UNITY_ID
}  // namespace ccdlab

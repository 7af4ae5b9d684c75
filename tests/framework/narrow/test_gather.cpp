// The gather (narrow_phase.hpp, gather_simd.cpp): the SIMD gather writes the plain loop's pairs, in its order,
// on every target.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "framework/narrow/narrow_phase.hpp"
#include "support/simd_targets.hpp"
#include "support/test_meshes.hpp"

namespace ccdlab {
namespace CCDLAB_UNITY_ID {  // a namespace of this file's own (tests/CMakeLists.txt)

using test::for_each_simd_target;

TEST(Gather, SimdGatherWritesThePlainLoopsPairsInItsOrderOnEveryTarget) {
  MeshData g = test::grid(14, 11);
  TriMesh mesh(Index(g.positions.size()), g.faces);
  const Representatives reps(mesh, RepresentativeRule::fixed, [](Index) { return true; });
  // Every non-adjacent face pair, in a shuffled order: all owner combinations the grid has, both orders of ids.
  std::vector<FacePair> candidates;
  for (Index f = 0; f < mesh.num_faces(); ++f)
    for (Index h = 0; h < mesh.num_faces(); ++h)
      if (f != h && !mesh.faces_adjacent(f, h)) candidates.push_back({f, h});
  std::mt19937 rng(3);
  std::shuffle(candidates.begin(), candidates.end(), rng);
  std::set<unsigned> combinations;
  for (const FacePair& p : candidates)
    combinations.insert(unsigned(reps.owners().owned_mask[p.a]) | unsigned(reps.owners().owned_mask[p.b]) << 6);
  EXPECT_GT(combinations.size(), 60u);
  const std::vector<VertexFacePair> vf_before = {{1, 2}, {3, 4}};  // appended to, not replaced
  const std::vector<EdgeEdgePair> ee_before = {{5, 6}};
  auto gather = [&](std::span<const FacePair> c, bool simd) {
    FeatureBatch b;
    b.vf.insert(b.vf.end(), vf_before.begin(), vf_before.end());
    b.ee.insert(b.ee.end(), ee_before.begin(), ee_before.end());
    reps.append_pairs(c, b.vf, b.ee, simd);
    return std::pair(std::vector<VertexFacePair>(b.vf.begin(), b.vf.end()), std::vector<EdgeEdgePair>(b.ee.begin(), b.ee.end()));
  };
  const auto expect = gather(candidates, false);
  EXPECT_GT(expect.first.size(), candidates.size());
  for_each_simd_target([&](const char* target) {
    EXPECT_EQ(gather(candidates, true), expect) << target;
    for (std::size_t n : {0, 1, 7}) EXPECT_EQ(gather(std::span(candidates).first(n), true), gather(std::span(candidates).first(n), false)) << target;
  });
}

}  // namespace CCDLAB_UNITY_ID
}  // namespace ccdlab

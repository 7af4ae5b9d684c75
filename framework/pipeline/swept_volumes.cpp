#include "framework/pipeline/swept_volumes.hpp"

#include "framework/util/error.hpp"

namespace ccdlab {

namespace {

/// An empty Array<KDop<k>> in the variant `Any`: the one dispatch from a run-time K to the k-DOP types.
template <class Any, template <class> class Array>
Any empty_for_k(int k) {
  switch (k) {
    case 6: return Array<KDop<6>>{};
    case 14: return Array<KDop<14>>{};
    case 18: return Array<KDop<18>>{};
    case 26: return Array<KDop<26>>{};
  }
  fail("bv.k: expected one of {}, got {}", kKdopKs, k);
}

}  // namespace

AnyBvs make_bvs(int k) { return empty_for_k<AnyBvs, BvArray>(k); }
AnyWideBvs make_wide_bvs(int k) { return empty_for_k<AnyWideBvs, WideBvs>(k); }

void compute_face_bvs(const TriMesh& mesh, const Positions& x0, const Positions& x1, double thickness, AnyBvs& out,
                      int threads, PhaseTrace* trace) {
  PhaseTrace unused;
  FeatureBounds vertex_dops;
  vertex_dops.update(x0, x1, thickness, threads, trace ? *trace : unused);
  std::visit(
      [&](auto& bvs) {
        using BV = typename std::decay_t<decltype(bvs)>::value_type;
        bvs.resize(mesh.num_faces());
        const SweptFaceBv<BV> swept{mesh, vertex_dops};
        parallel_chunks(std::size_t(mesh.num_faces()), kFaceChunk, threads, trace ? *trace : unused,
                        [&](std::size_t b, std::size_t e, int) {
                          for (std::size_t f = b; f < e; ++f) bvs[f] = swept(Index(f));
                        });
      },
      out);
}

std::vector<EndBoxes> compute_face_end_boxes(const TriMesh& mesh, const Positions& x0, const Positions& x1,
                                             double thickness, const CullReach& reach) {
  PhaseTrace unused;
  FeatureBounds vertex_dops;
  vertex_dops.update(x0, x1, thickness, 1, unused);
  const double r = end_boxes_reach(reach.abs, reach.rel, vertex_dops.scene_extent()) / 2;
  std::vector<EndBoxes> out(std::size_t(mesh.num_faces()));
  for (Index f = 0; f < mesh.num_faces(); ++f) out[std::size_t(f)] = face_end_boxes(vertex_dops.frame_points(), mesh.face(f), r);
  return out;
}

}  // namespace ccdlab

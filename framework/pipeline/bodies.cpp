#include "framework/pipeline/bodies.hpp"

#include "framework/util/error.hpp"

namespace ccdlab {

CollisionRules::CollisionRules(const TriMesh& mesh, std::vector<Body> bodies) : bodies_(std::move(bodies)) {
  body_of_face_.assign(mesh.num_faces(), -1);
  body_of_vertex_.assign(mesh.num_vertices(), -1);
  for (int b = 0; b < int(bodies_.size()); ++b) {
    const Body& body = bodies_[b];
    for (Index f = body.face_begin; f < body.face_end; ++f) body_of_face_[f] = b;
    for (Index v = body.vertex_begin; v < body.vertex_end; ++v) body_of_vertex_[v] = b;
  }
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    if (body_of_face_[f] < 0) fail("bodies: face {} belongs to no body", f);
    for (Index v : mesh.face(f))
      if (body_of_vertex_[v] != body_of_face_[f]) fail("bodies: face {} uses vertex {} of another body", f, v);
  }
}

std::vector<Body> single_cloth_body(const TriMesh& mesh) {
  return {Body{"mesh", BodyKind::cloth, true, 0, mesh.num_vertices(), 0, mesh.num_faces()}};
}

}  // namespace ccdlab

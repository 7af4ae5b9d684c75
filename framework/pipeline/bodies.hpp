#pragma once
// Bodies of a scene and which of their feature pairs may collide. A scene's meshes are concatenated into one
// topology (one id space for vertices, edges and faces); a Body is a contiguous range of it.
//   cloth    : deforming; tested against itself when self_collision is on, and against every other body
//   obstacle : moving or still, never tested against itself nor against other obstacles
#include <string>
#include <vector>

#include "framework/mesh/tri_mesh.hpp"

namespace ccdlab {

enum class BodyKind { cloth, obstacle };

struct Body {
  std::string name;
  BodyKind kind = BodyKind::cloth;
  bool self_collision = true;
  Index vertex_begin = 0, vertex_end = 0;  ///< [begin, end) in the concatenated topology
  Index face_begin = 0, face_end = 0;
};

/// Answers "may these two faces / features collide?" for a concatenated scene.
class CollisionRules {
 public:
  CollisionRules(const TriMesh& mesh, std::vector<Body> bodies);

  [[nodiscard]] const std::vector<Body>& bodies() const { return bodies_; }
  [[nodiscard]] int body_of_face(Index f) const { return body_of_face_[f]; }
  [[nodiscard]] int body_of_vertex(Index v) const { return body_of_vertex_[v]; }
  /// Whether features of body i may collide with features of body j (i == j: self-collision).
  [[nodiscard]] bool bodies_interact(int i, int j) const {
    if (i == j) return bodies_[i].kind == BodyKind::cloth && bodies_[i].self_collision;
    return bodies_[i].kind == BodyKind::cloth || bodies_[j].kind == BodyKind::cloth;
  }
  /// Candidate-pair rule of the broad phase: interacting bodies and, within one body, not adjacent.
  [[nodiscard]] bool faces_may_collide(const TriMesh& mesh, Index fa, Index fb) const {
    int i = body_of_face_[fa], j = body_of_face_[fb];
    return bodies_interact(i, j) && (i != j || !mesh.faces_adjacent(fa, fb));
  }

 private:
  std::vector<Body> bodies_;
  std::vector<int> body_of_face_;
  std::vector<int> body_of_vertex_;
};

/// A single self-colliding cloth body spanning the whole mesh (what `ccdlab step` uses).
std::vector<Body> single_cloth_body(const TriMesh& mesh);

}  // namespace ccdlab

#pragma once
// What `ccdlab export` draws, each as a VtkGrid (framework/export/vtk_file.hpp):
//   mesh_grid      the triangles at one frame; per triangle its body and how many contacts of the step from
//                  that frame touch it (a VF contact touches its face and the triangles around its vertex, an
//                  EE contact the triangles around its two edges); per point the displacement over the step
//   bvh_level_grid the k-DOPs of one depth of a BVH, each drawn as its polyhedron (framework/geometry/
//                  kdop_polyhedron.hpp): a 6-DOP is a box, an 18-DOP a box with bevelled edges
//   front_grid     a BVTT front: each node (a pair of BVH nodes) as a line between the centres of its two
//                  volumes (a point for a self node), labelled kept / sprouted / pruned against the last front
//   contacts_grid  the contacts of a step at their time of contact: the contact point, and the features (the
//                  face for VF, both edges for EE) where they meet
#include <cstdint>
#include <vector>

#include "framework/export/vtk_file.hpp"
#include "framework/hierarchy/bvh.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/pipeline/bodies.hpp"
#include "framework/primitive/contact.hpp"
#include "framework/traversal/front/binary_front.hpp"
#include "framework/traversal/scheduler.hpp"

namespace ccdlab {

/// Contacts touching each face (see above).
std::vector<int> contacts_per_face(const TriMesh& mesh, const Contacts& contacts);

VtkGrid mesh_grid(const TriMesh& mesh, const std::vector<Body>& bodies, const Positions& x, const Positions& x_next,
                  const std::vector<int>& face_contacts);

/// Depth of every node of a BVH (root 0).
std::vector<int> node_depths(const BvhTopology& bvh);

/// The volumes of the nodes at `depth` (cell arrays: node, depth, leaf, body).
VtkGrid bvh_level_grid(const BvhTopology& bvh, const AnyBvs& bvs, int depth, int body);

/// How a node of this step's front relates to the last step's front.
enum class FrontChange : std::uint8_t { kept = 0, sprouted = 1, pruned = 2 };

/// kept: in the last front too; sprouted: below a node of the last front (it opened); pruned: above nodes of
/// the last front (they merged back into it). `previous` empty: everything sprouted from the root.
std::vector<FrontChange> classify_front(const BvhTopology& bvh_a, const BvhTopology& bvh_b,
                                        const std::vector<FrontNode>& previous, const std::vector<FrontNode>& current);

/// Cell arrays: change (0 kept, 1 sprouted, 2 pruned), overlapping (the last test), depth_a, depth_b, self.
VtkGrid front_grid(const BvhTopology& bvh_a, const AnyBvs& bvs_a, const BvhTopology& bvh_b, const AnyBvs& bvs_b,
                   const std::vector<FrontNode>& nodes, const std::vector<FrontChange>& change);

/// Cell arrays: contact (index), kind (0 VF, 1 EE), toi, role (0 contact point, 1 feature).
VtkGrid contacts_grid(const Contacts& contacts, const Positions& x_t0, const Positions& x_t1);

}  // namespace ccdlab

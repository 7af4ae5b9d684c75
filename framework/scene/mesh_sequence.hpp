#pragma once
// MeshSequence: one topology (all bodies concatenated) and positions per frame; CCD step i = frame i → i+1.
// Frames are produced on demand by a FrameSource (a file reader or a procedural scene), so a long sequence
// never has to sit in memory; every frame is checked (vertex count, finite coordinates) when produced.
#include <functional>
#include <string>
#include <vector>

#include "framework/geometry/vec.hpp"
#include "framework/mesh/tri_mesh.hpp"
#include "framework/pipeline/bodies.hpp"

namespace ccdlab {

class MeshSequence {
 public:
  using FrameSource = std::function<Positions(int frame)>;

  MeshSequence(TriMesh topology, std::vector<Body> bodies, std::vector<std::string> frame_labels, FrameSource source,
               std::string description);

  [[nodiscard]] const TriMesh& topology() const { return topology_; }
  [[nodiscard]] const std::vector<Body>& bodies() const { return bodies_; }
  [[nodiscard]] int num_frames() const { return int(labels_.size()); }
  [[nodiscard]] int num_steps() const { return std::max(0, num_frames() - 1); }
  /// Label of a frame for reports (file name stem or frame number).
  [[nodiscard]] const std::string& frame_label(int frame) const { return labels_[frame]; }
  [[nodiscard]] const std::string& description() const { return description_; }
  /// Positions of frame i; throws Error naming the frame when they do not fit the topology.
  [[nodiscard]] Positions frame(int i) const;

 private:
  TriMesh topology_;
  std::vector<Body> bodies_;
  std::vector<std::string> labels_;
  FrameSource source_;
  std::string description_;
};

/// Step `step` (frame step → step + 1) of `sequence`, replayed: frames step, step + 1, step, … (`frames` of them),
/// every other step backwards. A steady simulation's later steps in miniature: the same pairs and contacts
/// every step, the BVH and the front warm after the first. Throws Error when the step is not one of the sequence's.
MeshSequence replay_step(MeshSequence sequence, int step, int frames);

/// "dir/%03d.ply" with first..last → the file names (printf-style integer pattern, exactly one %d).
std::vector<std::string> expand_frame_pattern(const std::string& pattern, int first, int last);

/// One body of a scene read from files: its frames (one file per frame, or one file for a body that never
/// moves) and its flags. A kinematic body is an obstacle: its motion is given, it is never tested against itself
/// nor against other kinematic bodies (bodies.hpp).
struct BodyFiles {
  std::string name = "mesh";
  std::vector<std::string> files;
  bool self_collision = true;
  bool kinematic = false;
};

/// A sequence read from mesh files (OBJ or PLY): the bodies' meshes concatenated, in order, into one topology.
/// Each body's first file defines its topology; every later file must have the same vertex count and the same
/// faces, else Error names it. Bodies with more than one file must all have the same number of frames. Every
/// file is read and checked once here, before any step; frames are read again on demand.
MeshSequence load_body_files(const std::vector<BodyFiles>& bodies);
/// One self-colliding cloth body (`scene: {frames: …}`).
MeshSequence load_frame_files(const std::vector<std::string>& files, bool self_collision = true);

}  // namespace ccdlab

#include "framework/scene/mesh_sequence.hpp"

#include <cstdio>
#include <filesystem>
#include <algorithm>
#include <memory>

#include "framework/mesh/mesh_io.hpp"
#include "framework/util/error.hpp"

namespace ccdlab {

MeshSequence::MeshSequence(TriMesh topology, std::vector<Body> bodies, std::vector<std::string> frame_labels,
                           FrameSource source, std::string description)
    : topology_(std::move(topology)),
      bodies_(std::move(bodies)),
      labels_(std::move(frame_labels)),
      source_(std::move(source)),
      description_(std::move(description)) {}

Positions MeshSequence::frame(int i) const {
  if (i < 0 || i >= num_frames()) fail("frame {}: out of range [0, {})", i, num_frames());
  Positions x = source_(i);
  if (Index(x.size()) != topology_.num_vertices())
    fail("frame {} ({}): {} vertices, expected {}", i, labels_[i], x.size(), topology_.num_vertices());
  for (std::size_t v = 0; v < x.size(); ++v)
    if (!x[v].allFinite()) fail("frame {} ({}): vertex {}: non-finite coordinate", i, labels_[i], v);
  return x;
}

MeshSequence replay_step(MeshSequence sequence, int step, int frames) {
  if (step < 0 || step >= sequence.num_steps())
    fail("replay.step: expected 0 … {} (the steps of {}), got {}", sequence.num_steps() - 1, sequence.description(), step);
  if (frames < 2) fail("replay.frames: expected at least 2, got {}", frames);
  auto base = std::make_shared<const MeshSequence>(std::move(sequence));
  std::vector<std::string> labels;
  for (int i = 0; i < frames; ++i) labels.push_back(base->frame_label(step + i % 2));
  return MeshSequence(base->topology(), base->bodies(), std::move(labels),
                      [base, step](int i) { return base->frame(step + i % 2); },
                      fmt::format("{}, step {} replayed", base->description(), step));
}

std::vector<std::string> expand_frame_pattern(const std::string& pattern, int first, int last) {
  auto pct = pattern.find('%');
  if (pct == std::string::npos || pattern.find('%', pct + 1) != std::string::npos)
    fail("scene.frames: expected a pattern with one %d (e.g. frames/%03d.ply), got '{}'", pattern);
  std::size_t conv = pattern.find_first_not_of("0123456789", pct + 1);
  if (conv == std::string::npos || pattern[conv] != 'd')
    fail("scene.frames: expected a %d or %0Nd conversion, got '{}'", pattern);
  if (last < first) fail("scene.last: expected >= first ({}), got {}", first, last);
  std::vector<std::string> files;
  for (int i = first; i <= last; ++i) {
    int n = std::snprintf(nullptr, 0, pattern.c_str(), i);
    std::string s(std::size_t(n), '\0');
    std::snprintf(s.data(), s.size() + 1, pattern.c_str(), i);
    files.push_back(std::move(s));
  }
  return files;
}

MeshSequence load_frame_files(const std::vector<std::string>& files, bool self_collision) {
  return load_body_files({BodyFiles{"mesh", files, self_collision, false}});
}

MeshSequence load_body_files(const std::vector<BodyFiles>& bodies) {
  if (bodies.empty()) fail("scene.bodies: expected at least one body");
  int frames = 1;
  for (const BodyFiles& b : bodies) {
    if (b.files.empty()) fail("scene.bodies: body '{}' has no frames", b.name);
    if (b.files.size() > 1) {
      if (frames > 1 && int(b.files.size()) != frames)
        fail("scene.bodies: body '{}' has {} frames, an earlier body has {} (every moving body needs one file per frame)",
             b.name, b.files.size(), frames);
      frames = int(b.files.size());
    }
  }
  if (frames < 2) fail("scene.frames: a sequence needs at least 2 frames, got {}", frames);

  // Topology: each body's first file, concatenated (vertex ids offset by the bodies before it).
  struct Part {
    std::vector<std::string> files;
    std::vector<Face> faces;  ///< local vertex ids
    Index vertices = 0, vertex_begin = 0;
    std::shared_ptr<Positions> first;
  };
  auto parts = std::make_shared<std::vector<Part>>();
  std::vector<Face> all_faces;
  std::vector<Body> body_list;
  Index vertices = 0;
  for (const BodyFiles& b : bodies) {
    MeshData m = read_mesh(b.files[0]);
    Part part{b.files, m.faces, Index(m.positions.size()), vertices, std::make_shared<Positions>(std::move(m.positions))};
    Body body{b.name, b.kinematic ? BodyKind::obstacle : BodyKind::cloth, b.self_collision && !b.kinematic, vertices,
              vertices + part.vertices, Index(all_faces.size()), Index(all_faces.size() + part.faces.size())};
    for (const Face& f : part.faces) all_faces.push_back({f[0] + vertices, f[1] + vertices, f[2] + vertices});
    vertices += part.vertices;
    body_list.push_back(body);
    parts->push_back(std::move(part));
  }
  TriMesh topology;
  try {
    topology = TriMesh(vertices, all_faces);
  } catch (const Error& e) {
    fail("{}: {}", bodies.size() == 1 ? bodies[0].files[0] : "scene.bodies", e.what());
  }
  auto read_part = [](const Part& p, int i) -> Positions {
    if (p.files.size() == 1 || i == 0) return *p.first;
    MeshData m = read_mesh(p.files[i]);
    if (m.positions.size() != p.first->size())
      fail("{}: frame {} has {} vertices, expected {} (as in {})", p.files[i], i, m.positions.size(), p.first->size(),
           p.files[0]);
    if (m.faces != p.faces) {
      std::size_t k = 0;
      while (k < m.faces.size() && k < p.faces.size() && m.faces[k] == p.faces[k]) ++k;
      fail("{}: frame {}: faces differ from {} (first difference at face {}; {} vs {} faces)", p.files[i], i, p.files[0],
           k, m.faces.size(), p.faces.size());
    }
    return std::move(m.positions);
  };
  auto source = [parts, read_part, vertices](int i) -> Positions {
    if (parts->size() == 1) return read_part(parts->front(), i);
    Positions x;
    x.reserve(std::size_t(vertices));
    for (const Part& p : *parts) {
      const Positions part = read_part(p, i);
      x.insert(x.end(), part.begin(), part.end());
    }
    return x;
  };
  // Every input is read and checked (format, counts, faces, finite coordinates) before the first step: a bad
  // frame 900 is reported now, not after hours of steps with a partial result left behind.
  for (const Part& p : *parts)
    for (int i = 1; i < int(p.files.size()); ++i) (void)read_part(p, i);
  const BodyFiles& lead = *std::max_element(bodies.begin(), bodies.end(), [](const BodyFiles& a, const BodyFiles& b) {
    return a.files.size() < b.files.size();
  });
  std::vector<std::string> labels;
  for (const auto& f : lead.files) labels.push_back(std::filesystem::path(f).stem().string());
  std::string desc = fmt::format("{} .. {} ({} frames)", lead.files.front(), lead.files.back(), frames);
  if (bodies.size() > 1) desc += fmt::format(", {} bodies", bodies.size());
  return MeshSequence(std::move(topology), std::move(body_list), std::move(labels), std::move(source), std::move(desc));
}

}  // namespace ccdlab

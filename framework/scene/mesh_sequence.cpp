#include "framework/scene/mesh_sequence.hpp"

#include <cstdio>
#include <filesystem>
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
  if (files.size() < 2) fail("scene.frames: a sequence needs at least 2 frames, got {}", files.size());
  MeshData first = read_mesh(files[0]);
  TriMesh topology;
  try {
    topology = TriMesh(first.positions.size(), first.faces);
  } catch (const Error& e) {
    fail("{}: {}", files[0], e.what());
  }
  auto faces = std::make_shared<std::vector<Face>>(first.faces);
  auto first_positions = std::make_shared<Positions>(std::move(first.positions));
  std::vector<std::string> labels;
  for (const auto& f : files) labels.push_back(std::filesystem::path(f).stem().string());
  auto source = [files, faces, first_positions](int i) -> Positions {
    if (i == 0) return *first_positions;
    MeshData m = read_mesh(files[i]);
    if (m.positions.size() != first_positions->size())
      fail("{}: frame {} has {} vertices, expected {} (as in {})", files[i], i, m.positions.size(),
           first_positions->size(), files[0]);
    if (m.faces != *faces) {
      std::size_t k = 0;
      while (k < m.faces.size() && k < faces->size() && m.faces[k] == (*faces)[k]) ++k;
      fail("{}: frame {}: faces differ from {} (first difference at face {}; {} vs {} faces)", files[i], i, files[0], k,
           m.faces.size(), faces->size());
    }
    return std::move(m.positions);
  };
  // Every input is read and checked (format, counts, faces, finite coordinates) before the first step: a bad
  // frame 900 is reported now, not after hours of steps with a partial result left behind.
  for (int i = 1; i < int(files.size()); ++i) (void)source(i);
  Body body{"mesh", BodyKind::cloth, self_collision, 0, topology.num_vertices(), 0, topology.num_faces()};
  std::string desc = fmt::format("{} .. {} ({} frames)", files.front(), files.back(), files.size());
  return MeshSequence(std::move(topology), {body}, std::move(labels), std::move(source), std::move(desc));
}

}  // namespace ccdlab

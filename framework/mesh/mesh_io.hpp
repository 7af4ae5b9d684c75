#pragma once
// Reading and writing triangle meshes: OBJ and PLY (ascii, binary little- and big-endian; float or double
// coordinates; any integer type for face lists). Polygons with more than 3 vertices are fan-triangulated.
// Every error names the file and the line (text formats) or the element (binary PLY).
#include <string>
#include <vector>

#include "framework/geometry/vec.hpp"
#include "framework/mesh/tri_mesh.hpp"

namespace ccdlab {

/// Positions and faces as read from one file, validated: finite coordinates, indices in range.
struct MeshData {
  Positions positions;
  std::vector<Face> faces;
};

enum class PlyEncoding { ascii, binary_little_endian, binary_big_endian };

/// Reads an .obj or .ply file (chosen by extension). Throws Error on any malformed input.
MeshData read_mesh(const std::string& path);
MeshData read_obj(const std::string& path);
MeshData read_ply(const std::string& path);
/// The same parsers on a file's content; `name` is used in errors (the path, or a label). For fuzzing and tests.
MeshData parse_obj(std::string text, const std::string& name);
MeshData parse_ply(std::string data, const std::string& name);

void write_obj(const std::string& path, const Positions& positions, const std::vector<Face>& faces);
void write_ply(const std::string& path, const Positions& positions, const std::vector<Face>& faces,
               PlyEncoding encoding = PlyEncoding::binary_little_endian, bool double_precision = true);

}  // namespace ccdlab

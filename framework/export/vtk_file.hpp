#pragma once
// VTK XML files for pictures (`ccdlab export`): an unstructured grid (.vtu) of points and mixed cells —
// vertices, lines, triangles, polygons — with named per-cell and per-point arrays, and a ParaView collection
// (.pvd) that makes a series of them (frames of a sequence, levels of a BVH) one time-stepped dataset.
// Written as ASCII XML: readable in an editor, opened by ParaView and by meshio (tested), small for the
// teaching meshes it is meant for. Files are written complete or not at all (OutputFile).
#include <cstdint>
#include <string>
#include <vector>

#include "framework/geometry/vec.hpp"

namespace ccdlab {

/// VTK cell types used here (values of vtkCellType.h).
enum class VtkCell : std::uint8_t { vertex = 1, line = 3, triangle = 5, polygon = 7 };

class VtkGrid {
 public:
  /// Appends a point; returns its index.
  int add_point(const Vec3& p);
  /// Appends a cell over existing point indices (2 for a line, 3 for a triangle, ≥ 3 for a polygon).
  void add_cell(VtkCell type, const std::vector<int>& points);
  /// Sets the value of a per-cell array for the last added cell (arrays are created on first use; cells
  /// added before hold 0).
  void set_cell_value(const std::string& array, double value);
  /// A per-point array, one value per point (checked when written).
  void set_point_array(const std::string& array, std::vector<double> values);

  [[nodiscard]] std::size_t num_points() const { return points_.size(); }
  [[nodiscard]] std::size_t num_cells() const { return types_.size(); }

  /// Writes the grid to `path` (.vtu); Error naming the path (and `what`, the option it came from).
  void write(const std::string& path, const std::string& what) const;

 private:
  struct Array {
    std::string name;
    std::vector<double> values;
  };
  std::vector<Vec3> points_;
  std::vector<std::int64_t> connectivity_, offsets_;
  std::vector<std::uint8_t> types_;
  std::vector<Array> cell_arrays_, point_arrays_;
};

/// One dataset of a series: the file (relative to the .pvd) and its time value (frame, level).
struct VtkSeriesEntry {
  double time;
  std::string file;
};

/// Writes a ParaView collection (.pvd) listing the entries.
void write_vtk_series(const std::string& path, const std::vector<VtkSeriesEntry>& entries, const std::string& what);

}  // namespace ccdlab

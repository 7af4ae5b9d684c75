#include "framework/export/vtk_file.hpp"

#include <fmt/format.h>

#include "framework/util/error.hpp"
#include "framework/util/files.hpp"

namespace ccdlab {

int VtkGrid::add_point(const Vec3& p) {
  points_.push_back(p);
  return int(points_.size() - 1);
}

void VtkGrid::add_cell(VtkCell type, const std::vector<int>& points) {
  for (int p : points)
    if (p < 0 || std::size_t(p) >= points_.size()) fail("VtkGrid: cell refers to point {} of {}", p, points_.size());
  connectivity_.insert(connectivity_.end(), points.begin(), points.end());
  offsets_.push_back(std::int64_t(connectivity_.size()));
  types_.push_back(std::uint8_t(type));
  for (Array& a : cell_arrays_) a.values.resize(types_.size(), 0.0);
}

void VtkGrid::set_cell_value(const std::string& array, double value) {
  if (types_.empty()) fail("VtkGrid: no cell to set '{}' on", array);
  auto it = std::find_if(cell_arrays_.begin(), cell_arrays_.end(), [&](const Array& a) { return a.name == array; });
  if (it == cell_arrays_.end()) {
    cell_arrays_.push_back({array, {}});
    it = cell_arrays_.end() - 1;
  }
  it->values.resize(types_.size(), 0.0);
  it->values.back() = value;
}

void VtkGrid::set_point_array(const std::string& array, std::vector<double> values) {
  point_arrays_.push_back({array, std::move(values)});
}

namespace {

template <class T>
void write_values(OutputFile& out, const std::vector<T>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) out << (i % 12 ? " " : "\n") << fmt::format("{}", values[i]);
  out << "\n";
}

void write_arrays(OutputFile& out, const char* tag, const std::vector<std::vector<double>>& values,
                  const std::vector<std::string>& names) {
  out << "<" << tag << ">\n";
  for (std::size_t a = 0; a < names.size(); ++a) {
    out << fmt::format("<DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">", names[a]);
    write_values(out, values[a]);
    out << "</DataArray>\n";
  }
  out << "</" << tag << ">\n";
}

}  // namespace

void VtkGrid::write(const std::string& path, const std::string& what) const {
  for (const Array& a : point_arrays_)
    if (a.values.size() != points_.size())
      fail("VtkGrid: point array '{}' has {} values for {} points", a.name, a.values.size(), points_.size());
  OutputFile out(path, what);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n<UnstructuredGrid>\n"
      << fmt::format("<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", points_.size(), types_.size());
  out << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">";
  std::vector<double> xyz;
  for (const Vec3& p : points_) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  write_values(out, xyz);
  out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">";
  write_values(out, connectivity_);
  out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">";
  write_values(out, offsets_);
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">";
  std::vector<int> types(types_.begin(), types_.end());
  write_values(out, types);
  out << "</DataArray>\n</Cells>\n";
  std::vector<std::vector<double>> values;
  std::vector<std::string> names;
  for (const Array& a : point_arrays_) values.push_back(a.values), names.push_back(a.name);
  write_arrays(out, "PointData", values, names);
  values.clear(), names.clear();
  for (const Array& a : cell_arrays_) {
    values.push_back(a.values);
    values.back().resize(types_.size(), 0.0);
    names.push_back(a.name);
  }
  write_arrays(out, "CellData", values, names);
  out << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  out.commit();
}

void write_vtk_series(const std::string& path, const std::vector<VtkSeriesEntry>& entries, const std::string& what) {
  OutputFile out(path, what);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const VtkSeriesEntry& e : entries)
    out << fmt::format("<DataSet timestep=\"{}\" part=\"0\" file=\"{}\"/>\n", e.time, e.file);
  out << "</Collection>\n</VTKFile>\n";
  out.commit();
}

}  // namespace ccdlab

#include "framework/mesh/mesh_io.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "framework/util/error.hpp"
#include "framework/util/files.hpp"

namespace ccdlab {
namespace {

/// Editors on some systems start text files with a UTF-8 byte-order mark; it is not part of the first record.
void strip_utf8_bom(std::string& text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.erase(0, 3);
}

std::string extension(const std::string& path) {
  auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(c));
  return ext;
}

/// `where` names the vertex ("file:line: vertex 4" or "file:line: element vertex 4").
void check_finite(const std::string& where, const Vec3& p) {
  if (!p.allFinite()) fail("{}: non-finite coordinate ({} {} {})", where, p.x(), p.y(), p.z());
}

/// Appends a polygon, fan-triangulated, after converting 1-based/negative OBJ or 0-based PLY indices.
void add_polygon(const std::string& where, const std::vector<long long>& poly, std::vector<Face>& faces,
                 Index num_vertices) {
  if (poly.size() < 3) fail("{}: face has {} vertices, expected at least 3", where, poly.size());
  for (long long v : poly)
    if (v < 0 || v >= num_vertices) fail("{}: vertex index {} out of range [0, {})", where, v, num_vertices);
  for (std::size_t i = 1; i + 1 < poly.size(); ++i)
    faces.push_back({Index(poly[0]), Index(poly[i]), Index(poly[i + 1])});
}

std::vector<std::string_view> split_ws(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

template <class T>
bool parse_number(std::string_view s, T& out) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && ptr == s.data() + s.size();
}

double parse_double(const std::string& where, std::string_view s, const char* field) {
  double v;
  if (!parse_number(s, v)) {
    // from_chars rejects "nan"/"inf" spellings in some forms; accept them so the finiteness check names them.
    std::string str(s);
    char* end = nullptr;
    v = std::strtod(str.c_str(), &end);
    if (end != str.c_str() + str.size() || str.empty())
      fail("{}: {}: expected a number, got '{}'", where, field, printable(s));
  }
  return v;
}

/// OBJ records that carry nothing ccdlab uses (texture coordinates, normals, grouping, materials, lines).
bool is_ignored_obj_record(std::string_view r) {
  for (std::string_view k : {"vt", "vn", "vp", "l", "p", "o", "g", "s", "mtllib", "usemtl", "cstype", "deg", "curv", "surf"})
    if (r == k) return true;
  return false;
}

}  // namespace

MeshData read_mesh(const std::string& path) {
  check_input_file(path);  // a missing path or a folder is named as such, not as an unknown format
  std::string ext = extension(path);
  if (ext == "obj") return read_obj(path);
  if (ext == "ply") return read_ply(path);
  fail("{}: unknown mesh format '.{}', expected .obj or .ply", path, ext);
}

// ---------------------------------------------------------------------------------------------------------
// OBJ: 'v x y z' and 'f a b c ...' (a may be 'a/t/n', negative = relative); other records are ignored.
MeshData read_obj(const std::string& path) { return parse_obj(read_file(path), path); }

MeshData parse_obj(std::string text, const std::string& path) {
  if (text.empty()) fail("{}: empty file", path);
  strip_utf8_bom(text);
  MeshData mesh;
  std::vector<std::pair<std::size_t, std::vector<long long>>> polygons;  // (line, 0-based indices)
  std::size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    auto tok = split_ws(line);
    if (tok.empty()) continue;
    std::string where = fmt::format("{}:{}", path, line_no);
    if (tok[0] == "v") {
      if (tok.size() < 4) fail("{}: vertex: expected 3 coordinates, got {}", where, tok.size() - 1);
      Vec3 p(parse_double(where, tok[1], "x"), parse_double(where, tok[2], "y"), parse_double(where, tok[3], "z"));
      check_finite(fmt::format("{}: vertex {}", where, mesh.positions.size()), p);
      mesh.positions.push_back(p);
    } else if (tok[0] == "f") {
      std::vector<long long> poly;
      for (std::size_t i = 1; i < tok.size(); ++i) {
        std::string_view idx = tok[i].substr(0, tok[i].find('/'));
        long long v;
        if (!parse_number(idx, v) || v == 0) fail("{}: face: expected a vertex index, got '{}'", where, printable(tok[i]));
        poly.push_back(v > 0 ? v - 1 : (long long)mesh.positions.size() + v);
      }
      polygons.emplace_back(line_no, std::move(poly));
    } else if (!is_ignored_obj_record(tok[0])) {
      // An unknown record is more likely a corrupt file than an extension: refuse rather than guess.
      fail("{}: unknown OBJ record '{}' (expected v, f, or one of vt vn vp l p o g s mtllib usemtl)", where,
           printable(tok[0]));
    }
  }
  for (auto& [line, poly] : polygons)
    add_polygon(fmt::format("{}:{}: face", path, line), poly, mesh.faces, Index(mesh.positions.size()));
  if (mesh.faces.empty()) fail("{}: no faces", path);
  return mesh;
}

// ---------------------------------------------------------------------------------------------------------
// PLY
namespace {

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

PlyType parse_ply_type(const std::string& where, std::string_view s) {
  if (s == "char" || s == "int8") return PlyType::i8;
  if (s == "uchar" || s == "uint8") return PlyType::u8;
  if (s == "short" || s == "int16") return PlyType::i16;
  if (s == "ushort" || s == "uint16") return PlyType::u16;
  if (s == "int" || s == "int32") return PlyType::i32;
  if (s == "uint" || s == "uint32") return PlyType::u32;
  if (s == "float" || s == "float32") return PlyType::f32;
  if (s == "double" || s == "float64") return PlyType::f64;
  fail("{}: property type: expected one of char uchar short ushort int uint float double, got '{}'", where, printable(s));
}

std::size_t ply_size(PlyType t) {
  switch (t) {
    case PlyType::i8: case PlyType::u8: return 1;
    case PlyType::i16: case PlyType::u16: return 2;
    case PlyType::i32: case PlyType::u32: case PlyType::f32: return 4;
    case PlyType::f64: return 8;
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::f32;
  bool is_list = false;
  PlyType count_type = PlyType::u8;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

/// Reads binary values from a buffer in a given byte order; reports truncation with its location.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& data, std::size_t pos, bool big_endian, std::string path)
      : data_(data), pos_(pos), swap_(big_endian != (std::endian::native == std::endian::big)), path_(std::move(path)) {}

  double read(PlyType t, const std::string& element, std::size_t index) {
    std::size_t n = ply_size(t);
    if (pos_ + n > data_.size())
      fail("{}: element {} {}: file truncated ({} bytes, needed more)", path_, element, index, data_.size());
    unsigned char buf[8];
    std::memcpy(buf, data_.data() + pos_, n);
    pos_ += n;
    if (swap_) std::reverse(buf, buf + n);
    switch (t) {
      case PlyType::i8: { std::int8_t v; std::memcpy(&v, buf, 1); return v; }
      case PlyType::u8: { std::uint8_t v; std::memcpy(&v, buf, 1); return v; }
      case PlyType::i16: { std::int16_t v; std::memcpy(&v, buf, 2); return v; }
      case PlyType::u16: { std::uint16_t v; std::memcpy(&v, buf, 2); return v; }
      case PlyType::i32: { std::int32_t v; std::memcpy(&v, buf, 4); return v; }
      case PlyType::u32: { std::uint32_t v; std::memcpy(&v, buf, 4); return v; }
      case PlyType::f32: { float v; std::memcpy(&v, buf, 4); return v; }
      case PlyType::f64: { double v; std::memcpy(&v, buf, 8); return v; }
    }
    return 0;
  }
  [[nodiscard]] std::size_t remaining() const { return data_.size() - pos_; }

 private:
  const std::string& data_;
  std::size_t pos_;
  bool swap_;
  std::string path_;
};

/// Reads ASCII tokens line by line, for located errors.
class AsciiCursor {
 public:
  AsciiCursor(const std::string& data, std::size_t pos, std::size_t line, std::string path)
      : data_(data), pos_(pos), line_(line), path_(std::move(path)) {}

  /// Reads one value; a value of a float property is rounded to float, as the header declares.
  double read(PlyType type, const std::string& element, std::size_t index, const std::string& property) {
    while (tok_i_ >= tokens_.size()) {
      if (pos_ >= data_.size())
        fail("{}:{}: element {} {}: file truncated, property {} missing", path_, line_, element, index, property);
      std::size_t end = data_.find('\n', pos_);
      if (end == std::string::npos) end = data_.size();
      tokens_ = split_ws(std::string_view(data_).substr(pos_, end - pos_));
      tok_i_ = 0;
      pos_ = end + 1;
      ++line_;
    }
    std::string where = fmt::format("{}:{}: element {} {}", path_, line_, element, index);
    double v = parse_double(where, tokens_[tok_i_++], property.c_str());
    return type == PlyType::f32 ? double(float(v)) : v;
  }
  [[nodiscard]] std::size_t line() const { return line_; }

 private:
  const std::string& data_;
  std::size_t pos_;
  std::size_t line_;
  std::string path_;
  std::vector<std::string_view> tokens_;
  std::size_t tok_i_ = 0;
};

}  // namespace

MeshData read_ply(const std::string& path) { return parse_ply(read_file(path), path); }

MeshData parse_ply(std::string data, const std::string& path) {
  if (data.empty()) fail("{}: empty file", path);
  strip_utf8_bom(data);
  // --- header ---
  std::size_t pos = 0, line_no = 0;
  auto next_line = [&]() -> std::string_view {
    if (pos >= data.size()) fail("{}:{}: header truncated (no end_header)", path, line_no);
    std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) end = data.size();
    std::string_view line(data.data() + pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    ++line_no;
    return line;
  };
  if (const auto first = next_line(); first != "ply")
    fail("{}:1: not a PLY file (first line must be 'ply', got '{}')", path, printable(first));
  std::string format;
  std::vector<PlyElement> elements;
  for (;;) {
    auto tok = split_ws(next_line());
    std::string where = fmt::format("{}:{}", path, line_no);
    if (tok.empty() || tok[0] == "comment" || tok[0] == "obj_info") continue;
    if (tok[0] == "end_header") break;
    if (tok[0] == "format") {
      if (tok.size() < 2) fail("{}: format: expected ascii, binary_little_endian or binary_big_endian", where);
      format = std::string(tok[1]);
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        fail("{}: format: expected ascii, binary_little_endian or binary_big_endian, got '{}'", where, printable(format));
    } else if (tok[0] == "element") {
      std::size_t count;
      if (tok.size() != 3 || !parse_number(tok[2], count))
        fail("{}: element: expected 'element NAME COUNT', got '{}'", where, printable(fmt::format("{}", fmt::join(tok, " ")), 64));
      elements.push_back({std::string(tok[1]), count, {}});
    } else if (tok[0] == "property") {
      if (elements.empty()) fail("{}: property before any element", where);
      PlyProperty p;
      if (tok.size() == 5 && tok[1] == "list") {
        p.is_list = true;
        p.count_type = parse_ply_type(where, tok[2]);
        p.type = parse_ply_type(where, tok[3]);
        p.name = tok[4];
      } else if (tok.size() == 3) {
        p.type = parse_ply_type(where, tok[1]);
        p.name = tok[2];
      } else {
        fail("{}: property: expected 'property TYPE NAME' or 'property list CTYPE TYPE NAME'", where);
      }
      elements.back().properties.push_back(p);
    } else {
      fail("{}: unknown header keyword '{}'", where, printable(tok[0]));
    }
  }
  if (format.empty()) fail("{}: header has no 'format' line", path);

  // --- body ---
  MeshData mesh;
  BinaryCursor bin(data, pos, format == "binary_big_endian", path);
  AsciiCursor txt(data, pos, line_no, path);
  const bool ascii = format == "ascii";
  bool have_vertices = false, have_faces = false;
  for (const PlyElement& el : elements) {
    const bool is_vertex = el.name == "vertex";
    const bool is_face = el.name == "face";
    int xyz[3] = {-1, -1, -1};
    int face_list = -1;
    for (std::size_t i = 0; i < el.properties.size(); ++i) {
      const auto& p = el.properties[i];
      if (is_vertex && !p.is_list && (p.name == "x" || p.name == "y" || p.name == "z")) xyz[p.name[0] - 'x'] = int(i);
      if (is_face && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) face_list = int(i);
    }
    if (is_vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0))
      fail("{}: element vertex: properties x, y, z are required", path);
    if (is_face && face_list < 0) fail("{}: element face: property list vertex_indices is required", path);
    if (is_vertex) have_vertices = true;
    if (is_face) have_faces = true;
    if (el.properties.empty()) continue;  // nothing to read, whatever the count
    // The header's count is a claim: check it against the bytes the file really has before allocating.
    // (ASCII: a loose bound, one value and a separator per item, so that an ordinary truncation is still
    // reported where it happens, with its line.)
    std::size_t min_item_bytes = ascii ? 2 : 0;
    if (!ascii)
      for (const auto& p : el.properties) min_item_bytes += ply_size(p.is_list ? p.count_type : p.type);
    const std::size_t body_bytes = data.size() - pos;
    if (el.count > (body_bytes + 1) / min_item_bytes)
      fail("{}: element {} {}: the header declares more items than the file can hold ({} bytes after the header, "
           "at least {} per item)", path, el.name, el.count, body_bytes, min_item_bytes);
    if (is_vertex && el.count > TriMesh::kMaxVertices)
      fail("{}: element vertex {}: more than ccdlab's 32-bit vertex ids allow ({})", path, el.count, TriMesh::kMaxVertices);
    if (is_vertex) mesh.positions.resize(el.count);
    std::vector<long long> poly;
    for (std::size_t k = 0; k < el.count; ++k) {
      std::size_t line_of_item = txt.line() + 1;
      for (std::size_t i = 0; i < el.properties.size(); ++i) {
        const auto& p = el.properties[i];
        auto read = [&](PlyType t) { return ascii ? txt.read(t, el.name, k, p.name) : bin.read(t, el.name, k); };
        if (p.is_list) {
          double n = read(p.count_type);
          if (!(n >= 0) || n != std::floor(n) || n > double(data.size()))
            fail("{}: element {} {}: list {}: expected a count from 0 to the file size, got {}", path, el.name, k, p.name, n);
          if (is_face && int(i) == face_list) poly.clear();
          for (long long j = 0; j < (long long)n; ++j) {
            double v = read(p.type);
            if (is_face && int(i) == face_list) {
              if (!(std::fabs(v) <= 0x1p62) || v != std::floor(v))
                fail("{}: element face {}: vertex index: expected an integer, got {}", path, k, v);
              poly.push_back((long long)v);
            }
          }
        } else {
          double v = read(p.type);
          if (is_vertex)
            for (int c = 0; c < 3; ++c)
              if (int(i) == xyz[c]) mesh.positions[k][c] = v;
        }
      }
      std::string where = ascii ? fmt::format("{}:{}: element {} {}", path, line_of_item, el.name, k)
                                : fmt::format("{}: element {} {}", path, el.name, k);
      if (is_vertex) check_finite(where, mesh.positions[k]);
      if (is_face) add_polygon(where, poly, mesh.faces, Index(mesh.positions.size()));
    }
  }
  if (!have_vertices || !have_faces) fail("{}: a PLY mesh needs elements 'vertex' and 'face'", path);
  if (!ascii && bin.remaining() > 0)
    fail("{}: {} unexpected bytes after the last element (header and body disagree)", path, bin.remaining());
  if (mesh.faces.empty()) fail("{}: no faces", path);
  return mesh;
}

// ---------------------------------------------------------------------------------------------------------
void write_obj(const std::string& path, const Positions& positions, const std::vector<Face>& faces) {
  std::ofstream out(path);
  if (!out) fail("{}: cannot write file", path);
  for (const Vec3& p : positions) out << fmt::format("v {} {} {}\n", p.x(), p.y(), p.z());
  for (const Face& f : faces) out << fmt::format("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
  if (!out) fail("{}: write failed", path);
}

void write_ply(const std::string& path, const Positions& positions, const std::vector<Face>& faces,
               PlyEncoding encoding, bool double_precision) {
  std::ofstream out(path, std::ios::binary);
  if (!out) fail("{}: cannot write file", path);
  const char* fmt_name = encoding == PlyEncoding::ascii                  ? "ascii"
                         : encoding == PlyEncoding::binary_little_endian ? "binary_little_endian"
                                                                         : "binary_big_endian";
  const char* type = double_precision ? "double" : "float";
  out << "ply\nformat " << fmt_name << " 1.0\ncomment written by ccdlab\n"
      << "element vertex " << positions.size() << "\nproperty " << type << " x\nproperty " << type
      << " y\nproperty " << type << " z\nelement face " << faces.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  if (encoding == PlyEncoding::ascii) {
    for (const Vec3& p : positions)
      if (double_precision) out << fmt::format("{} {} {}\n", p.x(), p.y(), p.z());
      else out << fmt::format("{} {} {}\n", float(p.x()), float(p.y()), float(p.z()));
    for (const Face& f : faces) out << fmt::format("3 {} {} {}\n", f[0], f[1], f[2]);
  } else {
    const bool swap = (encoding == PlyEncoding::binary_big_endian) != (std::endian::native == std::endian::big);
    auto put = [&](const void* src, std::size_t n) {
      unsigned char buf[8];
      std::memcpy(buf, src, n);
      if (swap) std::reverse(buf, buf + n);
      out.write(reinterpret_cast<const char*>(buf), std::streamsize(n));
    };
    for (const Vec3& p : positions)
      for (int c = 0; c < 3; ++c) {
        if (double_precision) put(&p[c], 8);
        else { float v = float(p[c]); put(&v, 4); }
      }
    for (const Face& f : faces) {
      std::uint8_t n = 3;
      put(&n, 1);
      for (Index v : f) { std::int32_t i = v; put(&i, 4); }
    }
  }
  if (!out) fail("{}: write failed", path);
}

}  // namespace ccdlab

#include "framework/queries/query_set.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <gmp.h>
#include <nlohmann/json.hpp>

#include "framework/util/error.hpp"
#include "framework/util/files.hpp"

namespace ccdlab {
namespace fs = std::filesystem;

double parse_exact_double(const std::string& num, const std::string& den, const std::string& where) {
  struct Rational {
    mpq_t q;
    Rational() { mpq_init(q); }
    ~Rational() { mpq_clear(q); }
  } value, back;
  auto integer = [&](const std::string& text, mpz_ptr out, const char* what) {
    const bool ok = !text.empty() && text.find_first_not_of("+-0123456789") == std::string::npos &&
                    mpz_set_str(out, text.c_str() + (text[0] == '+'), 10) == 0;
    if (!ok) fail("{}: {}: expected an integer, got '{}'", where, what, text);
  };
  integer(num, mpq_numref(value.q), "numerator");
  integer(den, mpq_denref(value.q), "denominator");
  if (mpz_sgn(mpq_denref(value.q)) == 0) fail("{}: denominator: expected a non-zero integer, got 0", where);
  mpq_canonicalize(value.q);
  const double d = mpq_get_d(value.q);  // truncates: exact iff converting back gives the same rational
  if (!std::isfinite(d)) fail("{}: {}/{} is not a finite double", where, num, den);
  mpq_set_d(back.q, d);
  if (!mpq_equal(back.q, value.q)) fail("{}: {}/{} is not exactly representable as a double", where, num, den);
  return d;
}

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) {
    while (!cell.empty() && (cell.back() == '\r' || cell.back() == ' ')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(cell.begin());
    out.push_back(cell);
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

/// Edge–edge or vertex–face, from the folder name (handcrafted) or the file stem suffix (simulation).
ContactKind kind_of(const fs::path& file) {
  const std::string dir = file.parent_path().filename().string(), stem = file.stem().string();
  if (dir == "edge-edge" || stem.ends_with("ee")) return ContactKind::ee;
  if (dir == "vertex-face" || stem.ends_with("vf")) return ContactKind::vf;
  fail("{}: cannot tell edge-edge from vertex-face queries (expected a folder 'edge-edge' / 'vertex-face' or a "
       "file name ending in 'ee' / 'vf')", file.string());
}

std::vector<char> read_truth_json(const fs::path& json_path, std::size_t expected, const fs::path& csv) {
  std::error_code ec;
  if (!fs::exists(json_path, ec)) fail("{}: no ground truth: 6-column queries need {}", csv.string(), json_path.string());
  check_input_file(json_path.string());
  std::ifstream in(json_path);
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    fail("{}: invalid JSON: {}", json_path.string(), e.what());
  }
  if (!j.is_array()) fail("{}: expected a JSON array of booleans", json_path.string());
  if (j.size() != expected)
    fail("{}: {} answers for the {} queries of {}", json_path.string(), j.size(), expected, csv.string());
  std::vector<char> truth;
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_boolean()) fail("{}: element {}: expected true or false, got {}", json_path.string(), i, j[i].dump());
    truth.push_back(j[i].get<bool>() ? 1 : 0);
  }
  return truth;
}

struct FileQueries {
  std::vector<std::array<Vec3, 8>> points;
  std::vector<char> truth;  // empty for 6-column files
  std::vector<int> first_line;
};

FileQueries read_csv(const fs::path& file) {
  check_input_file(file.string());
  std::ifstream in(file);
  FileQueries out;
  std::string line;
  int line_no = 0, columns = 0;
  std::array<Vec3, 8> rows;
  int row = 0;
  char truth = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line == "\r") continue;
    const auto cells = split_csv(line);
    const std::string where = fmt::format("{}:{}", file.string(), line_no);
    if (columns == 0) {
      columns = int(cells.size());
      if (columns != 6 && columns != 7) fail("{}: expected 6 or 7 columns (x,y,z as num,den pairs [+ truth]), got {}", where, columns);
    } else if (int(cells.size()) != columns) {
      fail("{}: expected {} columns like the first row, got {}", where, columns, cells.size());
    }
    for (int c = 0; c < 3; ++c)
      rows[row][c] = parse_exact_double(cells[2 * c], cells[2 * c + 1], fmt::format("{}: column {}", where, 2 * c + 1));
    if (columns == 7) {
      if (cells[6] != "0" && cells[6] != "1") fail("{}: column 7 (ground truth): expected 0 or 1, got '{}'", where, cells[6]);
      const char t = cells[6] == "1";
      if (row == 0) truth = t;
      else if (t != truth) fail("{}: column 7 (ground truth): differs from the query's first row", where);
    }
    if (row == 0) out.first_line.push_back(line_no);
    if (++row == 8) {
      out.points.push_back(rows);
      if (columns == 7) out.truth.push_back(truth);
      row = 0;
    }
  }
  if (row != 0)
    fail("{}: truncated: the last query has {} of its 8 rows (query {} starts at line {})", file.string(), row,
         out.points.size() + 1, out.first_line.back());
  if (out.points.empty()) fail("{}: no queries", file.string());
  return out;
}

}  // namespace

std::vector<QuerySet> load_query_sets(const fs::path& root) {
  if (!fs::exists(root)) fail("{}: no such file or directory", root.string());
  std::vector<fs::path> files;
  if (fs::is_directory(root)) {
    for (const auto& e : fs::recursive_directory_iterator(root))
      if (e.is_regular_file() && e.path().extension() == ".csv") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    if (files.empty()) fail("{}: no .csv query files under this directory", root.string());
  } else {
    files.push_back(root);
  }
  std::vector<QuerySet> sets;
  std::map<std::string, std::size_t> index;
  for (const fs::path& file : files) {
    FileQueries fq = read_csv(file);
    // A set is named scene/kind whatever folder the user pointed at, so a row always says where it comes from.
    const fs::path abs = fs::absolute(file).lexically_normal();
    fs::path scene_dir;
    std::string kind_part;
    if (fq.truth.empty()) {  // simulation layout: <scene>/queries/<stem>.csv + <scene>/mma_bool/<stem>_mma_bool.json
      scene_dir = abs.parent_path().parent_path();
      fq.truth = read_truth_json(scene_dir / "mma_bool" / (file.stem().string() + "_mma_bool.json"), fq.points.size(), file);
      kind_part = file.stem().string();
    } else {  // handcrafted layout: <scene>/<kind>/*.csv
      scene_dir = abs.parent_path().parent_path();
      kind_part = abs.parent_path().filename().string();
    }
    const std::string scene = scene_dir.filename().empty() ? kind_part : scene_dir.filename().string();
    const std::string name = scene + "/" + kind_part;
    const ContactKind kind = kind_of(file);
    auto [it, fresh] = index.try_emplace(name, sets.size());
    if (fresh) {
      sets.emplace_back();
      sets.back().name = name;
      sets.back().scene = scene;
      sets.back().collection = scene_dir.has_parent_path() ? scene_dir.parent_path().filename().string() : "";
      sets.back().kind = kind;
    }
    QuerySet& s = sets[it->second];
    if (s.kind != kind) fail("{}: {} queries in a set of {} queries ({})", file.string(), to_string(kind), to_string(s.kind), name);
    for (std::size_t i = 0; i < fq.points.size(); ++i) {
      const auto& p = fq.points[i];
      if (kind == ContactKind::vf) s.vf.push_back({p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]});
      else s.ee.push_back({p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]});
      s.truth.push_back(fq.truth[i]);
      s.toi.push_back(std::nan(""));
      s.origin.push_back(fmt::format("{}:{}", file.string(), fq.first_line[i]));
    }
  }
  return sets;
}

}  // namespace ccdlab

#pragma once
// Sets of elementary CCD queries with known answers: the shared benchmark format (../shared/data/ccd-queries,
// Wang et al. 2021 and Belgrod et al. 2023) and the built-in hard cases (hard_cases.hpp).
//
// File format: CSV, 8 rows per query, one vertex per row as exact rationals x_num,x_den,y_num,y_den,z_num,z_den;
// rows ea0_t0 ea1_t0 eb0_t0 eb1_t0 ea0_t1 ea1_t1 eb0_t1 eb1_t1 (edge–edge) or v f0 f1 f2 at t0 then t1
// (vertex–face). A 7th column holds the ground truth (handcrafted sets); otherwise it is the JSON array of
// booleans `../mma_bool/<stem>_mma_bool.json` beside the `queries/` folder (simulation sets).
#include <filesystem>
#include <string>
#include <vector>

#include "framework/primitive/contact.hpp"

namespace ccdlab {

struct QuerySet {
  std::string name;        ///< scene/kind: "erleben-wedges/edge-edge", "cloth-funnel/227ee", "hard-cases/two-roots"
  std::string scene;       ///< "erleben-wedges", "cloth-funnel", "hard-cases"
  std::string collection;  ///< the folder above the scene ("handcrafted", "simulation"), "hard-cases", or ""
  ContactKind kind = ContactKind::vf;
  std::vector<VertexFaceQuery> vf;  ///< the queries, when kind == vf
  std::vector<EdgeEdgeQuery> ee;    ///< when kind == ee
  std::vector<char> truth;          ///< 1 = the primitives touch for some t in [0, 1]
  std::vector<double> toi;          ///< known exact time of contact, NaN where unknown (hard cases only)
  std::vector<std::string> origin;  ///< where each query comes from ("file:line" or a hard-case label)

  [[nodiscard]] std::size_t size() const { return truth.size(); }
};

/// Reads one CSV file, or every *.csv under a directory (sorted), merging the files of one directory into
/// one set, named scene/kind whatever `root` is: <scene>/<kind>/*.csv (handcrafted) → "scene/kind",
/// <scene>/queries/<stem>.csv (simulation) → "scene/stem". Throws Error naming file,
/// line and column on malformed input: wrong column count, non-integer or zero denominator, a value that is
/// not exactly a finite double, a truncated query, inconsistent or missing ground truth.
std::vector<QuerySet> load_query_sets(const std::filesystem::path& root);

/// Parses one rational "num/den" exactly into a double; throws Error (with `where`) unless exact and finite.
double parse_exact_double(const std::string& num, const std::string& den, const std::string& where);

}  // namespace ccdlab

#pragma once
// Ground truth of a real step in ../shared/data: the colliding feature pairs listed in
// ccd-queries/simulation/<scene>/{boxes,mma_bool}/<prefix>{vf,ee}*.json (ids: vertex v → v, edge e → nV + e,
// face f → nV + nE + f; see ../shared/data/README.md).
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "framework/mesh/tri_mesh.hpp"
#include "framework/primitive/feature_pairs.hpp"

namespace ccdlab::test {

struct GroundTruth {
  std::set<VertexFacePair> vf_true, vf_false;
  std::set<EdgeEdgePair> ee_true, ee_false;
};

inline nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

inline GroundTruth load_truth(const std::string& root, const std::string& scene, const std::string& prefix,
                              const TriMesh& mesh) {
  GroundTruth gt;
  const std::string base = root + "/ccd-queries/simulation/" + scene + "/";
  const long long nv = mesh.num_vertices(), ne = mesh.num_edges();
  auto vf_ids = read_json(base + "boxes/" + prefix + "vf.json");
  auto vf_bool = read_json(base + "mma_bool/" + prefix + "vf_mma_bool.json");
  auto ee_ids = read_json(base + "boxes/" + prefix + "ee.json");
  auto ee_bool = read_json(base + "mma_bool/" + prefix + "ee_mma_bool.json");
  EXPECT_EQ(vf_ids.size(), vf_bool.size());
  EXPECT_EQ(ee_ids.size(), ee_bool.size());
  for (std::size_t i = 0; i < vf_ids.size(); ++i) {
    long long a = vf_ids[i][0], b = vf_ids[i][1];
    EXPECT_LT(a, nv);
    VertexFacePair p{Index(a), Index(b - nv - ne)};
    (vf_bool[i].get<bool>() ? gt.vf_true : gt.vf_false).insert(p);
  }
  for (std::size_t i = 0; i < ee_ids.size(); ++i) {
    long long a = ee_ids[i][0].get<long long>() - nv, b = ee_ids[i][1].get<long long>() - nv;
    EdgeEdgePair p{Index(std::min(a, b)), Index(std::max(a, b))};
    (ee_bool[i].get<bool>() ? gt.ee_true : gt.ee_false).insert(p);
  }
  return gt;
}

}  // namespace ccdlab::test

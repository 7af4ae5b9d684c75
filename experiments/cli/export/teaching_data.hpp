#pragma once
// What the teaching page (`ccdlab export CONFIG --html OUT.html`) shows, gathered from the experiment as one JSON
// document (framework/export/teaching_page.hpp writes it into the page):
//   mesh      faces, their body, every frame's positions, per step the contacts touching each face;
//   bodies    each BVH's topology (children, depth, leaf face) — the same at every K: the builder splits by
//             centroids;
//   ks        per K (the config's first, then the others of 6 / 14 / 18 / 26): the k-DOP slabs of every node
//             above depth `levels`, per step, and the step's counts (BV tests, candidates, contacts, ms); for the
//             config's K also the BVTT front of every pass (kept / sprouted / pruned) and the candidate pairs;
//   contacts  per step, each with its features, time of contact and the BVTT leaf pair (or the orphan set)
//             that led to it, by the ownership rule;
//   walks     the BVTT below one small self node of the detailed step, in the order of sequential, phc and
//             front (framework/export/bvtt_walk.hpp).
// Coordinates are integers on a grid of 2⁻¹⁶ of the scene's extent (origin and quantum in `grid`): a page of a
// few MB, not tens.
#include <nlohmann/json.hpp>

#include "framework/config/experiment.hpp"
#include "framework/scene/mesh_sequence.hpp"
#include "framework/util/progress.hpp"

namespace ccdlab::cli {

struct TeachingOptions {
  int levels = 8;          ///< BVH depths drawn: 0 … levels − 1
  int detail_step = -1;    ///< the step whose BVTT is walked; −1: the one with the most contacts
  int walk_leaves = 16;    ///< the walked sub-tree: a self node with at most this many leaves
};

nlohmann::json teaching_data(const ExperimentConfig& config, const Registries& reg, const MeshSequence& scene,
                             const TeachingOptions& o, Progress& progress);

}  // namespace ccdlab::cli

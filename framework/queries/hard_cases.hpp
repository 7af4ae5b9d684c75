#pragma once
// Built-in hard (degenerate) elementary queries with answers known by construction, for the accuracy ladder
// (docs/results-accuracy.md): contact exactly at t = 0 / t = 1, vertex on an edge or a vertex, coplanar motion, parallel and
// collinear edges, zero-length edges and zero-area faces, no motion, two roots in one step ("pass through and
// back"), tangential (double-root) contact — each with ± perturbations of 2^-10, 2^-20, 2^-30, 2^-40 and one
// ulp that flip or keep the answer. All coordinates are dyadic, so every perturbed query is exactly what it
// says and its answer is exact. Two more sets repeat every case under exact transforms: scaled by 2^-40
// (motions of ~1e-12) and scaled by 2^20 / translated by ~1e6 (large coordinates; only where exact).
#include <vector>

#include "framework/queries/query_set.hpp"

namespace ccdlab {

/// One set per family ("hard-cases/<family>") plus "hard-cases/tiny-motion" and "hard-cases/large-coordinates".
std::vector<QuerySet> hard_case_sets();

}  // namespace ccdlab

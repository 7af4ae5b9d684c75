#pragma once
// The BVTT expansion rule, its one home. A node of the BV test tree is a pair of BVH nodes (a, b), a == b a
// self node (the seed paper, §3). How a node opens:
//   self node (A, A), A inner and its self test not skipped      → (L, L), (R, R), (L, R)
//   pair node (A, B) whose volumes overlap, not two leaves        → the two children of the side descend_a picks
// Every walk applies it: the binary walks, task splits and the binary front through BvttView (bvtt_view.hpp),
// the 4-wide walks and the wide front on a record's lanes (bvtt_wide.hpp, lane_pair_walk-inl.hpp,
// front/wide_front_walk-inl.hpp). It is written here on plain values because the wide walks carry slots and
// size measures on their stacks instead of nodes.
//
// Seeds of pieces of work (the fronts' rebuilds, front/) are cut by another rule, on leaf counts alone: a piece
// is a share of the pass's leaf pairs, and a rule on topology gives the same seeds at every step and thread
// count. It opens no node for a test (a seed's children cover the same leaf pairs), so the candidates do not
// depend on it.
#include "framework/mesh/tri_mesh.hpp"  // Index

namespace ccdlab::bvtt_rule {

/// Does the self node (A, A) open? A is not a leaf and its self test is not skipped this step (`skip_root`:
/// the normal-cone skips of hierarchy/normal_cones.hpp, or nullptr when culling is off).
[[nodiscard]] constexpr bool self_opens(bool a_is_leaf, const Index* skip_root, Index a) {
  return !a_is_leaf && !(skip_root && skip_root[a] >= 0);
}

/// The descent rule of a pair node: open a (true) or b (false) — the larger by size_measure, never a leaf.
template <class Size>
[[nodiscard]] constexpr bool descend_a(bool a_is_leaf, bool b_is_leaf, Size size_a, Size size_b) {
  return b_is_leaf || (!a_is_leaf && size_a >= size_b);
}

/// A seed over `leaves_a` × `leaves_b` leaf pairs is small enough to be one piece: at most `max_pairs` of
/// them, or one leaf pair.
[[nodiscard]] constexpr bool seed_is_piece(double leaves_a, double leaves_b, double max_pairs) {
  return leaves_a * leaves_b <= max_pairs || (leaves_a == 1 && leaves_b == 1);
}

/// The same for a self seed (A, A) over `leaves` leaves: its n·(n−1)/2 leaf pairs.
[[nodiscard]] constexpr bool self_seed_is_piece(double leaves, double max_pairs) {
  return leaves * (leaves - 1) / 2 <= max_pairs;
}

/// The most leaf pairs one seed may cover: 1/`granularity` of the pass's (a self pass's n·(n−1)/2 over its n
/// leaves, else n_a·n_b), and no fewer than `min_pairs`.
[[nodiscard]] constexpr double seed_max_pairs(double leaves_a, double leaves_b, bool self, double granularity,
                                              double min_pairs) {
  const double all = self ? leaves_a * (leaves_a - 1) / 2 : leaves_a * leaves_b;
  return all / granularity > min_pairs ? all / granularity : min_pairs;
}

/// A binary seed too large to be a piece splits its side with more leaves (a on ties). (A wide seed opens the
/// records of both sides at once.)
[[nodiscard]] constexpr bool seed_splits_a(double leaves_a, double leaves_b) { return leaves_a >= leaves_b; }

}  // namespace ccdlab::bvtt_rule

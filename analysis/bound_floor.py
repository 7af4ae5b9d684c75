#!/usr/bin/python3
"""How far tighter swept bounds could cut a step's candidate face pairs: the floor of time-split k-DOPs.

    /usr/bin/python3 analysis/bound_floor.py A.ply B.ply [--k 18] [--pieces 2,4,8]

The traversal's candidates are the non-adjacent face pairs (no shared vertex) whose swept k-DOPs overlap: each
face bounded over the whole step. Splitting the step into P time pieces and bounding each piece on its own
(motion is linear, so a piece's bound is the k-DOP of the face's corners at the piece's two ends) keeps a pair
only if some piece's bounds overlap. This prints, as a Markdown table, how many candidates survive each split;
then how many candidates join two faces of one connected piece (a rod's or a sheet's self-collision pairs), and
with --features the vertex-face and edge-edge pairs whose own swept k-DOPs overlap (a broad phase on features).

The last row is the floor of every split: the pairs whose faces' k-DOPs already overlap at t0 or at t1. The first
piece's bound holds the face at t0 and the last piece's holds it at t1, so no split into time pieces, however
fine, removes those pairs; only a tighter shape (more axes, the faces themselves) could. The counts use float64
projections without the outward rounding ccdlab's bounds get, so the first row can be a few pairs below the
pipeline's `candidate_pairs`.
"""
import argparse
import sys

import numpy as np

KDOP_AXES = {  # framework/geometry/kdop.hpp's tables, in the same order
    6: [(1, 0, 0), (0, 1, 0), (0, 0, 1)],
    14: [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1), (1, -1, 1), (1, 1, -1), (1, -1, -1)],
    18: [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (1, 0, 1), (0, 1, 1), (1, -1, 0), (1, 0, -1), (0, 1, -1)],
    26: [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1), (1, -1, 1), (1, 1, -1), (1, -1, -1),
         (1, 1, 0), (1, 0, 1), (0, 1, 1), (1, -1, 0), (1, 0, -1), (0, 1, -1)],
}
CHUNK = 1 << 20  # pairs tested at a time (bounds the temporary arrays)


def read_frames(path_a, path_b):
    """(points at t0, points at t1, faces) of two frames with the same faces; exits with the file named on error."""
    import meshio
    meshes = []
    for path in (path_a, path_b):
        try:
            mesh = meshio.read(path)
        except Exception as e:  # meshio raises many types for malformed files
            sys.exit(f"bound_floor: {path}: cannot read: {e}")
        faces = mesh.cells_dict.get("triangle")
        if faces is None or len(faces) == 0:
            sys.exit(f"bound_floor: {path}: no triangles")
        points = np.asarray(mesh.points, dtype=np.float64)[:, :3]
        if not np.isfinite(points).all():
            row = int(np.nonzero(~np.isfinite(points).all(axis=1))[0][0])
            sys.exit(f"bound_floor: {path}: vertex {row} is not finite")
        meshes.append((points, np.asarray(faces, dtype=np.int64)))
    (p0, f0), (p1, f1) = meshes
    if len(p0) != len(p1):
        sys.exit(f"bound_floor: {path_b}: {len(p1)} vertices, {path_a} has {len(p0)}")
    if f0.shape != f1.shape or not np.array_equal(f0, f1):
        sys.exit(f"bound_floor: {path_b}: its faces differ from {path_a}'s")
    return p0, p1, f0


def kdops(frames, faces, axes):
    """(lo, hi), each (faces × axes): the k-DOP of every face's corners in all of `frames`."""
    proj = np.concatenate([frame[faces] @ axes.T for frame in frames], axis=1)  # faces × corners × axes
    return proj.min(axis=1), proj.max(axis=1)


def overlap(box, i, j):
    lo, hi = box
    return np.all(lo[i] <= hi[j], axis=1) & np.all(lo[j] <= hi[i], axis=1)


def swept_candidates(p0, p1, faces, box):
    """(i, j), i < j: the pairs of `faces` (vertex triples; an edge repeats a vertex, a vertex is itself thrice)
    that share no vertex and whose swept k-DOPs `box` overlap."""
    from scipy.spatial import cKDTree
    lo, hi = box[0][:, :3], box[1][:, :3]  # x, y, z are the first three axes of every table
    center, radius = (lo + hi) / 2, np.linalg.norm(hi - lo, axis=1) / 2
    # Overlapping boxes have centres at most r_i + r_j apart. Faces are binned by radius (powers of two) so a
    # few large faces (an obstacle's) do not widen every search: per pair of bins, centres within the sum of
    # the bins' largest radii.
    level = np.floor(np.log2(np.maximum(radius, 1e-300))).astype(np.int64)
    bins = [np.nonzero(level == v)[0] for v in np.unique(level)]
    trees = [cKDTree(center[members]) for members in bins]
    reach = [radius[members].max() for members in bins]
    pairs = [np.empty((0, 2), dtype=np.int64)]
    for a, (members_a, tree_a) in enumerate(zip(bins, trees)):
        pairs.append(members_a[tree_a.query_pairs(2 * reach[a], output_type="ndarray")])
        for b in range(a + 1, len(bins)):
            near = tree_a.sparse_distance_matrix(trees[b], reach[a] + reach[b], output_type="ndarray")
            pairs.append(np.stack([members_a[near["i"]], bins[b][near["j"]]], axis=1))
    pairs = np.sort(np.concatenate(pairs), axis=1)
    pairs = np.unique(pairs[pairs[:, 0] != pairs[:, 1]], axis=0)
    i, j = pairs[:, 0], pairs[:, 1]
    shared = np.zeros(len(i), dtype=bool)
    for u in range(3):
        for v in range(3):
            shared |= faces[i, u] == faces[j, v]
    i, j = i[~shared], j[~shared]
    keep = np.concatenate([overlap(box, i[s:s + CHUNK], j[s:s + CHUNK]) for s in range(0, len(i), CHUNK)])
    return i[keep], j[keep]


def surviving(boxes, i, j):
    """How many pairs overlap in at least one of `boxes` (one per time piece)."""
    count = 0
    for s in range(0, len(i), CHUNK):
        a, b = i[s:s + CHUNK], j[s:s + CHUNK]
        count += int(np.logical_or.reduce([overlap(box, a, b) for box in boxes]).sum())
    return count


def floor_table(p0, p1, faces, k, pieces):
    """([(row label, candidates)], candidates within one piece): the whole-step swept k-DOPs, each split into time
    pieces, and the floor."""
    axes = np.asarray(KDOP_AXES[k], dtype=np.float64)
    i, j = swept_candidates(p0, p1, faces, kdops([p0, p1], faces, axes))
    rows = [(f"swept {k}-DOP over the step (the traversal's test)", len(i))]
    for n in pieces:
        at = [p0 + (p1 - p0) * (t / n) for t in range(n + 1)]
        boxes = [kdops([at[t], at[t + 1]], faces, axes) for t in range(n)]
        rows.append((f"split into {n} time pieces", surviving(boxes, i, j)))
    rows.append((f"floor: {k}-DOPs overlap at t0 or at t1", surviving([kdops([p0], faces, axes),
                                                                     kdops([p1], faces, axes)], i, j)))
    return rows, same_piece(faces, i, j)


def same_piece(faces, i, j):
    """(how many pairs (i, j) join two faces of one connected piece (a rod, a sheet), how many pieces)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    n = int(faces.max()) + 1
    edges = coo_matrix((np.ones(2 * len(faces)), (faces[:, [0, 0]].ravel(), faces[:, [1, 2]].ravel())), shape=(n, n))
    _, vertex_piece = connected_components(edges, directed=False)
    piece = vertex_piece[faces[:, 0]]
    return int((piece[i] == piece[j]).sum()), len(np.unique(piece))


def feature_pairs(p0, p1, faces, k):
    """(VF, EE): the vertex-face and edge-edge pairs sharing no vertex whose swept k-DOPs overlap, i.e. what a
    broad phase on features instead of faces would hand to the narrow phase (before any feature-level culling)."""
    axes = np.asarray(KDOP_AXES[k], dtype=np.float64)
    edges = np.unique(np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1), axis=0)
    n = len(p0)
    points = np.repeat(np.arange(n)[:, None], 3, axis=1)
    with_faces = np.concatenate([points, faces])  # one search: only its vertex-face pairs are counted
    i, j = swept_candidates(p0, p1, with_faces, kdops([p0, p1], with_faces, axes))
    vf = int(((i < n) & (j >= n)).sum())  # i < j, so a vertex is always i
    segments = edges[:, [0, 1, 1]]
    ee = len(swept_candidates(p0, p1, segments, kdops([p0, p1], segments, axes))[0])
    return vf, ee


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("frame_a")
    ap.add_argument("frame_b")
    ap.add_argument("--k", type=int, default=18, choices=sorted(KDOP_AXES))
    ap.add_argument("--pieces", default="2,4,8", help="comma-separated numbers of time pieces")
    ap.add_argument("--features", action="store_true",
                    help="also count the vertex-face and edge-edge pairs whose own swept k-DOPs overlap")
    args = ap.parse_args()
    try:
        pieces = [int(n) for n in args.pieces.split(",")]
    except ValueError:
        sys.exit(f"bound_floor: --pieces: '{args.pieces}' is not a comma-separated list of integers")
    if any(n < 1 for n in pieces):
        sys.exit(f"bound_floor: --pieces: every number of pieces must be at least 1, got '{args.pieces}'")
    p0, p1, faces = read_frames(args.frame_a, args.frame_b)
    rows, (within, n_pieces) = floor_table(p0, p1, faces, args.k, pieces)
    whole = rows[0][1]
    print(f"{args.frame_a} → {args.frame_b}: {len(faces):,} faces\n")
    print("| bound | candidate face pairs | share of the swept k-DOP's |")
    print("|---|---|---|")
    for label, count in rows:
        print(f"| {label} | {count:,} | {count / whole:.2f} |" if whole else f"| {label} | {count:,} | — |")
    print(f"\n{within:,} of the {whole:,} swept candidates join two faces of one connected piece "
          f"({n_pieces:,} pieces).")
    if args.features:
        vf, ee = feature_pairs(p0, p1, faces, args.k)
        print(f"Feature pairs sharing no vertex whose swept {args.k}-DOPs overlap: {vf:,} vertex-face + {ee:,} "
              f"edge-edge = {vf + ee:,}.")


if __name__ == "__main__":
    main()

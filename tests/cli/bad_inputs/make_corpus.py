#!/usr/bin/python3
"""Writes the corpus of bad (and awkward but valid) inputs that tests/cli/bad_inputs.cmake runs through the CLI.

Run from anywhere: /usr/bin/python3 tests/cli/bad_inputs/make_corpus.py. The files are committed; this script
says how each was made. Every file is tiny: the two triangles of tests/cli/fall_t0.obj, broken one way.
"""
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0.2, 0.2, 1), (0.6, 0.2, 1), (0.25, 0.25, 0.5)]
F = [(1, 2, 3), (4, 5, 6)]


def obj(vs=V, fs=F, extra="", eol="\n"):
    lines = [f"v {x} {y} {z}" for x, y, z in vs] + ["f " + " ".join(str(i) for i in f) for f in fs]
    return (eol.join(lines) + eol + extra).encode()


def ply_header(fmt="ascii", nv=len(V), nf=len(F), vtype="float", itype="int", ctype="uchar", extra=""):
    return (f"ply\nformat {fmt} 1.0\n{extra}element vertex {nv}\nproperty {vtype} x\nproperty {vtype} y\n"
            f"property {vtype} z\nelement face {nf}\nproperty list {ctype} {itype} vertex_indices\nend_header\n").encode()


F0 = [tuple(i - 1 for i in f) for f in F]  # 0-based for PLY


def ply_ascii(vs=V, fs=F0, **kw):
    body = "".join(f"{x} {y} {z}\n" for x, y, z in vs) + "".join(f"{len(f)} " + " ".join(str(i) for i in f) + "\n" for f in fs)
    return ply_header(nv=kw.pop("nv", len(vs)), nf=kw.pop("nf", len(fs)), **kw) + body.encode()


def ply_binary(vs=V, fs=F0, nv=None, nf=None, tail=b""):
    out = ply_header("binary_little_endian", len(vs) if nv is None else nv, len(fs) if nf is None else nf)
    for v in vs:
        out += struct.pack("<3f", *v)
    for f in fs:
        out += struct.pack("<B", len(f)) + struct.pack(f"<{len(f)}i", *f)
    return out + tail


rng = random.Random(8)
files = {
    # OBJ
    "empty.obj": b"",
    "no_faces.obj": obj(fs=[]),
    "nan.obj": obj(vs=V[:4] + [(0.6, float("nan"), 1)] + V[5:]),
    "inf.obj": obj(vs=V[:2] + [(0, float("inf"), 0)] + V[3:]),
    "index_out_of_range.obj": obj(fs=[(1, 2, 3), (4, 5, 7)]),
    "negative_index_out_of_range.obj": obj(fs=[(1, 2, 3), (-1, -2, -9)]),
    "zero_index.obj": obj(fs=[(0, 1, 2), (4, 5, 6)]),
    "degenerate_face.obj": obj(fs=[(1, 2, 3), (4, 4, 6)]),
    "duplicate_face.obj": obj(fs=[(1, 2, 3), (4, 5, 6), (6, 4, 5)]),
    "two_vertex_face.obj": obj(fs=[(1, 2, 3), (4, 5)]),
    "bad_number.obj": obj(vs=V[:3] + [("0.2", "zero", 1)] + V[4:]),
    "too_few_coordinates.obj": b"v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n",
    "unknown_record.obj": obj(extra="xyz 1 2 3\n"),
    "random_bytes.obj": bytes(rng.randrange(256) for _ in range(4096)),
    "huge_line.obj": obj(extra="v " + "1" * 300_000 + " 0 0\n"),
    "non_manifold.obj": obj(vs=V + [(0.5, 0.5, -1), (0.5, 0.5, 1)], fs=F + [(1, 2, 7), (1, 2, 8)]),
    "crlf.obj": obj(eol="\r\n"),
    "bom.obj": b"\xef\xbb\xbf" + obj(),
    "t1_other_vertex_count.obj": obj(vs=V + [(5, 5, 5)]),
    # PLY
    "empty.ply": b"",
    "not_ply.ply": b"PLY?\nformat ascii 1.0\n",
    "no_end_header.ply": ply_header()[: -len(b"end_header\n")],
    "absurd_vertex_count.ply": ply_ascii(nv=4_000_000_000_000),
    "absurd_face_count.ply": ply_binary(nf=2**60),
    "wrong_vertex_count.ply": ply_ascii(vs=V, nv=7),
    "truncated_binary.ply": ply_binary()[:-7],
    "garbage_after_body.ply": ply_binary(tail=bytes(rng.randrange(256) for _ in range(64))),
    "garbage_body.ply": ply_header("binary_little_endian") + bytes(rng.randrange(256) for _ in range(97)),
    "nan.ply": ply_ascii(vs=V[:1] + [(1, float("nan"), 0)] + V[2:]),
    "negative_index.ply": ply_ascii(fs=[(0, 1, 2), (3, -4, 5)]),
    "index_out_of_range.ply": ply_ascii(fs=[(0, 1, 2), (3, 4, 6)]),
    "absurd_list_count.ply": ply_header() + "".join(f"{x} {y} {z}\n" for x, y, z in V).encode() + b"3 0 1 2\n1000000000000 3 4 5\n",
    "float_index.ply": ply_ascii(fs=[(0, 1, 2), (3, 4.5, 5)], itype="float"),
    "bad_property_type.ply": ply_ascii(vtype="quad"),
    "unknown_keyword.ply": ply_ascii(extra="frobnicate 3\n"),
    "crlf.ply": ply_ascii().replace(b"\n", b"\r\n"),
    "bom.ply": b"\xef\xbb\xbf" + ply_ascii(),
    # YAML
    "empty.yaml": b"",
    "list.yaml": b"- a\n- b\n",
    "syntax_error.yaml": b"name: x\nscene: {builtin: drape_fold, resolution: [12\n",
    "threads_zero.yaml": b"name: t\nscene: {builtin: drape_fold, resolution: 8, num_frames: 3}\nthreads: 0\n",
    "threads_huge.yaml": b"name: t\nscene: {builtin: drape_fold, resolution: 8, num_frames: 3}\nthreads: 100000\n",
    "missing_frame.yaml": b"name: t\nscene: {frames: [../fall_t0.obj, ../fall_t1.obj, ../fall_t1.obj, missing_frame.obj]}\n",
    "bad_frame_late.yaml": b"name: t\nscene: {frames: [../fall_t0.obj, ../fall_t1.obj, ../fall_t1.obj, nan.obj]}\n",
    "binary.yaml": bytes(rng.randrange(256) for _ in range(512)),
    "key_twice.yaml": b"name: t\nscene: {builtin: drape_fold, resolution: 8, num_frames: 3}\nthreads: 1\nthreads: 2\n",
    "nested_key_twice.yaml": b"name: t\nscene:\n  builtin: drape_fold\n  resolution: 8\n  resolution: 9\n",
    # Query CSV and ground-truth JSON (layout of ../shared/data/ccd-queries)
    "queries/edge-edge/five_columns.csv": b"1,1,0,1,0,1\n" * 7 + b"1,1,0,1,0\n",
    "queries/edge-edge/truncated.csv": b"1,1,0,1,0,1,0\n" * 5,
    "queries/edge-edge/not_a_number.csv": b"1,1,0,1,zero,1,0\n" + b"1,1,0,1,0,1,0\n" * 7,
    "queries/edge-edge/zero_denominator.csv": b"1,0,0,1,0,1,0\n" + b"1,1,0,1,0,1,0\n" * 7,
    "queries/edge-edge/bad_truth.csv": b"1,1,0,1,0,1,2\n" + b"1,1,0,1,0,1,0\n" * 7,
    "truthless/queries/short_truth_ee.csv": b"1,1,0,1,0,1\n" * 16,
    "truthless/mma_bool/short_truth_ee_mma_bool.json": b"[true]",
    "truthless/queries/broken_json_ee.csv": b"1,1,0,1,0,1\n" * 8,
    "truthless/mma_bool/broken_json_ee_mma_bool.json": b"[tru",
    "truthless/queries/no_truth_ee.csv": b"1,1,0,1,0,1\n" * 8,
}
for name, data in files.items():
    path = os.path.join(HERE, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)
print(f"wrote {len(files)} files under {HERE}")

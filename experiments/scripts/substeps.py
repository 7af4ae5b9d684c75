#!/usr/bin/python3
"""Sub-step sequences and steady cloth_ball replays for `ccdlab bench` (docs/results-scheduling.md, issue 33).

    /usr/bin/python3 experiments/scripts/substeps.py OUT_DIR
    build/bin/ccdlab bench OUT_DIR/rod_twist.yaml --threads 1,2 --rounds 5

Writes, as PLY frames and bench configs under OUT_DIR:
  rod_twist.yaml, n_body.yaml     a shared real step (../shared/data) cut into 5 linear sub-steps (6 frames)
  cloth_ball_substeps.yaml        step 15 -> 16 of the simulated full-size cloth_ball, sheet and kinematic ball as
                                  two bodies, cut the same way
  cloth_ball_steady.yaml          the same step replayed A B A B ... (11 frames)
cloth_ball needs its cached simulation (results/cloth_ball_full/scene: `ccdlab run
experiments/configs/cloth_ball_full.yaml` writes it); without it, or without ../shared/data, those sets are
skipped with a message.
"""
import json
import os
import sys

import meshio
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.path.join(ROOT, '..', 'shared', 'data', 'meshes')
CLOTH_BALL = os.path.join(ROOT, 'results', 'cloth_ball_full', 'scene')
SUB_STEPS = 5


def write_mesh(path, points, faces):
    meshio.write(path, meshio.Mesh(points, [('triangle', faces.astype(np.int32))]), binary=True)
    return path


def cut(name, pa, pb, faces, out):
    """Frames of the step pa -> pb cut into SUB_STEPS linear sub-steps."""
    return [write_mesh(os.path.join(out, f'{name}_s{i}.ply'), (1 - i / SUB_STEPS) * pa + i / SUB_STEPS * pb, faces)
            for i in range(SUB_STEPS + 1)]


def config(name, bodies, out):
    """A bench config; bodies: [(body name, frames, kinematic)]."""
    if len(bodies) == 1:
        scene = f'  frames: [{", ".join(bodies[0][1])}]\n'
    else:
        scene = '  bodies:\n' + ''.join(f'    - name: {b}\n      frames: [{", ".join(frames)}]\n'
                                        + ('      kinematic: true\n' if kinematic else '')
                                        for b, frames, kinematic in bodies)
    path = os.path.join(out, f'{name}.yaml')
    with open(path, 'w') as f:
        f.write(f'name: {name}\nscene:\n{scene}bv: {{k: 18}}\ntester: float\n'
                f'output: {{dir: {os.path.join(out, "results_" + name)}}}\n')
    print('wrote', path)


def real_step(name, a, b, out):
    pa, pb = (meshio.read(os.path.join(SHARED, p)) for p in (a, b))
    faces = pa.cells_dict['triangle']
    config(name, [(name, cut(name, pa.points.astype(np.float64), pb.points.astype(np.float64), faces, out), False)],
           out)


def cloth_ball(a, b, out):
    meta = json.load(open(os.path.join(CLOTH_BALL, 'meta.json')))

    def bodies(i):  # [(name, points, faces)] of frame i, split by meta.json's ranges
        m = meshio.read(os.path.join(CLOTH_BALL, f'frame_{i:04d}.ply'))
        tris = m.cells_dict['triangle']
        return [(body['name'], m.points[body['vertices'][0]:body['vertices'][1]].astype(np.float64),
                 tris[body['faces'][0]:body['faces'][1]] - body['vertices'][0]) for body in meta['bodies']]

    first, last = bodies(a), bodies(b)
    kinematic = {'ball': True}
    sub, steady = [], []
    for (name, pa, faces), (_, pb, _) in zip(first, last):
        sub.append((name, cut(f'cb_{name}', pa, pb, faces, out), kinematic.get(name, False)))
        ends = [write_mesh(os.path.join(out, f'cb_{name}_{tag}.ply'), p, faces) for tag, p in (('A', pa), ('B', pb))]
        steady.append((name, [ends[i % 2] for i in range(11)], kinematic.get(name, False)))
    config('cloth_ball_substeps', sub, out)
    config('cloth_ball_steady', steady, out)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = os.path.abspath(sys.argv[1])
    os.makedirs(out, exist_ok=True)
    if os.path.isdir(SHARED):
        real_step('rod_twist', 'rod-twist/3036.ply', 'rod-twist/3037.ply', out)
        real_step('n_body', 'n-body-simulation/balls16_18.ply', 'n-body-simulation/balls16_19.ply', out)
    else:
        print(f'substeps: {SHARED} not found: no real-step sequences', file=sys.stderr)
    if os.path.isfile(os.path.join(CLOTH_BALL, 'meta.json')):
        cloth_ball(15, 16, out)
    else:
        print(f'substeps: {CLOTH_BALL} not found: run experiments/configs/cloth_ball_full.yaml first', file=sys.stderr)


if __name__ == '__main__':
    main()

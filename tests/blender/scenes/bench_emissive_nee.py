"""Benchmark (not a test): emissive-triangle NEE against BSDF sampling alone, at equal time,
in a scene lit only by an emissive panel. Not registered in ctest: it measures.

    python3 bench_emissive_nee.py --memograph PATH [--scene DIR] [--size N] [--frames F]

DIR is a compare_scene.py output of units_area (DIR/export/scene.gltf: a white plane under a
Blender area light, which memograph imports as an emissive quad). A reference is rendered
with NEE at many samples; then each mode renders F frames with several seeds. Variance =
mean squared error per pixel against the reference; time = memograph's GPU time per frame x
frames. Efficiency = 1 / (variance x time); the printed ratio is the variance at equal time,
without NEE over with NEE.
"""

import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, '..'))
sys.dont_write_bytecode = True
from compare_nodes import read_pfm  # noqa: E402


def render(mg, scene, out, size, frames, paths, seed, nee):
    cmd = [mg, 'render', os.path.join(scene, 'export', 'scene.gltf'), '--materials',
           os.path.join(scene, 'export'), '--size', '%dx%d' % (size, size), '--frames',
           str(frames), '--paths', str(paths), '--bounces', '2', '--seed', str(seed), '--out', out]
    if not nee:
        cmd.append('--no-emissive-nee')
    r = subprocess.run(cmd, capture_output=True, text=True, check=True)
    ms = float(re.search(r'median ([0-9.eE+-]+) ms per frame', r.stdout + r.stderr).group(1))
    _, _, rows = read_pfm(out)
    return [c for row in rows for p in row for c in p], ms * frames


def main():
    p = argparse.ArgumentParser()
    p.add_argument('--memograph', required=True)
    p.add_argument('--scene', default='/tmp/memograph_scene_units_area')
    p.add_argument('--size', type=int, default=32)
    p.add_argument('--frames', type=int, default=16)
    p.add_argument('--seeds', type=int, default=4)
    a = p.parse_args()
    tmp = os.path.join(a.scene, 'bench')
    os.makedirs(tmp, exist_ok=True)
    ref, _ = render(a.memograph, a.scene, os.path.join(tmp, 'ref.pfm'), a.size, 256, 16, 99, True)
    result = {}
    for nee in (True, False):
        mse, time = 0.0, 0.0
        for seed in range(a.seeds):
            img, t = render(a.memograph, a.scene, os.path.join(tmp, 'run.pfm'), a.size, a.frames,
                            1, seed + 1, nee)
            mse += sum((x - y) ** 2 for x, y in zip(img, ref)) / len(img) / a.seeds
            time += t / a.seeds
        result[nee] = (mse, time)
        print('%-12s variance %.6g  GPU time %.2f ms  variance x time %.6g'
              % ('NEE' if nee else 'BSDF only', mse, time, mse * time))
    ratio = (result[False][0] * result[False][1]) / (result[True][0] * result[True][1])
    print('variance at equal time: %.1fx lower with emissive NEE (reference 4096 spp with NEE, '
          '%dx%d, %d spp per run, %d seeds)' % (ratio, a.size, a.size, a.frames, a.seeds))


if __name__ == '__main__':
    main()

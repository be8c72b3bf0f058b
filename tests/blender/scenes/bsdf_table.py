"""The per-BSDF error table against Cycles (docs/results.md, "BSDF lobes against Cycles"):

    python3 tests/blender/scenes/bsdf_table.py --memograph build/tools/memograph \\
        [--out DIR] [--keep-cycles]

Runs compare_scene.py for every bsdf_* scene (each BSDF tree on a sphere, and the room) into
DIR/<scene>, reads each one's result.json and prints a Markdown table: the mean LDR-FLIP and
the mean brightness difference (memograph - Cycles, relative), and whether both meet the
targets (0.05 and 2 %; the room is compared at 2048 samples a pixel, and the Transparent
ball's ctest allows more FLIP: compare_scene.CHECKS and BSDF_FLIP_LIMITS).
Exit 1 if a scene could not be rendered or failed its ctest's limits.
"""

import argparse
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True
import compare_scene  # noqa: E402


def main(argv=None):
    p = argparse.ArgumentParser(prog='bsdf_table.py')
    p.add_argument('--memograph', required=True)
    p.add_argument('--out', default='/tmp/memograph_bsdf_table')
    p.add_argument('--keep-cycles', action='store_true')
    args = p.parse_args(argv)
    scenes = sorted(s for s in compare_scene.CHECKS if s.startswith('bsdf_'))
    rows, failed = [], []
    for scene in scenes:
        out = os.path.join(args.out, scene)
        cmd = ['--scene', scene, '--memograph', args.memograph, '--out', out]
        code = compare_scene.main(cmd + (['--keep-cycles'] if args.keep_cycles else []))
        path = os.path.join(out, 'result.json')
        if not os.path.exists(path):
            failed.append(scene)
            rows.append('| %s | - | - | not rendered |' % scene)
            continue
        with open(path) as f:
            r = json.load(f)
        if code != 0:
            failed.append(scene)
        meets = r['flip'] <= compare_scene.BSDF_FLIP_LIMIT and abs(r['brightness']) <= 0.02
        rows.append('| %s | %.4f | %+.2f %% | %s |' % (
            scene, r['flip'], 100 * r['brightness'], 'yes' if meets else 'no'))
    print('| scene | mean LDR-FLIP (<= %.2f) | mean brightness vs Cycles (within 2 %%) | '
          'meets both |' % compare_scene.BSDF_FLIP_LIMIT)
    print('| --- | --- | --- | --- |')
    print('\n'.join(rows))
    if failed:
        print('bsdf_table: missed or failed: %s' % ', '.join(failed))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())

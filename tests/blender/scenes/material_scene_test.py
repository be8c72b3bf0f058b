"""The material-heavy example scene end to end, with no hand-editing (issue 41, part 4):

    python3 material_scene_test.py --memograph PATH [--out DIR] [--blender PATH]

builds the .blend from nothing with examples/blender/make_material_scene.py (and its camera
path), exports it with `memograph import-blender --scene`, compiles every exported material
and reads its cut metadata, then renders a tiny image along the first frames of the camera
path on whatever Vulkan device is there (lavapipe in CI). Fails when Blender is missing, when
a material is missing, fails to compile or lacks cut metadata, or when the render fails or
writes no finite image. It checks that the scene works, not how it looks.
"""

import argparse
import glob
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, '..', '..', '..', 'examples', 'blender', 'make_material_scene.py')
# The materials make_material_scene.py builds: all must come out as graphs.
MATERIALS = {'Bricks', 'CarPaint', 'Cells4D', 'GlazedCeramic', 'Label', 'Marble', 'Moss',
             'PlasterWall', 'RidgedRock', 'RustedMetal', 'TerrazzoFloor', 'Wood'}


def fail(msg):
    print('FAIL: ' + msg)
    return 1


def run(cmd, env=None):
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    return r.returncode, r.stdout + r.stderr


def blender_env():
    """Debian's Blender takes its Python home from the first python on PATH: under a pyenv
    interpreter it would miss Debian's numpy, which the glTF exporter needs (as in
    compare_scene.py). Give Blender, and import-blender which starts it, the PATH without the
    running interpreter's bin."""
    env = dict(os.environ)
    own_bin = os.path.dirname(os.path.realpath(sys.executable))
    env['PATH'] = os.pathsep.join(d for d in env.get('PATH', '').split(os.pathsep)
                                  if d and os.path.realpath(d) != own_bin)
    return env


def pfm_values(path):
    data = open(path, 'rb').read()
    m = re.match(rb'(P[Ff])\s+(\d+)\s+(\d+)\s+(\S+)\s', data)
    ch = 3 if m.group(1) == b'PF' else 1
    n = int(m.group(2)) * int(m.group(3)) * ch
    endian = '<' if float(m.group(4)) < 0 else '>'
    return int(m.group(2)), int(m.group(3)), struct.unpack_from(endian + '%df' % n, data,
                                                                 m.end())


def main(argv=None):
    p = argparse.ArgumentParser(prog='material_scene_test.py')
    p.add_argument('--memograph', required=True)
    p.add_argument('--out', default='/tmp/memograph_material_scene')
    p.add_argument('--blender', default=None)
    args = p.parse_args(argv)
    out = os.path.abspath(args.out)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    blender = args.blender or shutil.which('blender')
    if not blender:
        return fail('Blender 3.4 not found on PATH: run tools/setup.sh (or pass --blender)')
    env = blender_env()
    blend, camera = os.path.join(out, 'materials.blend'), os.path.join(out, 'materials.camera')
    export = os.path.join(out, 'export')

    t0 = time.time()
    code, log = run([blender, '-b', '--factory-startup', '--python-exit-code', '1', '--python',
                     SCRIPT, '--', blend, '--camera-path', camera], env)
    if code != 0 or not os.path.exists(blend) or not os.path.exists(camera):
        return fail('make_material_scene.py exited with %d:\n%s' % (code, log[-2000:]))

    t1 = time.time()
    code, log = run([args.memograph, 'import-blender', blend, '--out', export, '--scene'], env)
    if code != 0:
        return fail('import-blender --scene exited with %d:\n%s' % (code, log[-3000:]))
    graphs = {os.path.basename(g)[:-len('.mgraph')]
              for g in glob.glob(os.path.join(export, '*.mgraph'))}
    if graphs != MATERIALS:
        return fail('exported materials %s, expected %s' % (sorted(graphs), sorted(MATERIALS)))
    if ' 0 error(s)' not in log:
        return fail('import-blender reported errors:\n' + log[-3000:])

    t_import = time.time()
    # Every material compiles, and its metadata carries the cut the cache would take.
    compiled = os.path.join(out, 'compiled')
    code, log = run([args.memograph, 'compile', *sorted(glob.glob(os.path.join(export,
                                                                                '*.mgraph'))),
                     '-o', compiled, '--target', 'glsl', '--quiet'])
    if code != 0:
        return fail('memograph compile exited with %d:\n%s' % (code, log[-3000:]))
    for name in sorted(MATERIALS):
        with open(os.path.join(compiled, name + '.json')) as f:
            meta = json.load(f)
        if not all(k in meta for k in ('cutDomain', 'cutWidth', 'cutCostShare')):
            return fail('%s.json lacks cut metadata: %s' % (name, sorted(meta)))
        print('  %-14s cutDomain %-6s cutWidth %d cutCostShare %.3f'
              % (name, meta['cutDomain'], meta['cutWidth'], meta['cutCostShare']))

    # A tiny render along the first two cameras of the path: the scene loads, every material
    # links into the renderer, and frames finish.
    t2 = time.time()
    image, stats = os.path.join(out, 'render.pfm'), os.path.join(out, 'render.csv')
    code, log = run([args.memograph, 'render', os.path.join(export, 'scene.gltf'), '--materials',
                     export, '--camera-path', camera, '--size', '32x18', '--frames', '2',
                     '--out', image, '--stats', stats])
    if code != 0:
        return fail('memograph render exited with %d:\n%s' % (code, log[-3000:]))
    w, h, values = pfm_values(image)
    if (w, h) != (32, 18) or not all(math.isfinite(v) for v in values) or max(values) <= 0:
        return fail('the render wrote no finite, lit 32x18 image (%dx%d)' % (w, h))
    with open(stats) as f:
        header = f.readline().strip().split(',')
        first = f.readline().strip().split(',')
    materials = int(first[header.index('materials')])
    # The renderer's material count holds the scene's twelve (and its own default, if any).
    if materials < len(MATERIALS):
        return fail('the renderer linked %d materials, fewer than the scene\'s %d'
                    % (materials, len(MATERIALS)))
    t3 = time.time()
    print('material_scene: %d materials; Blender %.1f s, import %.1f s, compile %.1f s, '
          'render %.1f s' % (len(MATERIALS), t1 - t0, t_import - t1, t2 - t_import, t3 - t2))
    return 0


if __name__ == '__main__':
    sys.exit(main())

#!/usr/bin/env python3
"""Exporter end-to-end tests: combined graphs against Cycles, every warning path,
bad input, the add-on zip. Needs Blender 3.4 (tools/setup.sh installs it) and a built
memograph; without Blender it FAILS with a clear message, it never skips.

    python3 tests/blender/combined/run_combined.py --memograph build/tools/memograph \
        [--zip build/tools/blender/memograph_export.zip] [--nodes nodes] [--out DIR]
        [--only combined,warnings,errors,example,addon]

1. build_scenes.py (inside Blender) builds combined.blend / warnings.blend and bakes the
   combined materials with Cycles (Emit, 64x64 float).
2. `memograph import-blender combined.blend` exports them (twice: the files must be
   byte-identical), `memograph bake` evaluates them, and each material's emission must
   match Cycles within its tolerance.
3. `memograph import-blender warnings.blend` must report each expected warning (material,
   node, message) on stderr, and every exported graph must compile.
4. Errors: a material without output, an unknown --materials name, a non-.blend file, a
   truncated .blend, a missing file, Blender missing from PATH: exit 1 with a clear message.
5. The committed example (examples/blender/procedural.blend) exports cleanly and compiles.
6. The add-on zip installs and enables in Blender (bpy.ops.preferences.addon_install) and
   File > Export > memograph works through its operator.
"""

import argparse
import array
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
SIZE = 64
# Per-material tolerance (max abs error per channel). Analytic graphs: 1e-3.
# Images: 8-bit PNG decoded and linearised by Cycles (OCIO) vs memograph's SRGBToLinear on
# the stored value/255: the same texel, so 1e-3 too.
TOLERANCE = {}
DEFAULT_TOLERANCE = 1e-3

failures = []


def check(ok, what):
    what = ' | '.join(l for l in what.splitlines() if l.strip())
    print('%s: %s' % ('ok  ' if ok else 'FAIL', what))
    if not ok:
        failures.append(what)
    return ok


def run(cmd, env=None, timeout=300):
    t0 = time.time()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       env=env, timeout=timeout)
    return p.returncode, p.stdout, p.stderr, time.time() - t0


def read_pfm(path):
    with open(path, 'rb') as f:
        data = f.read()
    parts = data.split(b'\n', 3)
    w, h = (int(x) for x in parts[1].split())
    scale = float(parts[2])
    channels = 3 if parts[0] == b'PF' else 1
    a = array.array('f')
    a.frombytes(parts[3][:w * h * channels * 4])
    if (scale < 0) != (sys.byteorder == 'little'):
        a.byteswap()
    return w, h, channels, a


def compare(ref_path, got_path):
    rw, rh, rc, ref = read_pfm(ref_path)
    gw, gh, gc, got = read_pfm(got_path)
    if (rw, rh) != (gw, gh):
        return None, 'size %dx%d vs %dx%d' % (gw, gh, rw, rh)
    worst, where = 0.0, None
    for p in range(rw * rh):
        for c in range(3):
            r = ref[p * rc + (c if rc == 3 else 0)]
            g = got[p * gc + (c if gc == 3 else 0)]
            e = abs(r - g)
            if e > worst or e != e:
                worst, where = e, (p % rw, p // rw, c, r, g)
    return worst, where


def blender_path(args):
    if args.blender:
        return args.blender if os.access(args.blender, os.X_OK) else None
    return shutil.which('blender')


def import_blender(args, blend, out, extra=(), env=None):
    cmd = [args.memograph, 'import-blender', blend, '--out', out]
    if args.blender:
        cmd += ['--blender', args.blender]
    return run(cmd + list(extra), env=env)


def parse_warnings(stderr):
    """{material: [(node, message)]} from `warning: MAT: NODE: MSG` lines."""
    found = {}
    for line in stderr.splitlines():
        if not line.startswith('warning: '):
            continue
        parts = line[len('warning: '):].split(': ', 2)
        if len(parts) == 3:
            node = '' if parts[1] == '(material)' else parts[1]
            found.setdefault(parts[0], []).append((node, parts[2]))
    return found


def test_combined(args, work):
    out1 = os.path.join(work, 'export')
    out2 = os.path.join(work, 'export_again')
    rc, so, se, secs = import_blender(args, os.path.join(work, 'combined.blend'), out1)
    check(rc == 0, 'import-blender combined.blend exits 0 (got %d)%s' % (rc, '' if rc == 0
                                                                         else ': ' + se[-2000:]))
    if se.strip():
        print('  its warnings:\n    ' + '\n    '.join(se.strip().splitlines()))
    rc2, _, _, _ = import_blender(args, os.path.join(work, 'combined.blend'), out2)
    graphs = sorted(glob.glob(os.path.join(out1, '*.mgraph')))
    same = rc2 == 0 and all(
        open(g, 'rb').read() == open(os.path.join(out2, os.path.basename(g)), 'rb').read()
        for g in graphs)
    check(same and graphs, 'a second export is byte-identical (%d graphs)' % len(graphs))
    check(os.path.isfile(os.path.join(out1, 'textures', 'mg_C_image_srgb.png')),
          'the packed image is unpacked next to the graphs (textures/mg_C_image_srgb.png)')
    index = json.load(open(os.path.join(out1, 'index.json')))
    check(index['materials'].get('C_reroutes', {}).get('file') == 'C_reroutes.mgraph',
          'index.json maps Blender names to graph files')
    mg = os.path.join(work, 'mg')
    cmd = [args.memograph, 'bake'] + graphs + ['--size', '%dx%d' % (SIZE, SIZE), '--format',
                                               'pfm', '--out', mg]
    if args.nodes:
        cmd += ['--nodes', args.nodes]
    rc, so, se, secs = run(cmd, timeout=600)
    if rc != 0:
        print('  memograph bake exit %d:\n%s' % (rc, (so + se)[-3000:]))
    rows = []
    for ref in sorted(glob.glob(os.path.join(work, 'cycles', '*.pfm'))):
        name = os.path.splitext(os.path.basename(ref))[0]
        got = os.path.join(mg, name + '_emission.pfm')
        tol = TOLERANCE.get(name, DEFAULT_TOLERANCE)
        if not os.path.isfile(got):
            check(False, '%s: memograph bake wrote no %s' % (name, os.path.basename(got)))
            rows.append((name, None, tol))
            continue
        worst, where = compare(ref, got)
        rows.append((name, worst, tol))
        check(worst is not None and worst <= tol,
              '%s: max abs error %.3g <= %g%s' % (name, worst if worst is not None else -1,
                                                 tol, '' if worst is not None and worst <= tol
                                                 else ' (pixel, channel, cycles, memograph: %r)'
                                                 % (where,)))
    return rows


def test_warnings(args, work):
    exp = json.load(open(os.path.join(work, 'expected.json')))['warnings']
    names = sorted(n for n in exp)
    out = os.path.join(work, 'export_warnings')
    rc, so, se, _ = import_blender(args, os.path.join(work, 'warnings.blend'), out,
                                   ['--materials'] + names)
    check(rc == 0, 'import-blender warnings.blend (W_* materials) exits 0 (got %d)' % rc)
    found = parse_warnings(se)
    for mat in names:
        got = found.get(mat, [])
        for node, text in exp[mat]:
            hit = any(n == node and text in m for n, m in got)
            check(hit, 'warning for %s / %s: "%s"%s' % (mat, node or '(material)', text,
                                                        '' if hit else ' -- got: %r' % got))
    # Everything exported, even with warnings, must compile.
    graphs = sorted(glob.glob(os.path.join(out, '*.mgraph')))
    check(len(graphs) == len(names), 'one graph per W_* material (%d of %d)'
          % (len(graphs), len(names)))
    cmd = [args.memograph, 'compile'] + graphs + ['--target', 'both', '-o',
                                                  os.path.join(work, 'compiled_w')]
    if args.nodes:
        cmd += ['--nodes', args.nodes]
    rc, so, se, _ = run(cmd)
    check(rc == 0, 'the W_* exports compile%s' % ('' if rc == 0 else ':\n' + se[-3000:]))


def test_errors(args, work):
    blend = os.path.join(work, 'warnings.blend')
    out = os.path.join(work, 'export_errors')
    rc, so, se, _ = import_blender(args, blend, out, ['--materials', 'E_no_output'])
    check(rc == 1 and 'E_no_output' in se and 'no Material Output' in se,
          'a material without Material Output: exit 1 naming it (got %d: %s)' % (rc, se[-300:]))
    rc, so, se, _ = import_blender(args, blend, out, ['--materials', 'Nope'])
    check(rc == 1 and "no material named 'Nope'" in se,
          'an unknown --materials name: exit 1 (got %d: %s)' % (rc, se[-300:]))
    bad = os.path.join(work, 'not_a_blend.blend')
    with open(bad, 'w') as f:
        f.write('this is not a blend file\n')
    rc, so, se, _ = import_blender(args, bad, out)
    check(rc == 1 and 'not a .blend file' in se, 'a text file: exit 1 "not a .blend file" '
          '(got %d: %s)' % (rc, se.strip()))
    trunc = os.path.join(work, 'truncated.blend')
    with open(os.path.join(work, 'combined.blend'), 'rb') as f:
        head = f.read(4096)
    with open(trunc, 'wb') as f:
        f.write(head)
    rc, so, se, _ = import_blender(args, trunc, out)
    check(rc == 1 and 'error' in (so + se).lower(),
          'a truncated .blend: exit 1 with an error (got %d: %s)' % (rc, (so + se).strip()[-400:]))
    rc, so, se, _ = import_blender(args, os.path.join(work, 'missing.blend'), out)
    check(rc == 1 and 'no such file' in se, 'a missing .blend: exit 1 (got %d)' % rc)
    env = dict(os.environ, PATH='/nonexistent')
    rc, so, se, _ = run([args.memograph, 'import-blender', blend, '--out', out], env=env)
    check(rc == 1 and 'Blender was not found on PATH' in se,
          'Blender missing from PATH: exit 1 with how to install it (got %d: %s)'
          % (rc, se.strip()))
    rc, so, se, _ = run([args.memograph, 'import-blender', blend, '--out', out, '--blender',
                         '/nonexistent/blender'])
    check(rc == 1 and 'not an executable' in se, '--blender to nothing: exit 1 (got %d)' % rc)
    rc, so, se, _ = run([args.memograph, 'import-blender', blend])
    check(rc == 2, 'no --out: usage error, exit 2 (got %d)' % rc)


def test_example(args, work):
    """The committed example exports without warnings, and its graphs compile."""
    out = os.path.join(work, 'export_example')
    rc, so, se, _ = import_blender(args, os.path.join(REPO, 'examples', 'blender',
                                                      'procedural.blend'), out)
    graphs = sorted(glob.glob(os.path.join(out, '*.mgraph')))
    check(rc == 0 and not se.strip() and len(graphs) == 4,
          'examples/blender/procedural.blend exports 4 graphs without warnings (rc %d: %s)'
          % (rc, se.strip()[-500:]))
    cmd = [args.memograph, 'compile'] + graphs + ['--target', 'both', '-o',
                                                  os.path.join(work, 'compiled_example')]
    if args.nodes:
        cmd += ['--nodes', args.nodes]
    rc, so, se, _ = run(cmd)
    check(rc == 0 and graphs, 'the example\'s graphs compile%s' % ('' if rc == 0 else ': ' + se[-1500:]))


ADDON_CHECK = r'''
import bpy, os, sys, addon_utils
zip_path, out = sys.argv[sys.argv.index('--') + 1:]
bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
bpy.ops.preferences.addon_enable(module='memograph_export')
ok = hasattr(bpy.types, 'EXPORT_SCENE_OT_memograph')
funcs = [f.__name__ for f in bpy.types.TOPBAR_MT_file_export._dyn_ui_initialize()]
bpy.ops.wm.open_mainfile(filepath=os.path.join(out, 'combined.blend'))
r = bpy.ops.export_scene.memograph(directory=os.path.join(out, 'export_addon'))
print('ADDON', ok, 'menu_func_export' in funcs, r)
sys.stdout.flush()
os._exit(0)
'''


def test_addon(args, work, blender):
    if not check(args.zip and os.path.isfile(args.zip), 'the add-on zip exists (%s)' % args.zip):
        return
    names = zipfile.ZipFile(args.zip).namelist()
    for need in ('memograph_export/__init__.py', 'memograph_export/exporter.py',
                 'memograph_export/spec.py', 'memograph_export/specs/__init__.py',
                 'memograph_export/ui.py'):
        check(need in names, 'the zip holds %s' % need)
    check(not any('__pycache__' in n for n in names), 'the zip holds no __pycache__')
    script = os.path.join(work, 'addon_check.py')
    with open(script, 'w') as f:
        f.write(ADDON_CHECK)
    user = os.path.join(work, 'blender_user')  # keep the install out of ~/.config
    env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(user, 'scripts'),
               BLENDER_USER_CONFIG=os.path.join(user, 'config'))
    rc, so, se, _ = run([blender, '-b', '--factory-startup', '--python', script, '--',
                         os.path.abspath(args.zip), work], env=env)
    line = [l for l in so.splitlines() if l.startswith('ADDON')]
    check(rc == 0 and line and line[0] == "ADDON True True {'FINISHED'}",
          'the zip installs and enables; File > Export > memograph runs (%s)'
          % (line or (so + se)[-1500:]))
    check(len(glob.glob(os.path.join(work, 'export_addon', '*.mgraph'))) >= 10,
          'the operator wrote the graphs')


def main(argv=None):
    p = argparse.ArgumentParser()
    p.add_argument('--memograph', required=True)
    p.add_argument('--blender', default=None)
    p.add_argument('--zip', default=None)
    p.add_argument('--nodes', default=None)
    p.add_argument('--out', default=None)
    p.add_argument('--only', default='combined,warnings,errors,example,addon')
    args = p.parse_args(argv)
    args.memograph = os.path.abspath(args.memograph)
    only = set(args.only.split(','))
    blender = blender_path(args)
    if blender is None:
        print('FAIL: Blender (3.4) not found on PATH%s: run tools/setup.sh (it installs the '
              'Debian package "blender"). These tests never skip.'
              % (' (--blender %s)' % args.blender if args.blender else ''))
        return 1
    work = os.path.abspath(args.out or tempfile.mkdtemp(prefix='memograph_combined_'))
    if os.path.isdir(work):
        shutil.rmtree(work)
    os.makedirs(work)
    t0 = time.time()
    rc, so, se, secs = run([blender, '-b', '--factory-startup', '--python',
                            os.path.join(HERE, 'build_scenes.py'), '--', '--out', work],
                           timeout=600)
    if not check(rc == 0 and 'build_scenes: done' in so,
                 'Blender builds and bakes the scenes (%.1f s)' % secs):
        print((so + se)[-3000:])
        return 1
    if 'combined' in only:
        test_combined(args, work)
    if 'warnings' in only:
        test_warnings(args, work)
    if 'errors' in only:
        test_errors(args, work)
    if 'example' in only:
        test_example(args, work)
    if 'addon' in only:
        test_addon(args, work, blender)
    print('\nrun_combined: %d failure(s) in %.1f s; work folder %s'
          % (len(failures), time.time() - t0, work))
    for f in failures:
        print('  FAIL ' + f.splitlines()[0][:300])
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())

#!/usr/bin/env python3
"""Per-node Cycles comparison: Cycles vs `memograph bake`.

    python3 tests/blender/compare_nodes.py [--cases noise,math] [--match REGEX]
        [--out DIR] [--memograph PATH] [--nodes DIR] [--handwritten DIR] [--table FILE]

1. Blender (one process) runs build_and_bake.py: every selected case (tests/blender/cases/)
   is built on a UV plane, baked by Cycles (EMIT, 64x64 float) to DIR/cycles/<case>.pfm and
   exported by the add-on to DIR/export/<case>/.
2. `memograph bake <graphs> --size 64x64 --format pfm --out DIR/mg` evaluates the exports
   (a hand-written DIR2/<case>.mgraph given with --handwritten wins over the export).
3. Both images are compared per channel: max and mean absolute error against the case's
   tolerance (1e-3 analytic, 1e-2 noise/Voronoi/Musgrave unless the case says otherwise).

Exits 0 only if every selected case ran and passed. Plain python3, standard library only.
"""
import argparse
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SIZE = 64
NOT_FOUND = 'Blender 3.4 not found: run tools/setup.sh'


def read_pfm(path):
    """(width, height, rows) with rows[j][i] = (r, g, b) and row 0 = the bottom row (the
    PFM order, which is also Blender's). Handles PF/Pf and both byte orders."""
    with open(path, 'rb') as f:
        data = f.read()
    m = re.match(rb'(P[Ff])\s+(\d+)\s+(\d+)\s+(\S+)\s', data)
    if not m:
        raise ValueError('%s: not a PFM file' % path)
    w, h, scale = int(m.group(2)), int(m.group(3)), float(m.group(4))
    ch = 3 if m.group(1) == b'PF' else 1
    fmt = ('<' if scale < 0 else '>') + '%df' % (w * h * ch)
    vals = struct.unpack_from(fmt, data, m.end())
    rows = []
    for j in range(h):
        row = []
        for i in range(w):
            k = (j * w + i) * ch
            row.append(tuple(vals[k:k + 3]) if ch == 3 else (vals[k],) * 3)
        rows.append(row)
    return w, h, rows


def compare(ref, got):
    """Per channel max and mean absolute error, and the worst pixel (i, j, channel)."""
    w, h = len(ref[0]), len(ref)
    maxe, sume, worst = [0.0] * 3, [0.0] * 3, [None] * 3
    nan = False
    for j in range(h):
        for i in range(w):
            a, b = ref[j][i], got[j][i]
            for c in range(3):
                d = abs(a[c] - b[c])
                if d != d:  # NaN on either side (a NaN in both counts as equal)
                    if (a[c] != a[c]) and (b[c] != b[c]):
                        continue
                    nan = True
                    d = float('inf')
                sume[c] += d
                if d > maxe[c] or worst[c] is None:
                    maxe[c], worst[c] = d, (i, j)
    return maxe, [s / (w * h) for s in sume], worst, nan


def material_name(graph_path):
    """The material name `memograph bake` uses: the `material NAME;` statement, else the
    file stem (docs/guide/graph-format.md)."""
    with open(graph_path, encoding='utf-8', errors='replace') as f:
        text = f.read()
    m = re.search(r'^\s*material\s+([A-Za-z_][A-Za-z0-9_]*)\s*;', text, re.M)
    return m.group(1) if m else os.path.splitext(os.path.basename(graph_path))[0]


def default_memograph():
    for d in ('build', 'build-bake'):
        p = os.path.join(REPO, d, 'tools', 'memograph')
        if os.access(p, os.X_OK):
            return p
    return os.path.join(REPO, 'build', 'tools', 'memograph')


def fmt_err(x):
    return 'inf' if x == float('inf') else '%.2e' % x


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--cases', default='', help='comma-separated families (default: all)')
    p.add_argument('--match', default=None, help='regex (re.search) on case names')
    p.add_argument('--out', default=None, help='work folder (default: a new temp folder)')
    p.add_argument('--blender', default=None, help='Blender binary (default: blender on PATH)')
    p.add_argument('--memograph', default=None, help='memograph binary (default: the build '
                   'tree\'s tools/memograph)')
    p.add_argument('--nodes', default=None, help='passed to memograph bake --nodes')
    p.add_argument('--handwritten', default=None, help='folder of <case>.mgraph files used '
                   'instead of the export (for node work before the exporter handles a node)')
    p.add_argument('--reuse-cycles', action='store_true', help='skip Blender when --out '
                   'already holds its cases.json (iterate on memograph nodes only)')
    p.add_argument('--no-export', action='store_true', help='Blender bakes only (use with '
                   '--handwritten)')
    p.add_argument('--exr', action='store_true', help='Blender also saves its bakes as '
                   'OUT/cycles/<case>.exr')
    p.add_argument('--table', default=None, help='write the Markdown result table here')
    p.add_argument('--list', action='store_true', help='list the selected cases and exit')
    p.add_argument('--blender-budget', type=float, default=300.0, help='fail when the '
                   'Blender part takes longer (seconds; the whole Blender part of '
                   'the suite stays under 5 minutes)')
    p.add_argument('--any-blender', action='store_true', help='accept a Blender other than 3.4')
    return p.parse_args(argv)


def select_cases(args):
    sys.path.insert(0, HERE)
    import cases as registry
    errors = []
    fams = [f for f in args.cases.split(',') if f] or None
    return registry.all_cases(fams, args.match, errors=errors), errors


def run_blender(args, out):
    blender = args.blender or shutil.which('blender')
    if not blender or not os.access(blender, os.X_OK):
        sys.stdout.flush()
        print('compare_nodes: ERROR: ' + NOT_FOUND, file=sys.stderr)
        sys.exit(2)
    cmd = [blender, '-b', '--factory-startup', '--python-exit-code', '1', '--python',
           os.path.join(HERE, 'build_and_bake.py'), '--', '--out', out]
    if args.cases:
        cmd += ['--cases', args.cases]
    if args.match:
        cmd += ['--match', args.match]
    if args.no_export:
        cmd += ['--no-export']
    if args.exr:
        cmd += ['--exr']
    t0 = time.time()
    log_path = os.path.join(out, 'blender.log')
    with open(log_path, 'w') as log:
        rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, cwd=REPO)
    secs = time.time() - t0
    with open(log_path, errors='replace') as f:
        lines = f.read().splitlines()
    for ln in lines:  # the harness's own lines and Python errors, not Cycles' progress
        if ln.startswith('build_and_bake:') or 'Error' in ln or 'Traceback' in ln:
            print('  ' + ln)
    if rc != 0 or not os.path.exists(os.path.join(out, 'cases.json')):
        print('compare_nodes: ERROR: Blender exited with %d; last lines of %s:' % (rc, log_path))
        for ln in lines[-30:]:
            print('  ' + ln)
        sys.exit(3)
    return secs


def run_bake(args, out, graphs_by_normal):
    """One `memograph bake` call per plane normal (None: the default +Z), all into DIR/mg;
    returns the time and, per normal, what went wrong."""
    memograph = args.memograph or default_memograph()
    mg_out = os.path.join(out, 'mg')
    shutil.rmtree(mg_out, ignore_errors=True)
    os.makedirs(mg_out)
    if not any(graphs_by_normal.values()):
        return 0.0, {}
    if not os.access(memograph, os.X_OK):
        missing = 'memograph binary not found: %s (build it or pass --memograph)' % memograph
        return 0.0, {normal: missing for normal in graphs_by_normal}
    t0 = time.time()
    log_path = os.path.join(out, 'bake.log')
    problems = {}
    with open(log_path, 'w') as log:
        for normal in sorted(graphs_by_normal, key=lambda n: (n is not None, n or ())):
            graphs = sorted(set(graphs_by_normal[normal]))
            cmd = [memograph, 'bake'] + graphs + ['--size', '%dx%d' % (SIZE, SIZE), '--format',
                                                  'pfm', '--out', mg_out]
            if normal is not None:
                cmd += ['--normal', ','.join(repr(float(x)) for x in normal)]
            if args.nodes:
                cmd += ['--nodes', args.nodes]
            log.write(' '.join(cmd) + '\n')
            log.flush()
            rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, cwd=REPO)
            if rc != 0:
                problems[normal] = 'memograph bake exited with %d (see %s)' % (rc, log_path)
    return time.time() - t0, problems


def bake_errors_for(out, graph):
    """The lines of bake.log that name this graph (its errors)."""
    try:
        with open(os.path.join(out, 'bake.log'), errors='replace') as f:
            # Without the command lines (one per bake call), which name every graph.
            lines = [ln for ln in f.read().splitlines() if ' bake ' not in ln]
    except OSError:
        return ''
    base = os.path.basename(graph)
    hits = [ln for ln in lines if base in ln and 'error' in ln.lower()]
    return ' | '.join(hits[:3])


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    selected, fam_errors = select_cases(args)
    if args.list:
        for c in selected:
            print('%-40s %-10s %-28s %s' % (c.name, c.family, c.node, c.mode()))
        return 0
    if not selected and not fam_errors:
        print('compare_nodes: no case selected')
        return 1
    out = os.path.abspath(args.out or tempfile.mkdtemp(prefix='memograph_nodes_'))
    os.makedirs(out, exist_ok=True)
    print('compare_nodes: %d cases, work folder %s' % (len(selected), out))

    t_all = time.time()
    meta_path = os.path.join(out, 'cases.json')
    blender_secs = 0.0
    if not (args.reuse_cycles and os.path.exists(meta_path)):
        if os.path.exists(meta_path):
            os.remove(meta_path)
        blender_secs = run_blender(args, out)
    with open(meta_path) as f:
        meta = json.load(f)
    if not meta['blender'].startswith('3.4') and not args.any_blender:
        print('compare_nodes: ERROR: Blender %s ran; the reference is Blender 3.4 (%s)' % (
            meta['blender'], NOT_FOUND))
        return 2
    records = {r['name']: r for r in meta['cases']}

    # Which graph bakes each case: hand-written first, then the export.
    graphs, problems = {}, {}
    for c in selected:
        rec = records.get(c.name)
        if rec is None:
            problems[c.name] = 'not in %s (rerun without --reuse-cycles)' % meta_path
            continue
        if 'error' in rec:
            problems[c.name] = rec['error']
            continue
        hw = os.path.join(args.handwritten, c.name + '.mgraph') if args.handwritten else None
        if hw and os.path.exists(hw):
            graphs[c.name] = os.path.abspath(hw)
        elif rec.get('mgraph'):
            graphs[c.name] = rec['mgraph']
        else:
            exp = rec.get('export', '?')
            problems[c.name] = ('no graph (export skipped; see above)'
                                if exp.startswith('skipped') else 'no graph: export ' + exp)
    # The tilted plane's face normal as Blender computed it (build_and_bake.py records it),
    # closer to Cycles' own than the case's rounded one.
    graphs_by_normal, normal_of = {}, {}
    for c in selected:
        if c.name in graphs:
            normal = records[c.name].get('normal')
            key = tuple(float(x) for x in normal) if normal is not None else None
            graphs_by_normal.setdefault(key, []).append(graphs[c.name])
            normal_of[c.name] = key
    bake_secs, bake_problems = run_bake(args, out, graphs_by_normal)

    results = []
    for c in selected:
        r = {'case': c, 'maxe': None, 'meane': None, 'pass': False, 'why': problems.get(c.name),
             'output': records.get(c.name, {}).get('output') or c.output or ''}
        results.append(r)
        if r['why']:
            continue
        g = graphs[c.name]
        mg_path = os.path.join(out, 'mg', material_name(g) + '_emission.pfm')
        if not os.path.exists(mg_path):
            r['why'] = 'memograph bake wrote no %s%s' % (
                os.path.basename(mg_path),
                ': ' + (bake_errors_for(out, g) or bake_problems.get(normal_of.get(c.name))
                       or 'see bake.log'))
            continue
        try:
            _, _, ref = read_pfm(records[c.name]['cycles'])
            w, h, got = read_pfm(mg_path)
            if (w, h) != (SIZE, SIZE):
                raise ValueError('memograph image is %dx%d' % (w, h))
        except (OSError, ValueError, struct.error) as e:
            r['why'] = 'reading images: %s' % e
            continue
        maxe, meane, worst, nan = compare(ref, got)
        r.update(maxe=maxe, meane=meane)
        r['pass'] = not nan and max(maxe) <= c.max_error
        if not r['pass']:
            ch = max(range(3), key=lambda k: maxe[k])
            i, j = worst[ch]
            r['why'] = ('worst pixel (%d,%d) uv=(%.5f,%.5f) channel %s: cycles %r memograph %r%s'
                        % (i, j, (i + 0.5) / SIZE, (j + 0.5) / SIZE, 'RGB'[ch],
                           tuple(round(x, 6) for x in ref[j][i]),
                           tuple(round(x, 6) for x in got[j][i]),
                           ' (NaN differs)' if nan else ''))
            warns = records[c.name].get('export_warnings') or []
            if warns:
                r['why'] += '; export warning%s: %s' % ('s' if len(warns) > 1 else '',
                                                        ' / '.join(warns[:3]))

    # Report.
    print()
    print('%-36s %-24s %-8s %-9s %-9s %-9s %-7s %s' % (
        'case', 'node', 'output', 'max R', 'max G', 'max B', 'tol', 'result'))
    for r in results:
        c = r['case']
        errs = [fmt_err(x) for x in r['maxe']] if r['maxe'] else ['-'] * 3
        status = 'pass' if r['pass'] else ('FAIL' if r['maxe'] else 'NOT RUN')
        print('%-36s %-24s %-8s %-9s %-9s %-9s %-7g %s' % (
            c.name, c.node.replace('ShaderNode', ''), r['output'], errs[0], errs[1], errs[2],
            c.max_error, status))
        if r['why']:
            print('    ' + r['why'])
    for fam, msg in fam_errors:
        print('FAMILY %s failed to load: %s' % (fam, msg))
    n_pass = sum(r['pass'] for r in results)
    n_fail = sum(1 for r in results if not r['pass'] and r['maxe'])
    n_notrun = sum(1 for r in results if not r['maxe'])
    total = time.time() - t_all
    print('\ncompare_nodes: %d passed, %d failed, %d not run%s; Blender %.1fs, memograph bake '
          '%.1fs, total %.1fs (work folder %s)' % (
              n_pass, n_fail, n_notrun,
              ', %d families failed to load' % len(fam_errors) if fam_errors else '',
              blender_secs, bake_secs, total, out))
    if meta.get('export_skipped'):
        print('compare_nodes: export was skipped: %s' % meta['export_skipped'])
    if args.table:
        write_table(args.table, results, meta, blender_secs, bake_secs, fam_errors, args.cases,
                    out)
    over = blender_secs > args.blender_budget
    if over:
        print('compare_nodes: FAIL: the Blender part took %.1fs, over the %gs budget' % (
            blender_secs, args.blender_budget))
    return 0 if n_pass == len(results) and not fam_errors and not over else 1


def table_name(path):
    full = os.path.abspath(path)
    rel = os.path.relpath(full, REPO)
    return full if rel.startswith('..') else rel


def write_table(path, results, meta, blender_secs, bake_secs, fam_errors, families, out):
    lines = [
        '# Blender node accuracy: Cycles against memograph bake',
        '',
        'The current per-node accuracy, generated by `python3 tests/blender/compare_nodes.py%s '
        '--table %s` ([how it works](blender.md#node-accuracy-against-cycles)). Each case '
        'bakes one node output on a UV '
        'plane with Cycles (Blender %s, Emit bake, %dx%d float) and with `memograph bake` '
        'from the add-on\'s export; the columns are the maximum absolute error per channel '
        '(mean in parentheses for failures).' % (
            ' --cases ' + families if families else '', table_name(path), meta['blender'],
            SIZE, SIZE),
        '',
        '| case | node | mode | output | max err R | max err G | max err B | tolerance | pass |',
        '|---|---|---|---|---|---|---|---|---|',
    ]
    for r in results:
        c = r['case']
        if r['maxe']:
            errs = [fmt_err(x) for x in r['maxe']]
            if not r['pass']:
                errs = ['%s (%s)' % (e, fmt_err(m)) for e, m in zip(errs, r['meane'])]
            ok = 'yes' if r['pass'] else '**no**'
        else:
            errs = ['-'] * 3
            ok = '**not run**'
        mode = c.mode().replace('|', '\\|')
        lines.append('| %s | %s | %s | %s | %s | %s | %s | %g | %s |' % (
            c.name, c.node.replace('ShaderNode', ''), mode, r['output'], errs[0], errs[1],
            errs[2], c.max_error, ok))
    lines.append('')
    n_pass = sum(r['pass'] for r in results)
    lines.append('%d of %d cases pass. Blender part: %.1f s; memograph bake: %.1f s.' % (
        n_pass, len(results), blender_secs, bake_secs))
    fams = {}
    for r in results:
        f = fams.setdefault(r['case'].family, [0, 0, 0])
        f[0 if r['pass'] else 1 if r['maxe'] else 2] += 1
    lines += ['', '| family | pass | fail | not run |', '|---|---|---|---|']
    lines += ['| %s | %d | %d | %d |' % (k, v[0], v[1], v[2]) for k, v in sorted(fams.items())]
    case_notes = [(r['case'].name, r['case'].note) for r in results if r['case'].note]
    if case_notes:
        lines += ['', '## Case notes', '']
        lines += ['- `%s`: %s' % n for n in case_notes]
    notes = [(r['case'].name, r['why'].replace(out + os.sep, 'OUT/'))
             for r in results if r['why']]
    if notes or fam_errors:
        lines += ['', '## Failures and cases not run', '']
        lines += ['- `%s`: %s' % (n, w.replace('|', '\\|')) for n, w in notes]
        lines += ['- family `%s` failed to load: %s' % f for f in fam_errors]
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('compare_nodes: wrote %s' % path)


if __name__ == '__main__':
    sys.exit(main())

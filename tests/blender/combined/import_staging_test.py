#!/usr/bin/env python3
"""`memograph import-blender --out DIR` commits DIR as a set (docs/guide/limits.md).
No Blender needed: a fake `blender` (a shell script given with --blender) writes what the
exporter writes (graphs, index.json, textures/) into the folder it is given, then exits 0,
exits 1 or kills itself. A failed export must leave DIR as it was (and remove the staging
folder and any folder it created); a successful one must put every file in DIR.

    python3 tests/blender/combined/import_staging_test.py --memograph build/tools/memograph
"""

import argparse
import os
import shutil
import stat
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '../..'))
from folder_snapshot import snapshot  # noqa: E402

FAKE_BLENDER = r"""#!/bin/sh
# A stand-in for Blender: finds --out DIR, writes an export there, then does $FAKE_MODE.
echo run >> "$FAKE_LOG"
out=
while [ $# -gt 0 ]; do
  if [ "$1" = "--out" ]; then out=$2; fi
  shift
done
echo "out $out" >> "$FAKE_LOG"
mkdir -p "$out/textures" || exit 3
printf 'new a\n' > "$out/a.mgraph"
printf 'new b\n' > "$out/b.mgraph"
printf '{"materials": {}}\n' > "$out/index.json"
printf 'png' > "$out/textures/t.png"
echo "memograph: wrote 2 material(s) to $out, 0 warning(s), 0 error(s)"
case "$FAKE_MODE" in
  ok) exit 0 ;;
  fail) echo "error: M: something went wrong" >&2; exit 1 ;;
  crash) kill -SEGV $$ ;;
esac
exit 9
"""

failures = []


def check(ok, what):
    print('%s: %s' % ('ok  ' if ok else 'FAIL', what))
    if not ok:
        failures.append(what)
    return ok


def hidden(folder):
    """Staging folders and temporaries: every name starting with a dot, recursively."""
    found = []
    for root, dirs, files in os.walk(folder):
        found += [os.path.join(root, n) for n in dirs + files if n.startswith('.')]
    return found


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--memograph', required=True)
    args = parser.parse_args()
    memograph = os.path.abspath(args.memograph)
    work = tempfile.mkdtemp(prefix='memograph-import-staging-')
    try:
        run_tests(memograph, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        print('\n%d failure(s):' % len(failures))
        for f in failures:
            print('  ' + f)
        return 1
    print('\nall import-blender staging checks passed')
    return 0


def run_tests(memograph, work):
    fake = os.path.join(work, 'fake-blender')
    with open(fake, 'w') as f:
        f.write(FAKE_BLENDER)
    os.chmod(fake, 0o755)
    blend = os.path.join(work, 'scene.blend')
    with open(blend, 'wb') as f:
        f.write(b'BLENDER-v304' + b'\0' * 64)
    log = os.path.join(work, 'fake.log')
    base = os.path.join(work, 'outputs')
    os.makedirs(base)

    def run(out, mode):
        if os.path.exists(log):
            os.remove(log)
        env = dict(os.environ, FAKE_MODE=mode, FAKE_LOG=log,
                   MEMOGRAPH_BLENDER_EXPORTER=os.path.abspath(__file__))
        p = subprocess.run([memograph, 'import-blender', blend, '--out', out, '--blender', fake],
                           cwd=base, env=env, capture_output=True, text=True, timeout=60)
        lines = open(log).read().splitlines() if os.path.exists(log) else []
        staged_into = [l[4:] for l in lines if l.startswith('out ')]
        return p.returncode, p.stdout, p.stderr, staged_into

    def existing(name):
        out = os.path.join(base, name)
        os.makedirs(out)
        with open(os.path.join(out, 'a.mgraph'), 'w') as f:
            f.write('old a\n')
        with open(os.path.join(out, 'keep.txt'), 'w') as f:
            f.write('not the export\'s\n')
        return out

    # A failed export (error exit, then a crash) into a folder with an earlier export.
    for mode in ('fail', 'crash'):
        out = existing('failed_' + mode)
        before = snapshot(out)
        rc, so, se, staged_into = run(out, mode)
        check(rc == 1 and 'is unchanged' in se,
              '%s: exit 1 saying the folder is unchanged (got %d: %s)' % (mode, rc, se.strip()))
        check(len(staged_into) == 1 and staged_into[0] != out and
              os.path.dirname(staged_into[0]) == base and
              os.path.basename(staged_into[0]).startswith('.failed_%s.import-' % mode),
              '%s: Blender wrote into a staging folder beside DIR (%s)' % (mode, staged_into))
        check(snapshot(out) == before, '%s: DIR untouched (%s)' % (mode, sorted(snapshot(out))))
        check(not hidden(base), '%s: no staging folder or temporary left (%s)'
              % (mode, hidden(base)))

    # A failed export into a folder that does not exist, under parents that do not either.
    rc, so, se, _ = run('new/deeper/out', 'fail')
    check(rc == 1 and not os.path.exists(os.path.join(base, 'new')),
          'fail into a new DIR: exit 1, DIR and its created parents gone (got %d, %s)'
          % (rc, os.listdir(base)))

    # A successful export into an existing folder: every file there, the others kept.
    out = existing('updated')
    rc, so, se, _ = run(out, 'ok')
    got = snapshot(out)
    check(rc == 0, 'ok into an existing DIR: exit 0 (got %d: %s)' % (rc, se.strip()))
    check(sorted(got) == ['a.mgraph', 'b.mgraph', 'index.json', 'keep.txt', 'textures',
                          'textures/t.png'], 'ok: DIR holds the export and keep.txt (%s)'
          % sorted(got))
    check(open(os.path.join(out, 'a.mgraph')).read() == 'new a\n', 'ok: a.mgraph replaced')
    check(not hidden(base), 'ok: no staging folder or temporary left (%s)' % hidden(base))
    check(('to ' + out + ',') in so and '.import-' not in so,
          'ok: the summary names DIR, not the staging folder (%s)' % so.strip())

    # A successful export into a new folder, named with a trailing slash.
    rc, so, se, _ = run('fresh/', 'ok')
    fresh = os.path.join(base, 'fresh')
    check(rc == 0 and sorted(snapshot(fresh)) == ['a.mgraph', 'b.mgraph', 'index.json',
                                                  'textures', 'textures/t.png'],
          'ok into a new DIR: exit 0, the export there (got %d: %s)' % (rc, se.strip()))
    mode = stat.S_IMODE(os.stat(fresh).st_mode) if os.path.isdir(fresh) else 0
    check(mode & 0o055 == 0o055, 'ok: a new DIR is not left 0700 (mode %o)' % mode)
    check(not hidden(base), 'ok (new): nothing hidden left (%s)' % hidden(base))

    # The commit itself fails part-way (a folder where b.mgraph goes): DIR as it was.
    out = existing('blocked')
    os.makedirs(os.path.join(out, 'b.mgraph', 'inside'))
    before = snapshot(out)
    rc, so, se, _ = run(out, 'ok')
    check(rc == 1 and 'b.mgraph' in se and 'is unchanged' in se,
          'blocked commit: exit 1 naming b.mgraph (got %d: %s)' % (rc, se.strip()))
    check(snapshot(out) == before, 'blocked commit: DIR untouched, no textures/ created (%s)'
          % sorted(snapshot(out)))
    check(not hidden(base), 'blocked commit: nothing hidden left (%s)' % hidden(base))

    # --out names a file: refused before Blender runs.
    path = os.path.join(base, 'a_file')
    with open(path, 'w') as f:
        f.write('x')
    rc, so, se, staged_into = run(path, 'ok')
    check(rc == 1 and 'is a file, not a folder' in se and not os.path.exists(log),
          '--out a file: exit 1 before Blender runs (got %d: %s)' % (rc, se.strip()))


if __name__ == '__main__':
    sys.exit(main())

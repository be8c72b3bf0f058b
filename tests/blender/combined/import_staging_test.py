#!/usr/bin/env python3
"""`memograph import-blender --out DIR` commits DIR as a set (docs/guide/limits.md).
No Blender needed: a fake `blender` (a shell script given with --blender) writes what the
exporter writes (graphs, index.json, textures/) into the folder it is given, then exits 0,
exits 1 or kills itself. A failed export must leave DIR as it was (and remove the staging
folder and any folder it created); a successful one must put every file in DIR.

Blender is untrusted too: fakes that hang, that leave links, FIFOs, garbage, huge or
unlisted graphs or a bad index, that replace the staging folder with a file, that print
50 MB without a newline, /bin/true, and a memograph stopped by a signal (or SIGKILL)
while Blender runs. Each must end in exit 1 (or 128 + the signal), DIR untouched, no
staging folder left and no fake Blender left running.

    python3 tests/blender/combined/import_staging_test.py --memograph build/tools/memograph
"""

import argparse
import os
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time

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
echo "pid $$" >> "$FAKE_LOG"
mkdir -p "$out/textures" || exit 3
printf '# new a\nmaterial a;\nBaseColorOutput (1.0, 0.0, 0.0);\n' > "$out/a.mgraph"
printf 'material b;\nRoughnessOutput 0.5;\n' > "$out/b.mgraph"
printf '{"materials": {"A": {"file": "a.mgraph", "material": "a"},\n' > "$out/index.json"
printf '  "B \\u00e9": {"material": "b", "file": "b.mgraph"}}}\n' >> "$out/index.json"
printf 'png' > "$out/textures/t.png"
summary="memograph: wrote 2 material(s) to $out, 0 warning(s), 0 error(s)"
case "$FAKE_MODE" in
  ok) ;;
  fail) echo "$summary"; echo "error: M: something went wrong" >&2; exit 1 ;;
  crash) echo "$summary"; kill -SEGV $$ ;;
  hang) sleep 1000 & echo "child $!" >> "$FAKE_LOG"; echo "ready" >> "$FAKE_LOG"; wait; exit 0 ;;
  hang_alone) echo "ready" >> "$FAKE_LOG"; exec sleep 1000 ;;
  link_file) ln -s /etc/passwd "$out/textures/passwd.png" ;;
  link_graph) rm "$out/b.mgraph"; ln -s /etc/passwd "$out/b.mgraph" ;;
  link_folder) ln -s /etc "$out/textures/etc" ;;
  fifo) mkfifo "$out/textures/f.png" ;;
  garbage) printf '\377\000 }}} not a graph {{{\n' > "$out/b.mgraph" ;;
  huge) truncate -s 200M "$out/b.mgraph" ;;
  bad_index) printf '{"materials": [' > "$out/index.json" ;;
  index_names_missing) rm "$out/b.mgraph" ;;
  unlisted_graph) printf 'material c;\n' > "$out/c.mgraph" ;;
  wrong_material) printf 'material z;\n' > "$out/b.mgraph" ;;
  fewer_than_reported) summary="memograph: wrote 3 material(s) to $out, 0 warning(s), 0 error(s)" ;;
  no_summary) summary="" ;;
  replace_folder) rm -rf "$out"; echo x > "$out" ;;
  no_newlines) head -c 50000000 /dev/zero | tr '\000' x; echo ;;
esac
echo "$summary"
exit 0
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

    def command(out, extra=(), blender=None):
        return [memograph, 'import-blender', blend, '--out', out,
                '--blender', blender or fake] + list(extra)

    def environment(mode, **more):
        env = dict(os.environ, FAKE_MODE=mode, FAKE_LOG=log,
                   MEMOGRAPH_BLENDER_EXPORTER=os.path.abspath(__file__))
        env.update(more)
        return env

    def run(out, mode, extra=(), blender=None, **more):
        if os.path.exists(log):
            os.remove(log)
        p = subprocess.run(command(out, extra, blender), cwd=base,
                           env=environment(mode, **more), capture_output=True, text=True, errors='replace',
                           timeout=60)
        lines = open(log).read().splitlines() if os.path.exists(log) else []
        staged_into = [l[4:] for l in lines if l.startswith('out ')]
        return p.returncode, p.stdout, p.stderr, staged_into

    def fake_pids():
        """The fake Blender's pid and its background child's, from its log."""
        lines = open(log).read().splitlines() if os.path.exists(log) else []
        return [int(l.split()[1]) for l in lines if l.startswith(('pid ', 'child '))]

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
    check(open(os.path.join(out, 'a.mgraph')).read().startswith('# new a\n'),
          'ok: a.mgraph replaced')
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

    run_untrusted_blender_tests(memograph, work, base, blend, log, command, environment, run,
                                existing, fake_pids)


def alive(pid):
    """True while `pid` runs (a zombie waiting for its parent counts as gone)."""
    try:
        with open('/proc/%d/stat' % pid) as f:
            return f.read().rsplit(')', 1)[1].split()[0] != 'Z'
    except OSError:
        return False


def gone_soon(pids, seconds=3.0):
    """True when none of `pids` is running within `seconds` (init reaps orphans lazily)."""
    deadline = time.monotonic() + seconds
    while any(alive(p) for p in pids) and time.monotonic() < deadline:
        time.sleep(0.05)
    return not any(alive(p) for p in pids)


def run_untrusted_blender_tests(memograph, work, base, blend, log, command, environment, run,
                                existing, fake_pids):
    # Timeout: a Blender that never ends is stopped, with what it started.
    out = existing('hang')
    before = snapshot(out)
    t0 = time.monotonic()
    rc, so, se, _ = run(out, 'hang', ['--timeout', '1'])
    elapsed = time.monotonic() - t0
    pids = fake_pids()
    check(rc == 1 and 'did not finish within --timeout 1 s' in se and elapsed < 20,
          'timeout: exit 1 naming --timeout (got %d after %.1f s: %s)' % (rc, elapsed, se.strip()))
    check(len(pids) == 2 and gone_soon(pids),
          'timeout: the fake Blender and its child were stopped (%s)' % pids)
    check(snapshot(out) == before and not hidden(base),
          'timeout: DIR untouched, nothing hidden left (%s)' % hidden(base))
    rc, so, se, _ = run(out, 'ok', ['--timeout', 'soon'])
    check(rc == 2 and '--timeout' in se, 'timeout: a bad --timeout is a usage error (%d)' % rc)

    # The staged export is checked before it is committed: each bad export names its file.
    refused = [
        ('link_file', 'textures/passwd.png', 'symbolic link'),
        ('link_graph', 'b.mgraph', 'symbolic link'),
        ('link_folder', 'textures/etc', 'symbolic link'),
        ('fifo', 'textures/f.png', 'FIFO'),
        ('garbage', 'b.mgraph:1', 'error'),
        ('huge', 'b.mgraph', 'over the limit'),
        ('bad_index', 'index.json', 'not the exporter\'s index'),
        ('index_names_missing', 'index.json', 'does not hold'),
        ('unlisted_graph', 'c.mgraph', 'does not name'),
        ('wrong_material', 'b.mgraph', "declares material 'z'"),
        ('fewer_than_reported', 'index.json', 'reported 3'),
        ('no_summary', '', 'no summary'),
        ('replace_folder', '', 'not a folder'),
    ]
    for mode, name, why in refused:
        out = existing('refused_' + mode)
        before = snapshot(out)
        rc, so, se, _ = run(out, mode)
        named = os.path.join(out, name) if name else out
        check(rc == 1 and 'the export is refused: ' + named + ':' in se and
              why in se and 'is unchanged' in se,
              'validate %s: exit 1 naming %s (%s) (got %d: %s)'
              % (mode, name or 'DIR', why, rc, se.strip()[:400]))
        check(snapshot(out) == before and not hidden(base),
              'validate %s: DIR untouched, nothing hidden left (%s)' % (mode, hidden(base)))
    # The same into a DIR that does not exist: it is not created.
    rc, so, se, _ = run('never/made', 'link_file')
    check(rc == 1 and not os.path.exists(os.path.join(base, 'never')) and not hidden(base),
          'validate into a new DIR: exit 1, nothing created (%s)' % os.listdir(base))

    # A "Blender" that does nothing and exits 0 exports nothing: an error, not an empty DIR.
    rc, so, se, _ = run('from_true', 'ok', blender='/bin/true')
    check(rc == 1 and 'index.json' in se and not os.path.exists(os.path.join(base, 'from_true'))
          and not hidden(base), '/bin/true: exit 1, no DIR (got %d: %s)' % (rc, se.strip()))

    # 50 MB without a newline is read in linear time and bounded memory: the export still
    # succeeds, and memograph's peak RSS grows by far less than the 50 MB it was sent
    # (measured against the same import with a short output).
    measure = ('import resource, subprocess, sys\n'
               'r = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n'
               'print(r.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n'
               'sys.stderr.write(r.stderr)\n')

    def peak_rss(out, mode):
        p = subprocess.run([sys.executable, '-c', measure] + command(os.path.join(base, out)),
                           cwd=base, env=environment(mode), capture_output=True, text=True,
                           errors='replace', timeout=60)
        fields = p.stdout.split()
        if len(fields) != 2:
            return -1, -1, p.stderr
        return int(fields[0]), int(fields[1]), p.stderr

    rc, baseline_kib, se = peak_rss('short_output', 'ok')
    check(rc == 0, 'short output: the export succeeds (got %d: %s)' % (rc, se.strip()[-300:]))
    rc, peak_kib, se = peak_rss('no_newlines', 'no_newlines')
    print('no newlines: exit %d, peak RSS %.1f MiB (%.1f MiB with a short output)'
          % (rc, peak_kib / 1024.0, baseline_kib / 1024.0))
    check(rc == 0 and os.path.isfile(os.path.join(base, 'no_newlines', 'a.mgraph')),
          'no newlines: the export succeeds (got %d: %s)' % (rc, se.strip()[-300:]))
    check(0 < peak_kib - baseline_kib < 16 * 1024 or (0 < peak_kib <= baseline_kib),
          'no newlines: peak RSS grows by under 16 MiB for 50 MB of output (%d -> %d KiB)'
          % (baseline_kib, peak_kib))

    # Signals: SIGINT, SIGTERM and SIGHUP while Blender runs stop it, remove the staging
    # folder and exit with 128 + the signal.
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        out = existing('signal_%d' % sig)
        before = snapshot(out)
        if os.path.exists(log):
            os.remove(log)
        # SIGINT default in the child: a test run in the background inherits it ignored.
        p = subprocess.Popen(command(out), cwd=base, env=environment('hang'),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, errors='replace',
                             preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        deadline = time.monotonic() + 10
        while (not os.path.exists(log) or 'ready' not in open(log).read()) and \
                time.monotonic() < deadline:
            time.sleep(0.02)
        pids = fake_pids()
        p.send_signal(sig)
        try:
            so, se = p.communicate(timeout=15)
        except subprocess.TimeoutExpired:
            p.kill()
            for pid in pids:  # they hold the pipes open: communicate() would wait for them
                try:
                    os.kill(pid, signal.SIGKILL)
                except OSError:
                    pass
            so, se = p.communicate()
        check(p.returncode == 128 + sig and 'stopped by signal' in se,
              'signal %d: exit %d (got %s: %s)' % (sig, 128 + sig, p.returncode, se.strip()))
        check(len(pids) == 2 and gone_soon(pids),
              'signal %d: the fake Blender and its child were stopped (%s)' % (sig, pids))
        check(snapshot(out) == before and not hidden(base),
              'signal %d: DIR untouched, no staging folder left (%s)' % (sig, hidden(base)))

    # SIGKILL cannot be caught: Blender dies with memograph (PR_SET_PDEATHSIG), and the next
    # run into the same DIR removes the staging folder left behind.
    out = existing('killed')
    if os.path.exists(log):
        os.remove(log)
    # The fake is one process (exec sleep): what Blender itself starts cannot be reached
    # once memograph is gone.
    p = subprocess.Popen(command(out), cwd=base, env=environment('hang_alone'),
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 10
    while (not os.path.exists(log) or 'ready' not in open(log).read()) and \
            time.monotonic() < deadline:
        time.sleep(0.02)
    blender_pid = fake_pids()[:1]
    p.kill()
    p.wait()
    left = hidden(base)
    check(len(left) == 1 and '.killed.import-%d-' % p.pid in left[0],
          'SIGKILL: the staging folder names the pid (%s)' % left)
    check(blender_pid and gone_soon(blender_pid),
          'SIGKILL: the fake Blender died with memograph (%s)' % blender_pid)
    # A staging folder of a live process (ours) and look-alikes that are not staging
    # folders are kept.
    live = os.path.join(base, '.killed.import-%d-abcdef' % os.getpid())
    os.makedirs(live)
    lookalike = os.path.join(base, '.killed.import-notapid')
    os.makedirs(lookalike)
    other = os.path.join(base, '.other.import-%d-abcdef' % p.pid)
    os.makedirs(other)
    rc, so, se, _ = run(out, 'ok')
    check(rc == 0 and 'removed ' + left[0] in se if left else False,
          'SIGKILL: the next run removes the stale staging folder (got %d: %s)'
          % (rc, se.strip()))
    check(sorted(hidden(base)) == sorted([live, lookalike, other]),
          'SIGKILL: only the dead process\'s staging folder was removed (%s)' % hidden(base))
    for path in (live, lookalike, other):
        os.rmdir(path)

    # MEMOGRAPH_BLENDER_EXPORTER naming a missing file is an error before Blender runs.
    missing = os.path.join(work, 'no_such_exporter.py')
    rc, so, se, _ = run('exporter_missing', 'ok', MEMOGRAPH_BLENDER_EXPORTER=missing)
    check(rc == 1 and missing in se and not os.path.exists(log),
          'missing exporter: exit 1 naming it, Blender not run (got %d: %s)' % (rc, se.strip()))


if __name__ == '__main__':
    sys.exit(main())

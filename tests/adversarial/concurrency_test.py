#!/usr/bin/env python3
"""N processes writing the same outputs: every result file is complete and from
one process, every exit code tells the truth, and no temporary is left behind.

- `diff --out shared.png`: process k compares against its own test image, so each writes
  a different error map; the shared file must equal the map of exactly one of them.
- `compile -o shared/`: process k compiles materials A and B in colour k; afterwards all six
  files must come from one k (the folder is committed as a set, under a lock).
- A commit that fails part-way (B.json is a folder) restores the files already replaced.
Usage: concurrency_test.py MEMOGRAPH
"""
import os
import shutil
import struct
import subprocess
import sys
import tempfile

N = 8
ROUNDS = 2


def pfm(path, value):
    with open(path, "wb") as f:
        f.write(b"PF\n16 16\n-1.0\n" + struct.pack("<768f", *([value] * 768)))


def run_all(commands, cwd):
    procs = [subprocess.Popen(c, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
             for c in commands]
    return [(p.wait(), p.stderr.read().decode()) for p in procs]


def read(path):
    with open(path, "rb") as f:
        return f.read()


def leftovers(folder):
    return [n for n in os.listdir(folder) if n.startswith(".")]


def main():
    memograph = os.path.abspath(sys.argv[1])
    work = tempfile.mkdtemp(prefix="memograph-concurrency-")
    failures = []
    try:
        pfm(os.path.join(work, "ref.pfm"), 0.5)
        expected_maps = set()
        for k in range(N):
            pfm(os.path.join(work, "test%d.pfm" % k), 0.05 + 0.1 * k)
            alone = os.path.join(work, "alone%d.png" % k)
            code = subprocess.run([memograph, "diff", "ref.pfm", "test%d.pfm" % k, "--out",
                                   alone], cwd=work, capture_output=True).returncode
            if code != 0:
                failures.append("diff %d alone: exit %d" % (k, code))
                continue
            expected_maps.add(read(alone))
        if len(expected_maps) != N:
            failures.append("the %d diffs should give %d different maps, got %d" %
                            (N, N, len(expected_maps)))
        os.makedirs(os.path.join(work, "diffs"))
        for round in range(ROUNDS):
            results = run_all([[memograph, "diff", "ref.pfm", "test%d.pfm" % k, "--out",
                                "diffs/shared.png"] for k in range(N)], work)
            for k, (code, err) in enumerate(results):
                if code != 0:
                    failures.append("diff round %d process %d: exit %d: %s" %
                                    (round, k, code, err))
            if read(os.path.join(work, "diffs", "shared.png")) not in expected_maps:
                failures.append("diff round %d: shared.png is torn or mixed" % round)
            if leftovers(os.path.join(work, "diffs")):
                failures.append("diff: temporaries left: %s" % leftovers(os.path.join(work,
                                                                                      "diffs")))

        expected_sets = {}
        for k in range(N):
            for m in "AB":
                with open(os.path.join(work, "%s%d.mgraph" % (m, k)), "w") as f:
                    f.write("material %s;\nBaseColorOutput In=(%d, 0.5, 0.25);\n" % (m, k))
            alone = os.path.join(work, "alone%d" % k)
            code = subprocess.run([memograph, "compile", "A%d.mgraph" % k, "B%d.mgraph" % k,
                                   "-o", alone, "--quiet"], cwd=work).returncode
            if code != 0:
                failures.append("compile %d alone: exit %d" % (k, code))
                continue
            expected_sets[k] = {n: read(os.path.join(alone, n)) for n in os.listdir(alone)}
        shared = os.path.join(work, "shared")
        for round in range(ROUNDS):
            results = run_all([[memograph, "compile", "A%d.mgraph" % k, "B%d.mgraph" % k, "-o",
                                "shared", "--quiet"] for k in range(N)], work)
            for k, (code, err) in enumerate(results):
                if code != 0:
                    failures.append("compile round %d process %d: exit %d: %s" %
                                    (round, k, code, err))
            got = {n: read(os.path.join(shared, n)) for n in os.listdir(shared)}
            if got not in expected_sets.values():
                failures.append("compile round %d: the folder mixes runs: %s" %
                                (round, sorted(got)))

        # Part-way failure: B.json is a folder, so its rename fails after A's files and
        # B.glsl/B.hlsl were replaced; all of them must be back to the previous run's.
        before = {n: read(os.path.join(shared, n)) for n in os.listdir(shared)}
        os.remove(os.path.join(shared, "B.json"))
        os.makedirs(os.path.join(shared, "B.json"))
        before.pop("B.json")
        result = subprocess.run([memograph, "compile", "A0.mgraph", "B0.mgraph", "-o",
                                 "shared"], cwd=work, capture_output=True)
        err = result.stderr.decode()
        if result.returncode != 1 or "B.json" not in err or "Success" in err:
            failures.append("failing commit: exit %d, stderr %r" % (result.returncode, err))
        after = {n: read(os.path.join(shared, n)) for n in os.listdir(shared)
                 if n != "B.json"}
        if after != before:
            failures.append("failing commit: the files replaced before the failure were not "
                            "restored")
        if leftovers(shared):
            failures.append("compile: temporaries left: %s" % leftovers(shared))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for f in failures:
        print("FAIL: " + f)
    print("%d processes x %d rounds; %d failures" % (N, ROUNDS, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Peak memory of `memograph check`/`compile` grows with the graph text, not past it.

Each hostile input is near the 16 MiB text limit; the bound is the RSS of a trivial
graph's run (the process with its libraries) plus MEMORY_PER_INPUT_BYTE times the input.
The run's peak RSS is read from wait4's rusage. Usage: peak_memory_test.py MEMOGRAPH
"""
import os
import subprocess
import sys
import tempfile

MEMORY_PER_INPUT_BYTE = 64
SLACK_BYTES = 64 << 20


def peak_rss(argv, cwd):
    """Runs argv; returns (exit code, peak RSS in bytes, stderr head)."""
    with tempfile.TemporaryFile() as err:
        child = subprocess.Popen(argv, cwd=cwd, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        return child.returncode, usage.ru_maxrss * 1024, err.read(400).decode("utf-8", "replace")


def inputs():
    """(file name, text, command, expected exit code)."""
    chain = ["Float1Constant 0.5 Out>0;\n"]
    chain += ["Add A<%d B<%d Out>%d;\n" % (i, i, i + 1) for i in range(200_000)]
    chain.append("ColorOutput In<200000;\n")
    return [
        ("links_one_node.mgraph",
         "Float1Constant 0.5 Out>0;\nColorOutput " + "In<0 " * 3_000_000 + ";\n", "check", 1),
        ("numbers.mgraph", "Float1Constant " + "1 " * 8_000_000 + "Out>0;\n", "check", 1),
        ("semicolons.mgraph", ";" * 16_000_000, "check", 1),
        ("tiny_nodes.mgraph", "A;" * 8_000_000, "check", 1),
        ("outputs.mgraph",
         "Float1Constant 0.5 " + " ".join("Out>%d" % i for i in range(1_400_000)) + ";\n",
         "check", 1),
        ("chain.mgraph", "".join(chain), "check", 0),
        ("chain.mgraph", "".join(chain), "compile", 0),
    ]


def main():
    memograph = os.path.abspath(sys.argv[1])
    failures = []
    with tempfile.TemporaryDirectory(prefix="memograph-peak-") as work:
        small = os.path.join(work, "small.mgraph")
        with open(small, "w") as f:
            f.write("NormalInput Out>1;\nColorOutput In<1;\n")
        _, base, _ = peak_rss([memograph, "check", small], work)
        print("trivial graph: peak RSS %.0f MiB" % (base / 2**20))
        for name, text, command, expected in inputs():
            path = os.path.join(work, name)
            with open(path, "w") as f:
                f.write(text)
            argv = [memograph, command, path]
            if command == "compile":
                argv += ["-o", os.path.join(work, "out"), "--quiet"]
            code, peak, stderr = peak_rss(argv, work)
            size = len(text)
            bound = base + SLACK_BYTES + MEMORY_PER_INPUT_BYTE * size
            line = "%-22s %-8s %5.1f MB in, exit %d, peak RSS %6.0f MiB (bound %6.0f MiB)" % (
                name, command, size / 1e6, code, peak / 2**20, bound / 2**20)
            print(line)
            if code != expected:
                failures.append("%s: exit %d, expected %d: %s" % (line, code, expected, stderr))
            if peak > bound:
                failures.append(line + ": over the bound")
    for failure in failures:
        print("FAIL " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

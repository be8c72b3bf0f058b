#!/usr/bin/env python3
"""Writes each command's help, as the binary prints it, into docs/guide/cli.md.

The reference's sections hold one code block each that is the command's own help (`render`
and `bench` with --help-all); the prose around them is kept. The CLI test
TheCliReferenceHoldsEveryCommandsHelp fails when a block differs from the binary, so a help
change is one run of:
    python3 tools/make_cli_reference.py build/tools/memograph
"""
import os
import subprocess
import sys

# Section heading -> the arguments that print its block.
SECTIONS = {
    "## compile": ["compile", "--help"],
    "## check": ["check", "--help"],
    "## nodes": ["nodes", "--help"],
    "### render": ["render", "--help-all"],
    "### bench": ["bench", "--help-all"],
    "## bake": ["bake", "--help"],
    "## diff": ["diff", "--help"],
    "## import-blender": ["import-blender", "--help"],
    "## pack": ["pack", "--help"],
    "## selftest": ["selftest", "--help"],
}


def replace_block(text, heading, body, path):
    """The first code block after the line `heading` (before the next heading) holds body."""
    lines = text.splitlines(keepends=True)
    try:
        at = lines.index(heading + "\n")
    except ValueError:
        sys.exit("make_cli_reference: no section '%s' in %s" % (heading, path))
    fences = [i for i in range(at + 1, len(lines)) if lines[i] == "```\n"]
    later_heading = next((i for i in range(at + 1, len(lines)) if lines[i].startswith("#")),
                         len(lines))
    if len(fences) < 2 or fences[1] > later_heading:
        sys.exit("make_cli_reference: no code block under '%s' in %s" % (heading, path))
    return "".join(lines[:fences[0] + 1]) + body + "".join(lines[fences[1]:])


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_cli_reference.py MEMOGRAPH")
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "guide",
                        "cli.md")
    text = open(path, encoding="utf-8").read()
    for heading, args in SECTIONS.items():
        result = subprocess.run([sys.argv[1]] + args, capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit("make_cli_reference: '%s' exited %d" % (" ".join(args), result.returncode))
        help_text = result.stdout + result.stderr
        text = replace_block(text, heading, help_text, path)
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)
    print("make_cli_reference: wrote %s" % path)


if __name__ == "__main__":
    main()

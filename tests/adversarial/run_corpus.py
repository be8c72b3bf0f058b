#!/usr/bin/env python3
"""Runs the memograph CLI over the adversarial corpus (docs/guide/limits.md).

For every input it asserts: the exit code (1 bad input, 2 usage) and the message shape,
no crash (a signal fails the test), a time bound (TIMEOUT_S) and a memory bound (RLIMIT_AS
in the child), and, on failure, the output folder untouched. Usage: run_corpus.py MEMOGRAPH
"""
import concurrent.futures
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TIMEOUT_S = 20
MEMORY_BYTES = 3 << 30  # address space: a 4 GiB allocation from a 28-byte header fails

sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, ".."))
import make_scenes  # noqa: E402
from folder_snapshot import snapshot  # noqa: E402


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_BYTES, MEMORY_BYTES))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def prepare(work):
    """Inputs that cannot be committed: special files, links, large or generated files."""
    gen = os.path.join(work, "gen")
    os.makedirs(gen)
    os.mkfifo(os.path.join(gen, "fifo.mgraph"))
    os.mkfifo(os.path.join(gen, "fifo.campath"))
    os.mkfifo(os.path.join(gen, "fifo.pfm"))
    os.mkfifo(os.path.join(gen, "fifo.gltf"))
    os.symlink("loop_b.mgraph", os.path.join(gen, "loop_a.mgraph"))
    os.symlink("loop_a.mgraph", os.path.join(gen, "loop_b.mgraph"))
    os.symlink("loop_b.pfm", os.path.join(gen, "loop_a.pfm"))
    os.symlink("loop_a.pfm", os.path.join(gen, "loop_b.pfm"))
    os.makedirs(os.path.join(gen, "folder.mgraph"))
    with open(os.path.join(gen, "big.mgraph"), "wb") as f:
        f.truncate(17 << 20)  # over the 16 MiB text limit, sparse
    with open(os.path.join(gen, "big.campath"), "wb") as f:
        f.truncate(17 << 20)
    lib = os.path.join(gen, "types_10k")
    os.makedirs(os.path.join(lib, "prelude"))
    with open(os.path.join(lib, "prelude", "common.inc"), "w") as f:
        f.write("struct Unused { float x; };\n")
    with open(os.path.join(lib, "nodes.inc"), "w") as f:
        types = ", ".join("float" for _ in range(10000))
        f.write("/// @types T = %s\nvoid Copy(in T In, out T Out) { Out = In; }\n" % types)
    make_scenes.main(os.path.join(gen, "scenes"))
    prepare_graph_parser(gen)
    return gen


def cases(gen):
    c = os.path.join(HERE, "camera_paths")
    g = os.path.join(HERE, "graphs")
    i = os.path.join(HERE, "images")
    n = os.path.join(HERE, "nodelibs")
    s = os.path.join(gen, "scenes")
    valid = os.path.join(g, "valid.mgraph")
    long_name = "x" * 300 + ".mgraph"
    # (name, argv after `memograph`, exit code, regex the stderr must match)
    out = [
        ("usage: no command", [], 2, r"usage: memograph"),
        ("usage: unknown command", ["frobnicate"], 2, r"unknown command"),
        ("usage: unknown option", ["compile", "--frob", valid], 2, r"unknown option"),
        ("usage: missing value", ["compile", valid, "-o"], 2, r"needs a value"),
        ("usage: bad target", ["compile", valid, "--target", "spirv", "-o", "out"], 2,
         r"--target"),
        ("usage: render size 0x0", ["render", "builtin:landscape", "--size", "0x0", "--out",
                                    "out/x.png"], 2, r"--size"),
        ("usage: render size huge", ["render", "builtin:landscape", "--size", "100000x100000",
                                     "--out", "out/x.png"], 2, r"--size"),
        ("usage: render paths 0", ["render", "builtin:landscape", "--paths", "0", "--out",
                                   "out/x.png"], 2, r"--paths"),
        ("usage: render frames -1", ["render", "builtin:landscape", "--frames", "-1", "--out",
                                     "out/x.png"], 2, r"--frames"),
        ("usage: render bad extension", ["render", "builtin:landscape", "--out", "out/x.bmp"],
         2, r"--out must name"),
        ("usage: render probe 0", ["render", "builtin:landscape", "--cache", "texel",
                                   "--probe", "0", "--out", "out/x.png"], 2, r"probe"),
        ("usage: bench sizes empty", ["bench", "builtin:landscape", "--sizes", ""], 2,
         r"--sizes"),
        ("usage: bench sizes 0x5", ["bench", "builtin:landscape", "--sizes", "0x5"], 2,
         r"--sizes"),
        # An empty value is not "not given": the culling numbers' defaults live in the library.
        ("usage: render low frames empty", ["render", "builtin:landscape", "--culling", "lipac",
                                            "--low-frames", "", "--out", "out/x.png"], 2,
         r"'--low-frames' needs a value"),
        ("usage: render look appearing empty", ["render", "builtin:landscape",
                                                "--look-appearing=", "--out", "out/x.png"], 2,
         r"'--look-appearing' needs a value"),
        ("usage: render looks is no option", ["render", "builtin:landscape", "--looks", "off",
                                              "--out", "out/x.png"], 2,
         r"unknown option '--looks'"),
        ("usage: bench scene file", ["bench", "scene.gltf", "--csv", "out/keep.txt"], 2,
         r"built-in"),
        ("usage: bench csv kept", ["bench", "--paths", "x", "--csv", "out/keep.txt"], 2,
         r"--paths"),
        ("usage: diff ppd 1e12", ["diff", os.path.join(i, "ok_2x2.pfm"),
                                  os.path.join(i, "ok_2x2.pfm"), "--ppd", "1e12"], 2, r"ppd"),
        ("usage: diff out extension", ["diff", os.path.join(i, "ok_2x2.pfm"),
                                       os.path.join(i, "ok_2x2.pfm"), "--out", "out/x.gif"], 2,
         r"--out"),
        ("output: render out is a folder", ["render", "builtin:landscape", "--out",
                                            "out/sub.png"], 1, r"is a folder"),
        ("output: render missing folder", ["render", "builtin:landscape", "--out",
                                           "out/missing/x.png"], 1, r"does not exist"),
        ("output: render stats missing folder", ["render", "builtin:landscape", "--out",
                                                 "out/x.png", "--stats", "out/missing/s.csv"],
         1, r"does not exist"),
        ("output: bench frames-csv missing folder", ["bench", "builtin:landscape",
                                                     "--frames-csv", "out/missing/"], 1,
         r"does not exist"),
        ("output: compile into a file", ["compile", valid, "-o", "out/keep.txt"], 1,
         r"not a folder"),
        ("output: diff out missing folder", ["diff", os.path.join(i, "ok_2x2.pfm"),
                                             os.path.join(i, "ok_2x2.pfm"), "--out",
                                             "out/missing/x.png"], 1, r"does not exist"),
        ("file: graph FIFO", ["compile", os.path.join(gen, "fifo.mgraph"), "-o", "out"], 1,
         r"not a regular file \(a FIFO\)"),
        ("file: graph /dev/zero", ["compile", "/dev/zero", "-o", "out"], 1,
         r"not a regular file"),
        ("file: graph symlink loop", ["compile", os.path.join(gen, "loop_a.mgraph"), "-o",
                                      "out"], 1, r"symbolic link loop"),
        ("file: graph name too long", ["compile", os.path.join(gen, long_name), "-o", "out"],
         1, r"name is too long"),
        ("file: graph is a folder", ["compile", os.path.join(gen, "folder.mgraph"), "-o",
                                     "out"], 1, r"is a folder"),
        ("file: graph missing", ["compile", os.path.join(gen, "missing.mgraph"), "-o", "out"],
         1, r"no such file"),
        ("limit: graph over 16 MiB", ["compile", os.path.join(gen, "big.mgraph"), "-o", "out"],
         1, r"over the limit of 16 MiB"),
        ("limit: @types 10k", ["compile", valid, "--nodes", os.path.join(gen, "types_10k"),
                               "-o", "out"], 1, r"@types lists 10000 types"),
        ("camera: FIFO", ["render", "builtin:landscape", "--camera-path",
                          os.path.join(gen, "fifo.campath"), "--out", "out/x.png"], 1,
         r"FIFO"),
        ("camera: /dev/zero", ["render", "builtin:landscape", "--camera-path", "/dev/zero",
                               "--out", "out/x.png"], 1, r"not a regular file"),
        ("camera: over 16 MiB", ["render", "builtin:landscape", "--camera-path",
                                 os.path.join(gen, "big.campath"), "--out", "out/x.png"], 1,
         r"over the limit"),
        ("image: PFM FIFO", ["diff", os.path.join(gen, "fifo.pfm"),
                             os.path.join(i, "ok_2x2.pfm")], 1, r"FIFO"),
        ("image: PFM symlink loop", ["diff", os.path.join(gen, "loop_a.pfm"),
                                     os.path.join(i, "ok_2x2.pfm")], 1, r"symbolic link loop"),
        ("image: sizes differ", ["diff", os.path.join(i, "ok_1x1.pfm"),
                                 os.path.join(i, "ok_2x2.pfm"), "--out", "out/x.png"], 1,
         r"differ in size"),
        ("scene: FIFO", ["render", os.path.join(gen, "fifo.gltf"), "--out", "out/x.png"], 1,
         r"FIFO"),
    ]
    out += graph_parser_cases(gen)
    for name in sorted(os.listdir(os.path.join(HERE, "graphs"))):
        if name != "valid.mgraph":
            out.append(("graph: " + name, ["compile", os.path.join(g, name), valid, "-o", "out"],
                        1, r":\d+:\d+: error: "))
    for name, pattern in [("no_prelude", r"no prelude/"), ("inc_folder", r"is a folder"),
                          ("bad_types", r"@types"), ("empty", r"no \.inc files")]:
        out.append(("node library: " + name, ["compile", valid, "--nodes",
                                              os.path.join(n, name), "-o", "out"], 1, pattern))
    for name in sorted(os.listdir(c)):
        out.append(("camera: " + name, ["render", "builtin:landscape", "--camera-path",
                                        os.path.join(c, name), "--out", "out/x.png"], 1,
                    r"error: "))
    for name in sorted(os.listdir(i)):
        if not name.startswith("ok_"):
            out.append(("image: " + name, ["diff", os.path.join(i, name),
                                           os.path.join(i, "ok_2x2.pfm"), "--out",
                                           "out/x.png"], 1, r"error: "))
    # Scenes whose message is stated; the others need only an error.
    scene_messages = {
        "external_index_out_of_range.gltf":
            r"error: meshes\[0\]\.primitives\[0\]\.indices: index 2 is 60000, out of range",
        "external_missing_buffer.gltf":
            r"error: buffers\[0\]\.uri 'missing\.bin': .*missing\.bin: no such file",
        "external_short_buffer.gltf":
            r"error: buffers\[0\]\.uri .* has 20 bytes, fewer than the buffer's byteLength",
        "external_absolute_uri.gltf": r"error: buffers\[0\]\.uri '/etc/passwd' is an absolute",
        "vertex_index_out_of_range.gltf": r"error: meshes\[0\]\.primitives\[0\]\.indices",
        "base64_not_ascii.gltf": r"error: buffers\[0\]\.uri: the base64 data has a character",
        "base64_length.gltf": r"error: buffers\[0\]\.uri: the base64 data is 59 characters",
        "data_uri_long_header.gltf": r"error: buffers\[0\]\.uri: the data: URI's media type",
        "huge_component_type.gltf": r"error: accessors\[1\] needs .* a known componentType",
    }
    for name in sorted(os.listdir(s)):
        if not name.startswith("valid") and name.endswith((".gltf", ".glb", ".obj")):
            out.append(("scene: " + name, ["render", os.path.join(s, name), "--out",
                                           "out/x.png", "--size", "8x8"], 1,
                        scene_messages.get(name, r"error: ")))
    # --- Hostile scenes: scene limits, OBJ/MTL external files, built-in options, cameras ---
    h = prepare_hostile_scenes(gen)
    out += [
        ("hostile: OBJ 50000 usemtl", ["render", os.path.join(h, "usemtl_50k.obj"), "--out",
                                       "out/x.png", "--size", "8x8"], 1,
         r"usemtl_50k\.obj:32773:1: error: .* limit of 16384 meshes"),
        ("hostile: OBJ mtllib FIFO", ["render", os.path.join(h, "fifo_mtllib.obj"), "--out",
                                      "out/x.png", "--size", "8x8"], 1,
         r"fifo_mtllib\.obj:1:8: error: the material library 'fifo\.mtl'.*a FIFO"),
        ("hostile: OBJ fallback mtl FIFO", ["render", os.path.join(h, "fallback.obj"), "--out",
                                            "out/x.png", "--size", "8x8"], 1,
         r"fallback material library .*fallback\.mtl .*a FIFO"),
        ("hostile: MTL texture FIFO", ["render", os.path.join(h, "fifo_texture.obj"), "--out",
                                       "out/x.png", "--size", "8x8"], 1,
         r"textured\.mtl:2:8: error: the texture of 'map_Kd' 'fifo\.png'.*a FIFO"),
        ("hostile: OBJ mtllib /dev/zero", ["render", os.path.join(h, "dev_zero.obj"), "--out",
                                           "out/x.png", "--size", "8x8"], 1,
         r"dev_zero\.obj:1:8: error: the material library '/dev/zero' is an absolute path"),
        # lavapipe binds at most 128 MiB per storage buffer; the full city's vertices are
        # 2.3 GB, refused while the city is built, once they pass the range.
        ("hostile: city too large for lavapipe", ["render", "builtin:city",
                                                  "--size", "16x9", "--out", "out/x.png"], 1,
         r"the scene's vertex buffer would need at least \d+ bytes .*maxStorageBufferRange"),
        ("hostile: builtin terrain=0", ["render", "builtin:landscape:terrain=0", "--out",
                                        "out/x.png"], 2,
         r"terrain \(the landscape's terrain grid: cells per side\) is an integer in 2\.\.4096"),
        ("hostile: camera path denormal", ["render", "builtin:landscape:terrain=2",
                                           "--camera-path", os.path.join(h, "denormal.campath"),
                                           "--out", "out/x.png"], 1,
         r"denormal\.campath:2:1: error: the camera's position \(1e\+30"),
        ("hostile: camera at 1e30", ["render", "builtin:landscape:terrain=2", "--camera-path",
                                     os.path.join(h, "far.campath"), "--out", "out/x.png"], 1,
         r"far\.campath:1:1: error: the camera's position \(1e\+30, 0, 0\) is out of range"),
    ]
    # --- end of hostile scenes ---
    # import-blender with an untrusted Blender, and bake's --bounds and --out messages
    # (tools/cli/import_blender_command.cpp, staged_import.cpp, child_process.cpp): fake
    # Blenders (shell scripts) that hang, or leave links, FIFOs, garbage, huge graphs, a bad
    # index or a file instead of the staging folder. DIR (out/imported) must stay unmade.
    fakes = os.path.join(gen, "fake_blenders")
    os.makedirs(fakes, exist_ok=True)
    blend = os.path.join(fakes, "scene.blend")
    with open(blend, "wb") as f:
        f.write(b"BLENDER-v304" + b"\0" * 64)
    export = ('out=; while [ $# -gt 0 ]; do [ "$1" = --out ] && out=$2; shift; done\n'
              'printf "material a;\\n" > "$out/a.mgraph"\n'
              'printf \'{"materials": {"A": {"file": "a.mgraph", "material": "a"}}}\' '
              '> "$out/index.json"\n')
    behaviours = {
        "hang": ("sleep 1000\n", r"did not finish within --timeout 1 s"),
        "link_passwd": ('ln -s /etc/passwd "$out/b.mgraph"\n', r"b\.mgraph: is a symbolic link"),
        "link_etc": ('ln -s /etc "$out/etc"\n', r"etc: is a symbolic link"),
        "fifo": ('mkfifo "$out/f.png"\n', r"f\.png: is a FIFO"),
        "garbage": ('printf "}}} garbage" > "$out/a.mgraph"\n', r"a\.mgraph:1:\d+: error"),
        "huge": ('truncate -s 200M "$out/a.mgraph"\n', r"a\.mgraph: the file is 200 MiB"),
        "bad_index": ('printf "{[" > "$out/index.json"\n', r"index\.json: not the exporter"),
        "replace_folder": ('rm -rf "$out"; echo x > "$out"\n', r"not a folder"),
    }
    for name, (action, pattern) in sorted(behaviours.items()):
        script = os.path.join(fakes, name)
        with open(script, "w") as f:
            f.write("#!/bin/sh\n" + export + action +
                    'echo "memograph: wrote 1 material(s) to $out, 0 warning(s), 0 error(s)"\n')
        os.chmod(script, 0o755)
        out.append(("import-blender: " + name,
                    ["import-blender", blend, "--out", "out/imported", "--blender", script,
                     "--timeout", "1"], 1, pattern))
    out.append(("import-blender: /bin/true", ["import-blender", blend, "--out", "out/imported",
                                              "--blender", "/bin/true"], 1,
                r"index\.json: missing"))
    os.symlink(os.path.join(gen, "nowhere"), os.path.join(fakes, "dangling_out"))
    out.append(("bake: --bounds 1e38", ["bake", valid, "--size", "2x2", "--out", "out",
                                        "--bounds", "-1e38,-1e38,-1e38,1e38,1e38,1e38"], 2,
                r"xmin -1e38 is out of range"))
    out.append(("bake: --out dangling link", ["bake", valid, "--size", "2x2", "--format", "pfm",
                                              "--out", os.path.join(fakes, "dangling_out")], 1,
                r"is a dangling symbolic link"))
    # CLI outputs and usage: no output over an input (by path, link or hard link) or over
    # another output, every usage error before file or GPU work, errors on stderr.
    o = os.path.join(gen, "cli_outputs")
    os.makedirs(o)
    shutil.copy(os.path.join(i, "ok_2x2.pfm"), os.path.join(o, "ref.pfm"))
    os.symlink("ref.pfm", os.path.join(o, "ref_link.pfm"))
    os.link(os.path.join(o, "ref.pfm"), os.path.join(o, "ref_hard.pfm"))
    with open(os.path.join(o, "camera.txt"), "w") as f:
        f.write("0 1 5  0 0 0  60\n")
    os.symlink("camera.txt", os.path.join(o, "camera_link.csv"))
    ref, ok = os.path.join(o, "ref.pfm"), os.path.join(i, "ok_2x2.pfm")
    small = ["--size", "4x4", "--paths", "1", "--bounces", "1", "--floor-materials"]
    out += [
        ("cli: diff out is reference", ["diff", ref, ok, "--out", ref], 2,
         r"--out '.*ref\.pfm' is REFERENCE"),
        ("cli: diff out links to reference", ["diff", ref, ok, "--out",
                                              os.path.join(o, "ref_link.pfm")], 2,
         r"is REFERENCE"),
        ("cli: diff out hard link of test", ["diff", ok, ref, "--out",
                                             os.path.join(o, "ref_hard.pfm")], 2, r"is TEST"),
        ("cli: render stats links to camera path",
         ["render", "builtin:landscape", "--camera-path", os.path.join(o, "camera.txt"),
          "--stats", os.path.join(o, "camera_link.csv"), "--out", "out/x.png"] + small, 2,
         r"--stats '.*camera_link\.csv' is --camera-path"),
        ("cli: render stats is out", ["render", "builtin:landscape", "--out", "out/x.png",
                                      "--stats", "out/../out/x.png"] + small, 2,
         r"two outputs cannot share a file"),
        ("cli: render usage before folder", ["render", "builtin:landscape:terrain=1", "--out",
                                             "out/missing/x.png"] + small, 2,
         r"terrain \(the landscape's terrain grid: cells per side\) is an integer in 2\.\.4096"),
        ("cli: bench sizes trailing comma", ["bench", "builtin:landscape", "--sizes", "16x9,"],
         2, r"--sizes takes WxH\[,WxH\.\.\.\], not '16x9,'"),
        ("cli: bench second scene unknown", ["bench", "builtin:landscape:terrain=8",
                                             "builtin:bogus", "--sizes", "8x8", "--csv",
                                             "out/keep.txt"], 2,
         r"unknown built-in scene 'bogus'"),
        ("cli: bench csv is a per-frame file", ["bench", "builtin:landscape", "--sizes", "8x8",
                                                "--frames-csv", "out/f_", "--csv",
                                                "out/f_landscape_8x8.csv"], 2,
         r"two outputs cannot share a file"),
        ("cli: selftest too few iterations", ["selftest", "--iterations", "4"], 2,
         r"give --iterations 6 or more"),
    ]
    return out


# --- Graph parser and compiler messages: size limits near 16 MiB, names, paths, options ---
def prepare_graph_parser(gen):
    """Large graphs under the 16 MiB text limit, and small ones whose message is stated."""
    def put(name, text):
        with open(os.path.join(gen, name), "w") as f:
            f.write(text)
    put("links_3m.mgraph", "Float1Constant 0.5 Out>0;\nColorOutput " + "In<0 " * 3_000_000 + ";\n")
    put("numbers_8m.mgraph", "Float1Constant " + "1 " * 8_000_000 + "Out>0;\n")
    put("semicolons_16m.mgraph", ";" * 16_000_000)
    put("nodes_8m.mgraph", "A;" * 8_000_000)
    put("material_digit.mgraph", "material 1abc;\nNormalInput Out>1;\nColorOutput In<1;\n")
    put("material_long.mgraph",
        "material " + "x" * 100_000 + ";\nNormalInput Out>1;\nColorOutput In<1;\n")
    put("image_empty.mgraph",
        "UVInput Out>1;\nImageTexture Image=\"\" UV<1 Color>2;\nBaseColorOutput In<2;\n")
    put("not_a_folder", "x")


def graph_parser_cases(gen):
    def g(name):
        return os.path.join(gen, name)
    return [
        ("parser: 3M links", ["check", g("links_3m.mgraph")], 1, r"over the limit"),
        ("parser: 8M numbers", ["check", g("numbers_8m.mgraph")], 1, r"over the limit"),
        ("parser: 16M semicolons", ["check", g("semicolons_16m.mgraph")], 1,
         r":1:1: error: expected a node type"),
        ("parser: 8M nodes", ["compile", g("nodes_8m.mgraph"), "-o", "out"], 1,
         r"more than 250000 nodes"),
        ("parser: material 1abc", ["check", g("material_digit.mgraph")], 1,
         r":1:10: error: '1abc' is not a valid material name"),
        ("parser: material name 100k (check)", ["check", g("material_long.mgraph")], 1,
         r"over the limit of 200"),
        ("parser: material name 100k (compile)", ["compile", g("material_long.mgraph"), "-o",
                                                  "out/new"], 1, r"over the limit of 200"),
        ("parser: empty image path", ["check", g("image_empty.mgraph")], 1,
         r"empty texture path"),
        ("parser: bad --nodes before bad -o", ["compile", g("material_digit.mgraph"), "-o",
                                               g("not_a_folder"), "--nodes", g("missing")], 2,
         r"--nodes .*does not exist"),
    ]
# --- end of graph parser cases ---


def prepare_hostile_scenes(gen):
    """The hostile-scene inputs: generated OBJ/MTL files, FIFOs they name, camera paths."""
    h = os.path.join(gen, "hostile")
    os.makedirs(h)
    triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

    def write(name, text):
        with open(os.path.join(h, name), "w") as f:
            f.write(text)
    write("usemtl_50k.obj", triangle + "".join("usemtl m%d\nf 1 2 3\n" % k
                                               for k in range(50000)))
    os.mkfifo(os.path.join(h, "fifo.mtl"))
    write("fifo_mtllib.obj", "mtllib fifo.mtl\n" + triangle + "f 1 2 3\n")
    os.mkfifo(os.path.join(h, "fallback.mtl"))  # assimp's fallback for a missing mtllib
    write("fallback.obj", "mtllib missing.mtl\n" + triangle + "f 1 2 3\n")
    os.mkfifo(os.path.join(h, "fifo.png"))
    write("textured.mtl", "newmtl wood\nmap_Kd fifo.png\n")
    write("fifo_texture.obj", "mtllib textured.mtl\n" + triangle + "usemtl wood\nf 1 2 3\n")
    write("dev_zero.obj", "mtllib /dev/zero\n" + triangle + "f 1 2 3\n")
    # A denormal is a number (the first frame is fine); the second frame's camera is not.
    write("denormal.campath", "0 1e-310 5 0 0 0 45\n1e30 0 0 0 0 0 45\n")
    write("far.campath", "1e30 0 0 0 0 0 45\n")
    return h


def run_case(memograph, work, index, case):
    """Runs one input; returns (a line for the log, a failure message or None)."""
    name, argv, code, pattern = case
    run_dir = os.path.join(work, "run%d" % index)
    os.makedirs(os.path.join(run_dir, "out", "sub.png"))
    with open(os.path.join(run_dir, "out", "keep.txt"), "w") as f:
        f.write("must survive a failed command\n")
    before = snapshot(os.path.join(run_dir, "out"))
    # memograph's caches start empty under `work`; Mesa's shader cache stays where it is
    # without that XDG_CACHE_HOME, since a fresh one compiles every lavapipe pipeline anew.
    env = dict(os.environ, XDG_CACHE_HOME=os.path.join(work, "cache"),
               MESA_SHADER_CACHE_DIR=os.environ.get("MESA_SHADER_CACHE_DIR")
               or os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"))
    t0 = time.monotonic()
    try:
        result = subprocess.run([memograph] + argv, cwd=run_dir, env=env, capture_output=True,
                                timeout=TIMEOUT_S, preexec_fn=limit_memory)
    except subprocess.TimeoutExpired:
        return name + ": timeout", "%s: no answer within %d s" % (name, TIMEOUT_S)
    elapsed = time.monotonic() - t0
    stderr = result.stderr.decode("utf-8", "replace")
    problems = []
    if result.returncode < 0:
        problems.append("crashed with signal %d" % -result.returncode)
    elif result.returncode != code:
        problems.append("exit %d, expected %d" % (result.returncode, code))
    if not re.search(pattern, stderr):
        problems.append("stderr does not match /%s/" % pattern)
    if "internal error" in stderr or ": Success" in stderr:
        problems.append("an internal-error message")
    if result.returncode != 0 and snapshot(os.path.join(run_dir, "out")) != before:
        problems.append("the output folder changed")
    first = stderr.strip().splitlines()[0][:150] if stderr.strip() else ""
    line = "%-45s exit %d %5.2f s  %s" % (name, result.returncode, elapsed, first)
    if problems:
        return line, "%s: %s\n    stderr: %s" % (name, "; ".join(problems), stderr.strip()[:600])
    return line, None


def main():
    memograph = os.path.abspath(sys.argv[1])
    work = tempfile.mkdtemp(prefix="memograph-adversarial-")
    failures = []
    start = time.monotonic()
    try:
        gen = prepare(work)
        all_cases = cases(gen)
        # Independent runs, several at a time: the bound is per run, not for the sum.
        with concurrent.futures.ThreadPoolExecutor(max_workers=6) as pool:
            results = list(pool.map(lambda c: run_case(memograph, work, *c),
                                    enumerate(all_cases)))
        for line, problem in results:
            print(line)
            if problem:
                failures.append(problem)
        print("\n%d inputs in %.1f s" % (len(all_cases), time.monotonic() - start))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        print("\n%d failures:" % len(failures))
        for f in failures:
            print("  " + f)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

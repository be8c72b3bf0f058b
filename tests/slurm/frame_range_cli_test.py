#!/usr/bin/env python3
"""render --frame-range and bake --shard from the command line (issue 44), on lavapipe.

usage: frame_range_cli_test.py MEMOGRAPH REPOSITORY [unittest arguments]

A split render gives the frames of one run byte for byte (no cache: a frame's random numbers
depend on its index and the seed alone); --resume renders only the frames whose files are
missing or incomplete; a still camera's frame is its own image; the shards of a bake make the
unsharded bake; bad ranges, shards and output patterns are usage errors (exit 2).
"""

import filecmp
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

MEMOGRAPH = REPO = None
SCENE = "builtin:landscape:terrain=2"
RENDER = ["--size", "16x9", "--bounces", "2", "--paths", "2", "--seed", "3"]


def run(*args):
    result = subprocess.run([MEMOGRAPH, *args], capture_output=True, text=True, timeout=300)
    return result.returncode, result.stdout + result.stderr


class FrameRange(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="memograph-frames-")
        os.environ["XDG_CACHE_HOME"] = os.path.join(self.dir, "cache")
        self.path = os.path.join(REPO, "examples", "camera_paths", "landscape.campath")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def render(self, folder, frames, *extra):
        code, output = run("render", SCENE, "--camera-path", self.path, *RENDER,
                           "--frame-range", frames,
                           "--out", os.path.join(self.dir, folder, "frame_####.pfm"), *extra)
        self.assertEqual(code, 0, output)
        return output

    def frame(self, folder, f):
        return os.path.join(self.dir, folder, "frame_%04d.pfm" % f)

    def test_a_split_path_and_a_resumed_one_give_one_runs_frames(self):
        for folder in ("whole", "split"):
            os.makedirs(os.path.join(self.dir, folder))
        self.render("whole", "0:3")
        self.render("split", "0:1")
        self.render("split", "2:3")
        for f in range(4):
            self.assertTrue(filecmp.cmp(self.frame("whole", f), self.frame("split", f),
                                        shallow=False), "frame %d differs" % f)
        self.assertFalse(filecmp.cmp(self.frame("whole", 0), self.frame("whole", 1),
                                     shallow=False), "the camera moves: frames differ")
        # A preempted job: frame 3 never written, frame 1 cut short after the write. Frame 2,
        # complete between them, is neither written nor rendered again (no cache: nothing
        # crosses frames), so two frames are rendered, not three.
        os.remove(self.frame("split", 3))
        with open(self.frame("split", 1), "r+b") as f:
            f.truncate(100)
        kept = os.stat(self.frame("split", 2)).st_mtime_ns
        output = self.render("split", "0:3", "--resume")
        self.assertIn("2 written, 2 complete already", output)
        self.assertIn("; 2 frames rendered in all", output)
        self.assertEqual(os.stat(self.frame("split", 2)).st_mtime_ns, kept)
        for f in range(4):
            self.assertTrue(filecmp.cmp(self.frame("whole", f), self.frame("split", f),
                                        shallow=False), "frame %d differs after --resume" % f)
        output = self.render("split", "0:3", "--resume")
        self.assertIn("all complete; nothing to render", output)

    def test_a_still_cameras_frame_is_its_own_image(self):
        # No camera path: the scene's camera in every frame. A frame of a range does not
        # average the frames before it, so frame 1 alone is frame 1 of 0:1.
        os.makedirs(os.path.join(self.dir, "still"))
        for frames, out in (("0:1", "both_#.pfm"), ("1:1", "alone_#.pfm")):
            code, output = run("render", SCENE, *RENDER, "--frame-range", frames,
                               "--out", os.path.join(self.dir, "still", out))
            self.assertEqual(code, 0, output)
        both = [os.path.join(self.dir, "still", "both_%d.pfm" % f) for f in (0, 1)]
        alone = os.path.join(self.dir, "still", "alone_1.pfm")
        self.assertTrue(filecmp.cmp(both[1], alone, shallow=False))
        self.assertFalse(filecmp.cmp(both[0], both[1], shallow=False),
                         "frame 1 has its own random numbers")

    def test_bad_ranges_and_patterns_are_usage_errors(self):
        out = os.path.join(self.dir, "f_####.pfm")
        cases = [
            (["--frame-range", "3:1", "--out", out], "the last frame comes before the first"),
            (["--frame-range", "1", "--out", out], "--frame-range takes A:B"),
            (["--frame-range", "a:b", "--out", out], "--frame-range takes A:B"),
            (["--frame-range", "-1:2", "--out", out], "--frame-range takes A:B"),
            (["--frame-range", "0:3", "--out", os.path.join(self.dir, "f.pfm")],
             "put a run of '#' in its file name"),
            (["--frame-range", "0:3", "--out", os.path.join(self.dir, "f_#_##.pfm")],
             "more than one run of '#'"),
            (["--frame-range", "0:3", "--frames", "2", "--out", out], "--frames accumulates"),
            (["--frame-range", "0:3", "--stats", os.path.join(self.dir, "s.csv"), "--out", out],
             "--stats and --debug-culling"),
            (["--resume", "--out", out], "it needs --frame-range"),
            (["--frame-range", "0:4000000000", "--out", out], "at most 1000000 frames"),
            (["--frame-range", "0:360", "--camera-path", self.path, "--out", out],
             "ends past the camera path's last frame, 359"),
        ]
        for args, message in cases:
            with self.subTest(args=args):
                code, output = run("render", SCENE, *RENDER, *args)
                self.assertEqual(code, 2, output)
                self.assertIn(message, output)
        self.assertEqual(os.listdir(self.dir), [], "a usage error writes nothing")


class BakeShard(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="memograph-shards-")
        os.environ["XDG_CACHE_HOME"] = os.path.join(self.dir, "cache")
        self.library = os.path.join(self.dir, "library")
        os.makedirs(self.library)
        for graph in ("car_paint", "checker_floor", "lava", "marble"):
            shutil.copy(os.path.join(REPO, "examples", "graphs", graph + ".mgraph"), self.library)

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def bake(self, out, *extra):
        code, output = run("bake", self.library, "--size", "4x4", "--format", "pfm",
                           "--out", os.path.join(self.dir, out), *extra)
        self.assertEqual(code, 0, output)
        return output

    def test_the_union_of_the_shards_is_the_unsharded_bake(self):
        self.bake("whole")
        counts = []
        for shard in range(3):
            output = self.bake("sharded", "--shard", "%d/3" % shard)
            counts.append(output.count(" ... ok"))
        self.assertEqual(counts, [2, 1, 1])  # graphs 0 and 3, 1, 2
        comparison = filecmp.dircmp(os.path.join(self.dir, "whole"),
                                    os.path.join(self.dir, "sharded"))
        self.assertEqual((comparison.left_only, comparison.right_only), ([], []))
        _, mismatch, errors = filecmp.cmpfiles(comparison.left, comparison.right,
                                               comparison.common_files, shallow=False)
        self.assertEqual((mismatch, errors), ([], []))
        self.assertGreater(len(comparison.common_files), 4)

    def test_bad_shards_are_usage_errors(self):
        for shard in ("3/3", "1", "0/0", "a/2", "-1/2", "1/2/3", ""):
            with self.subTest(shard=shard):
                code, output = run("bake", self.library, "--size", "4x4", "--format", "pfm",
                                   "--out", os.path.join(self.dir, "x"), "--shard", shard)
                self.assertEqual(code, 2, output)
                self.assertIn("--shard", output)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "x")))


if __name__ == "__main__":
    MEMOGRAPH, REPO = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    # Each test gives memograph a fresh XDG_CACHE_HOME; Mesa's shader cache stays where it is
    # without one, since a fresh one compiles every lavapipe pipeline anew, seconds a render.
    os.environ.setdefault("MESA_SHADER_CACHE_DIR",
                          os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"))
    unittest.main(argv=[sys.argv[0], *sys.argv[3:]])

#!/usr/bin/env python3
"""Tests of tools/results/make_tables on small made-up calls: merging calls (a later run of a
label wins), marking runs made on another device than most, saying "timed out" for a run
whose step ran past its limit and how many frames a run stopped by its time limit covers,
and refusing bad input with exit 1 or 2.
Run: python3 tools/results/make_tables_test.py  (ctest runs it as tools.make_tables)."""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

MAKE_TABLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "make_tables")
COLUMNS = ["scene", "label", "device", "width", "height", "paths", "rays_per_path",
           "median_gpu_ms", "cache", "total_cache_hit_rate", "warmup", "frame_stride", "frames",
           "frames_requested", "stopped_early"]


def write_summary(path, runs):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        for scene, label, device, ms, hit, *timed in runs:
            frames = timed[0] if timed else 300
            writer.writerow({"frames": frames, "frames_requested": 300,
                             "stopped_early": int(frames < 300),
                             "scene": scene, "label": label, "device": device, "width": 1920,
                             "height": 1080, "paths": 6, "rays_per_path": 4,
                             "median_gpu_ms": ms, "cache": "none" if hit is None else "texel",
                             "total_cache_hit_rate": "" if hit is None else hit,
                             "warmup": 2, "frame_stride": 1})


def write_steps(path, steps):
    with open(path, "w") as f:
        f.write("status\tseconds\tlimit_s\ttable\tscene\tlabel\tcameras\tstride\tflags\n")
        for status, limit, scene, label in steps:
            f.write(f"{status}\t1\t{limit}\t6.2\t{scene}\t{label}\t300\t1\t--cache texel\n")


class MakeTablesTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)

    def path(self, name):
        return os.path.join(self.dir.name, name)

    def run_tool(self, *args):
        return subprocess.run([sys.executable, MAKE_TABLES, *args, "--out", self.path("t.md"),
                               "--plots", self.path("plots"), "--no-png"],
                              capture_output=True, text=True)

    def table_line(self, text, title, column):
        """The cells of the first table row starting with `title` after the heading `column`."""
        section = text[text.index(column):]
        line = next(l for l in section.splitlines() if l.startswith(f"| {title} |"))
        return [cell.strip() for cell in line.strip("|").split("|")]

    def test_merges_calls_marks_other_devices_and_timeouts(self):
        write_summary(self.path("a.csv"), [
            ("classroom", "none", "H200", 2000.0, None),
            ("classroom", "texel_s23_random", "H100", 130.0, 0.99),
            ("classroom", "texel_s23_lru-counter", "H200", 999.0, 0.5)])
        write_summary(self.path("b.csv"), [
            ("classroom", "texel_s23_lru-counter", "H200", 123.4, 0.996),
            ("classroom", "texel_s23_lrw-frame", "H200", 174.0, 0.97),
            ("classroom", "texel_s21_random", "H200", 350.0, 0.88, 120),
            ("classroom", "texel_s21_none", "H200", 0.0, 0.0, 0)])
        write_steps(self.path("a.tsv"), [("timeout", 150, "classroom", "tile_s23_random"),
                                         ("timeout", 120, "classroom", "tile_s23_none")])
        write_steps(self.path("b.tsv"), [("ok", 120, "classroom", "tile_s23_none")])
        result = self.run_tool("--summary", self.path("a.csv"), "--steps", self.path("a.tsv"),
                               "--summary", self.path("b.csv"), "--steps", self.path("b.tsv"))
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.path("t.md")) as f:
            text = f.read()
        self.assertIn("Device: H200 (5 runs); † = run on another device: H100 (1 runs)", text)
        small = "### Small cache"
        # Runs stopped by bench's --time-limit say how many frames their figures cover.
        self.assertEqual(self.table_line(text, "Random", small)[1], "350.0 (120 of 300 frames)")
        self.assertEqual(self.table_line(text, "No eviction", small)[1], "stopped in warm-up")
        large = "### Large cache"
        # The later call's run replaces the earlier one.
        self.assertEqual(self.table_line(text, "LRU counter", large)[1:3], ["123.4", "99.600 %"])
        self.assertEqual(self.table_line(text, "Random", large)[1], "130.0 †")
        self.assertEqual(self.table_line(text, "LRW frame", large)[1], "174.0")
        self.assertEqual(self.table_line(text, "Random", large)[4], "timed out (> 150 s)")
        # A later step that finished clears an earlier timeout; without a run it is not run.
        self.assertEqual(self.table_line(text, "No eviction", large)[4], "—")

    def test_defaults_table_gives_the_ratio_to_table_61s_row(self):
        write_summary(self.path("a.csv"), [
            ("classroom", "texel_default", "H200", 150.0, 0.995),
            ("classroom", "texel_s24_lru-counter", "H200", 120.0, 0.996)])
        result = self.run_tool("--summary", self.path("a.csv"))
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(self.path("t.md")) as f:
            text = f.read()
        self.assertEqual(self.table_line(text, "classroom", "## Defaults"),
                         ["classroom", "`--cache texel`", "150.0", "99.500 %", "120.0",
                          "99.600 %", "1.25×"])
        # No tile default was run: no row for it, and the default is not an "other run".
        self.assertNotIn("`--cache tile`", text)
        self.assertNotIn("| classroom | texel_default |", text)

    def test_bad_input_exits_1_and_usage_exits_2(self):
        missing = self.run_tool("--summary", self.path("missing.csv"))
        self.assertEqual(missing.returncode, 1)
        self.assertIn("cannot read", missing.stderr)
        with open(self.path("plain.csv"), "w") as f:
            f.write("scene,median_gpu_ms\nclassroom,1\n")
        plain = self.run_tool("--summary", self.path("plain.csv"))
        self.assertEqual(plain.returncode, 1)
        self.assertIn("no 'label' column", plain.stderr)
        usage = self.run_tool()
        self.assertEqual(usage.returncode, 2)
        self.assertFalse(os.path.exists(self.path("t.md")))


if __name__ == "__main__":
    unittest.main()

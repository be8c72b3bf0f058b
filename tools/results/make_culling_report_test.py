#!/usr/bin/env python3
"""Tests of tools/results/make_culling_report on a made-up run: medians, peaks and ratios to
`--culling none`, the pictures' FLIP table, and bad input refused with exit 1.
Run: python3 tools/results/make_culling_report_test.py (ctest runs it as
tools.make_culling_report)."""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

REPORT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "make_culling_report")
COLUMNS = ["frame", "gpu_ms", "frame_blas_bytes", "frame_tlas_bytes", "blas_build_gpu_ms",
           "tlas_build_gpu_ms", "active_instances", "omitted_instances", "culling_host_ms"]


def write_frames(path, frames):
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(COLUMNS)
        for i, (trace, mib, blas_ms, active) in enumerate(frames):
            writer.writerow([i, trace, mib * 2**20, 0, blas_ms, 0.5, active, 0, 0.1])


class MakeCullingReportTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)

    def make_run(self, modes):
        """A run folder holding frames_<mode>.csv for each {mode: frames}."""
        run = os.path.join(self.dir.name, "run")
        os.makedirs(run)
        for mode, frames in modes.items():
            write_frames(os.path.join(run, f"frames_{mode}.csv"), frames)
        return run

    def run_report(self, folder, *flags):
        out = os.path.join(self.dir.name, "report.md")
        result = subprocess.run([sys.executable, REPORT, folder, "--out", out, "--plots",
                                 os.path.join(self.dir.name, "plots"), "--no-png", *flags],
                                capture_output=True, text=True)
        text = ""
        if os.path.exists(out):
            with open(out) as f:
                text = f.read()
        return result, text

    def test_the_checks_results(self):
        run = self.make_run({"none": [(100.0, 1000, 0.0, 20000)],
                             "lipac": [(90.0, 300, 4.0, 3000)]})
        with open(os.path.join(run, "checks.txt"), "w") as f:
            f.write("PASS gpufill\nFAIL chit: the picture differs (mean LDR-FLIP 0.002|x)\n"
                    "noise\n")
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("| gpufill | pass |", text)
        self.assertIn("| chit | FAIL: the picture differs (mean LDR-FLIP 0.002\\|x) |", text)
        self.assertNotIn("noise", text)

    def test_ratios_to_none_and_the_pictures(self):
        run = self.make_run({
            "none": [(100.0, 1000, 0.0, 20000), (100.0, 1000, 0.0, 20000),
                     (110.0, 1000, 0.0, 20000)],
            "lipac": [(90.0, 300, 4.0, 3000), (80.0, 200, 1.0, 2000), (80.0, 100, 1.0, 1000)]})
        with open(os.path.join(run, "pictures.txt"), "w") as f:
            f.write("== camera 120: lipac against none\nLDR-FLIP of a against b\n"
                    "  mean  0.004200\n  max  0.5\n== camera 120: frustum against none\n"
                    "  mean  0.031000\n")
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        lipac = next(line for line in text.splitlines() if line.startswith("| lipac |"))
        cells = [c.strip() for c in lipac.strip("|").split("|")]
        # frames, median AS, peak AS, peak / none, trace, BLAS, TLAS, frame, frame / none
        self.assertEqual(cells[1:10], ["3", "200 MiB", "300 MiB", "0.30×", "80.00", "1.00",
                                       "0.50", "81.50", "0.811×"])
        # The path's time, 257.5 ms against 311.5, and the per-camera ratios' median: frames
        # 0.94, 0.81 and 0.74 of none's.
        self.assertEqual(cells[10:12], ["0.827×", "0.811×"])
        mirror = next(line for line in text.splitlines() if line.startswith("| mirror (camera 120)"))
        self.assertEqual([c.strip() for c in mirror.strip("|").split("|")][1:],
                         ["0.0310", "0.0042"])

    def test_the_looks_variants_are_rows_of_their_own(self):
        run = self.make_run({"none": [(100.0, 1000, 0.0, 20000)],
                             "lipac_appearing_16": [(90.0, 500, 1.0, 3000)],
                             "lipac_appearing_2": [(90.0, 250, 1.0, 3000)],
                             "lipac_looks_off": [(90.0, 900, 1.0, 3000)]})
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = [line.split("|")[1].strip() for line in text.splitlines()
                if line.startswith("| lipac_")]
        self.assertEqual(rows, ["lipac_looks_off", "lipac_appearing_2", "lipac_appearing_16"])
        two = next(line for line in text.splitlines() if line.startswith("| lipac_appearing_2 |"))
        self.assertEqual([c.strip() for c in two.strip("|").split("|")][4], "0.25×")

    def test_rows_compare_the_frames_every_row_rendered(self):
        # none ran 4 frames, lipac was stopped after 2: both are summed over the first 2 (over
        # all of none's, its median frame would be 250.5 ms and lipac 0.48x), and
        # a setting copied in by hand (frames_lipac_stride4.csv) is a row after the modes.
        run = self.make_run({
            "none": [(100.0, 1000, 0.0, 20000), (100.0, 1000, 0.0, 20000),
                     (400.0, 1000, 0.0, 20000), (400.0, 1000, 0.0, 20000)],
            "lipac": [(120.0, 300, 0.0, 3000), (120.0, 300, 0.0, 3000)],
            "lipac_stride4": [(105.0, 300, 0.0, 3000), (105.0, 300, 0.0, 3000),
                              (105.0, 900, 0.0, 3000)]})
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("over the first 2 frames", text)
        cells = {line.split("|")[1].strip(): [c.strip() for c in line.strip("|").split("|")]
                 for line in text.splitlines() if line.startswith("| none |")
                 or line.startswith("| lipac")}
        self.assertEqual(list(cells), ["none", "lipac", "lipac_stride4"])
        self.assertEqual(cells["none"][1], "4")  # frames it rendered
        self.assertEqual(cells["lipac"][8:10], ["120.50", "1.199×"])  # not against 3 frames
        self.assertEqual(cells["lipac_stride4"][3:5], ["300 MiB", "0.30×"])  # its 3rd is past

    def test_the_pictures_rows_name_each_cameras_role(self):
        run = self.make_run({"none": [(100.0, 1000, 0.0, 20000)]})
        with open(os.path.join(run, "pictures.txt"), "w") as f:
            for camera, role, flip in [("153", "mirror", 0.002), ("8", "flying in", 0.0003)]:
                f.write(f"== camera {camera} ({role}): lipac against none\n  mean  {flip}\n")
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = [line for line in text.splitlines() if "(camera " in line]
        self.assertEqual([row.split("|")[1].strip() for row in rows],
                         ["mirror (camera 153)", "flying in (camera 8)"])
        self.assertEqual(rows[0].split("|")[3].strip(), "0.0020")

    def test_pictured_variants_are_columns_of_their_own(self):
        run = self.make_run({"none": [(100.0, 1000, 0.0, 20000)]})
        with open(os.path.join(run, "pictures.txt"), "w") as f:
            for mode, flip in [("lipac", 0.004), ("lipac_every8", 0.006), ("frustum", 0.15)]:
                f.write(f"== camera 120 (mirror): {mode} against none\n  mean  {flip}\n")
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        lines = text.splitlines()
        header = next(line for line in lines if line.startswith("| camera |"))
        self.assertEqual([c.strip() for c in header.strip("|").split("|")],
                         ["camera", "frustum", "lipac", "lipac_every8"])
        row = next(line for line in lines if "(camera 120)" in line)
        self.assertEqual([c.strip() for c in row.strip("|").split("|")][1:],
                         ["0.1500", "0.0040", "0.0060"])

    def test_frames_by_kind_against_none(self):
        run = self.make_run({})
        none = [(99.5, 1000, 0.0, 20000)] * 8  # frame time 100 with the TLAS build
        write_frames(os.path.join(run, "frames_none.csv"), none)
        # Frames 0 and 4 count, frame 6 has a look: quiet 0.95, counting 1.10, look 1.20.
        path = os.path.join(run, "frames_lipac.csv")
        with open(path, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(COLUMNS + ["looks", "feedback_frame"])
            for i in range(8):
                trace = 110.0 if i % 4 == 0 else 120.0 if i == 6 else 95.0
                writer.writerow([i, trace - 0.5, 300 * 2**20, 0, 0.0, 0.5, 5000, 0, 0.1,
                                 int(i == 6), int(i % 4 == 0)])
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        row = next(line for line in text.splitlines() if line.startswith("| lipac | 0.9"))
        self.assertEqual([c.strip() for c in row.strip("|").split("|")],
                         ["lipac", "0.950× (5)", "1.100× (2)", "1.200× (1)"])
        # A run from before the column has no such table.
        write_frames(path, [(100.0, 1000, 0.0, 20000)] * 8)
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn("| mode | quiet |", text)

    def test_rays_against_none_flag_frames_that_lost_geometry(self):
        run = self.make_run({})
        write_frames(os.path.join(run, "frames_none.csv"), [(100.0, 1000, 0.0, 20000)] * 4)
        none_rays = [1000, 1000, 2000, 1000]
        culled_rays = [1000, 990, 1000, 940]  # 1.0, 0.99, 0.5 (short), 0.94 (short)
        for mode, rays in [("none", none_rays), ("lipac", culled_rays)]:
            with open(os.path.join(run, f"frames_{mode}.csv"), "w", newline="") as f:
                writer = csv.writer(f)
                writer.writerow(COLUMNS + ["rays"])
                for i, r in enumerate(rays):
                    writer.writerow([i, 99.5, 300 * 2**20, 0, 0.0, 0.5, 5000, 0, 0.1, r])
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        row = next(line for line in text.splitlines() if line.startswith("| lipac | 0.500"))
        self.assertEqual([c.strip() for c in row.strip("|").split("|")],
                         ["lipac", "0.500×", "0.965×", "2 of 4"])
        # A run without the column has no such table.
        write_frames(os.path.join(run, "frames_lipac.csv"), [(100.0, 1000, 0.0, 20000)] * 4)
        result, text = self.run_report(run)
        self.assertNotIn("| mode | lowest |", text)

    def test_plots_go_beside_a_report_written_under_another_name(self):
        run = self.make_run({"none": [(100.0, 1000, 0.0, 20000)] * 2,
                             "lipac": [(99.0, 300, 0.0, 5000)] * 2})
        out = os.path.join(self.dir.name, "results", "split.md")
        result = subprocess.run([sys.executable, REPORT, run, "--out", out, "--no-png"],
                                capture_output=True, text=True, cwd=self.dir.name)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(os.path.exists(os.path.join(self.dir.name, "results", "split_plots",
                                                    "culling.gp")))
        # Not the default report's folder (relative to the working directory).
        self.assertFalse(os.path.exists(os.path.join(self.dir.name, "docs")))

    def test_skipped_frames_leave_every_run(self):
        # The GPU's first frames after the scene's build can run slow in one run and not in
        # another: none's first frame here is 3x its second. With it, lipac's path reads
        # 0.601x none's (301.5 against 501.5 ms); without, 1.000x, and the rows still say how
        # many frames each ran.
        run = self.make_run({
            "none": [(300.0, 1000, 0.0, 20000), (100.0, 1000, 0.0, 20000),
                     (100.0, 1000, 0.0, 20000)],
            "lipac": [(100.0, 300, 0.0, 3000), (100.0, 300, 0.0, 3000),
                      (100.0, 300, 0.0, 3000)]})
        result, text = self.run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        lipac = next(line for line in text.splitlines() if line.startswith("| lipac |"))
        self.assertEqual([c.strip() for c in lipac.strip("|").split("|")][10], "0.601×")
        result, text = self.run_report(run, "--skip-frames", "1")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("frames 1 to 2 of the path (the first 1 left out", text)
        lipac = next(line for line in text.splitlines() if line.startswith("| lipac |"))
        cells = [c.strip() for c in lipac.strip("|").split("|")]
        self.assertEqual(cells[1], "3")
        self.assertEqual(cells[9:12], ["1.000×", "1.000×", "1.000×"])
        result, _ = self.run_report(run, "--skip-frames", "3")
        self.assertEqual(result.returncode, 1)
        self.assertIn("none left after --skip-frames 3", result.stderr)
        result, _ = self.run_report(run, "--skip-frames", "-1")
        self.assertEqual(result.returncode, 2)

    def test_bad_input_exits_1(self):
        result, _ = self.run_report(os.path.join(self.dir.name, "missing"))
        self.assertEqual(result.returncode, 1)
        empty = os.path.join(self.dir.name, "empty")
        os.makedirs(empty)
        result, _ = self.run_report(empty)
        self.assertEqual(result.returncode, 1)
        with open(os.path.join(empty, "frames_none.csv"), "w") as f:
            f.write("frame,gpu_ms\n0,1\n")
        result, _ = self.run_report(empty)
        self.assertEqual(result.returncode, 1)
        self.assertIn("not a culling run", result.stderr)


if __name__ == "__main__":
    unittest.main()

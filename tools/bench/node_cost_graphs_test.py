#!/usr/bin/env python3
"""Tests of tools/bench/node_cost_graphs.py without a GPU: every graph it writes compiles
(`memograph check`), every node with a nonzero estimate is timed or skipped with a reason,
a node's copies form one dependent chain that the compiler keeps whole, the table turns
made-up times into the costs they stand for, and `calibrate` turns a small made-up timing
table into kNodeCosts' values in a copy of compiler/cut.cpp.
Run: python3 tools/bench/node_cost_graphs_test.py build/tools/memograph
(ctest runs it as tools.node_cost_graphs)."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

SCRIPT = Path(__file__).resolve().parent / "node_cost_graphs.py"
CUT_CPP = Path(__file__).resolve().parents[2] / "compiler" / "cut.cpp"
MEMOGRAPH = None  # argv[1]
WORK = 16  # Add units a pixel: few copies, so that the graphs compile quickly


def write_graphs(folder, work=WORK, costs=CUT_CPP):
    subprocess.run(
        [sys.executable, SCRIPT, "write", "--memograph", MEMOGRAPH, "--out", folder,
         "--work", str(work), "--costs", str(costs)],
        check=True, capture_output=True, text=True)
    return json.loads((Path(folder) / "plan.json").read_text())


# A cost table of a few rows, so that the copies the graphs get do not move when
# compiler/cut.cpp is calibrated again.
FIXED_COSTS = """const NodeCost kNodeCosts[] = {
    {"MixColor", 1},
    {"Mapping", 3},
    {"VoronoiTexture", 60},
    {"NoiseTexture", 2, 10},
};
"""


def statements(path):
    """The graph's statements: [(node, {socket: link or constant text}, {output: link})]."""
    result = []
    for line in Path(path).read_text().split(";"):
        words = re.findall(r'"[^"]*"|\([^)]*\)|\[[^\]]*\]|\S+', line)
        if not words or words[0] == "material":
            continue
        inputs, outputs = {}, {}
        for word in words[1:]:
            match = re.match(r"^(\w+)([<>=])(.*)$", word)
            if match and match.group(2) == ">":
                outputs[match.group(1)] = match.group(3)
            elif match:
                inputs[match.group(1)] = (match.group(2), match.group(3))
        result.append((words[0], inputs, outputs))
    return result


class NodeCostGraphs(unittest.TestCase):
    def test_every_graph_compiles_and_every_estimated_node_is_timed_or_skipped(self):
        with tempfile.TemporaryDirectory() as folder:
            plan = write_graphs(folder)
            for material in sorted(plan["graphs"]):
                check = subprocess.run(
                    [MEMOGRAPH, "check", os.path.join(folder, material + ".mgraph")],
                    capture_output=True, text=True)
                self.assertEqual(check.returncode, 0, material + "\n" + check.stderr)
            timed = {g["node"] for g in plan["graphs"].values() if g["node"]}
            for node, (base, per_octave) in plan["estimates"].items():
                if base > 0 or per_octave > 0:
                    self.assertTrue(node in timed or node in plan["skipped"], node)
            # An fBm node is timed at two Detail values, for its octave term.
            self.assertIn("NoiseTexture_detail2", plan["graphs"])
            self.assertIn("NoiseTexture_detail8", plan["graphs"])
            self.assertIn("second", plan["skipped"]["Bump"])
            for graph in plan["graphs"].values():
                if graph["node"]:
                    baseline = plan["graphs"][graph["baseline"]]
                    self.assertEqual(baseline["copies"], graph["copies"], graph)
                    self.assertEqual(baseline["driven"], graph["driven"], graph)

    def test_copies_follow_the_estimate_in_powers_of_two(self):
        with tempfile.TemporaryDirectory() as folder:
            costs = Path(folder) / "costs.cpp"
            costs.write_text(FIXED_COSTS)
            plan = write_graphs(os.path.join(folder, "graphs"), work=1024, costs=costs)
        graphs = plan["graphs"]
        self.assertEqual(graphs["Add"]["copies"], 1024)  # estimate 1
        self.assertEqual(graphs["MixColor"]["copies"], 1024)  # estimate 1
        self.assertEqual(graphs["Mapping"]["copies"], 256)  # 3: 341, nearest power 256
        self.assertEqual(graphs["VoronoiTexture"]["copies"], 16)  # 60: 17
        # Both Details at the longer one's length: 92 for Detail 8, 11, at least 8.
        self.assertEqual(graphs["NoiseTexture_detail2"]["copies"], 8)
        self.assertEqual(graphs["NoiseTexture_detail8"]["copies"], 8)  # 92: 11, at least 8
        self.assertEqual(graphs["baseline_float_1024"]["copies"], 1024)

    def test_each_copy_reads_the_previous_copys_output(self):
        with tempfile.TemporaryDirectory() as folder:
            plan = write_graphs(folder)
            for material, driven in (("Add", "A"), ("MixColor", "Factor"),
                                     ("NoiseTexture_detail2", "Vector"),
                                     ("ImageTexture", "UV")):
                graph = plan["graphs"][material]
                nodes = statements(Path(folder) / f"{material}.mgraph")
                producer = {link: (i, node, inputs)
                            for i, (node, inputs, outputs) in enumerate(nodes)
                            for link in outputs.values()}
                copies = [(i, inputs) for i, (node, inputs, _) in enumerate(nodes)
                          if node == graph["node"]]
                self.assertEqual(len(copies), graph["copies"], material)
                for (previous, _), (index, inputs) in zip(copies, copies[1:]):
                    # Walk back from this copy's driven input through the link's nodes
                    # (multiply-add, dot, add) to the copy before it, never to uv alone.
                    self.assertEqual(inputs[driven][0], "<", material)
                    frontier, seen = [inputs[driven][1]], set()
                    while frontier:
                        at, node, node_inputs = producer[frontier.pop()]
                        seen.add(at)
                        if at > previous and node != graph["node"]:
                            frontier += [v for k, v in node_inputs.values() if k == "<"]
                    self.assertIn(previous, seen, f"{material}: copy at {index}")

    def test_the_compiler_keeps_every_copy_of_the_chain(self):
        # The compiler folds constants: a chain fed from uv must survive it whole.
        with tempfile.TemporaryDirectory() as folder:
            plan = write_graphs(folder)
            out = Path(folder) / "glsl"
            subprocess.run(
                [MEMOGRAPH, "compile", Path(folder) / "Add.mgraph",
                 Path(folder) / "Mul.mgraph", "--target", "glsl", "-o", out, "--quiet"],
                check=True, capture_output=True, text=True)
            for node in ("Add", "Mul"):
                text = (out / f"{node}.glsl").read_text()
                body = text[text.index(f"void EvaluateMaterial_{node}("):]
                body = body[: body.index("\n}\n")]
                self.assertEqual(len(re.findall(rf"^  {node}\(", body, re.M)),
                                 plan["graphs"][node]["copies"], node)

    def test_the_table_gives_each_node_its_cost_in_add_units(self):
        with tempfile.TemporaryDirectory() as folder:
            plan = write_graphs(folder)
            add_ns = 0.25  # ns per Add
            times = []
            for material, graph in plan["graphs"].items():
                baseline = 100.0 * graph["copies"]  # ns per pixel
                node = graph["node"]
                if node is None:
                    units = 0.0
                elif node in ("Add", "Mul"):
                    units = 1.0
                elif node == "NoiseTexture":  # 7 + 11 per octave; Detail d has d + 1
                    units = 7.0 + 11.0 * (graph["detail"] + 1)
                else:
                    units = 3.0
                ns = baseline + graph["copies"] * units * add_ns
                times.append(f"time {material} {ns:.6f} ns/pixel (median of 7 dispatches)")
            times_path = Path(folder) / "times.txt"
            times_path.write_text("\n".join(times) + "\n")
            table = subprocess.run(
                [sys.executable, SCRIPT, "table", "--plan", Path(folder) / "plan.json",
                 "--times", times_path], check=True, capture_output=True, text=True).stdout
        rows = {}
        for line in table.splitlines():
            fields = line.rsplit(None, 5)
            if len(fields) == 6 and not line.startswith("#"):
                rows[fields[0].strip()] = fields[1:]
        self.assertEqual(rows["Add"][0], "0.250000")
        self.assertEqual(rows["Add"][2], "1.00")
        self.assertEqual(rows["Mul"][2], "1.00")
        self.assertEqual(rows["NoiseTexture"][2], "7.00")
        self.assertEqual(rows["NoiseTexture per octave"][2], "11.00")
        self.assertEqual(rows["VoronoiTexture"][2], "3.00")
        voronoi_copies = plan["graphs"]["VoronoiTexture"]["copies"]
        self.assertEqual(rows["VoronoiTexture"][1], str(voronoi_copies))
        self.assertIn("# not timed: Geometry: reads only MaterialInputs", table)

    def test_a_missing_add_time_is_an_error(self):
        with tempfile.TemporaryDirectory() as folder:
            write_graphs(folder)
            times_path = Path(folder) / "times.txt"
            times_path.write_text("time NoiseTexture_detail2 5.0 ns/pixel\n")
            table = subprocess.run(
                [sys.executable, SCRIPT, "table", "--plan", Path(folder) / "plan.json",
                 "--times", times_path], capture_output=True, text=True)
        self.assertEqual(table.returncode, 1)
        self.assertIn("Add and its baseline must be timed", table.stderr)


class Calibration(unittest.TestCase):
    # A table as `table` prints it: Add 0.02 ns, so Voronoi is 40.5 units, Noise 3 + 6.5
    # an octave, Mapping below MIN_COST (noise around zero) and Gamma negative.
    TIMINGS = """# node costs: dependent chains of about 1024 Add units a pixel
# node                                ns/eval copies  Add units  estimate   ratio
Add                                  0.020000   1024       1.00      1.00    1.00
Mul                                  0.021000   1024       1.05      1.00    1.05
VoronoiTexture                       0.810000     16      40.50     60.00    0.68
NoiseTexture                         0.060000     32       3.00      2.00    1.50
NoiseTexture per octave              0.130000      8       6.50     10.00    0.65
Mapping                              0.004000    256       0.20      3.00    0.07
Gamma                               -0.003000    256      -0.15      3.00   -0.05
# not timed: Geometry: reads only MaterialInputs: its copies would be one
"""

    def calibrate(self, folder, *extra):
        timings = Path(folder) / "node_timings.txt"
        timings.write_text(self.TIMINGS)
        costs = Path(folder) / "cut.cpp"
        shutil.copy(CUT_CPP, costs)
        run = subprocess.run(
            [sys.executable, SCRIPT, "calibrate", "--timings", timings, "--costs", costs,
             *extra], capture_output=True, text=True)
        return run, costs.read_text()

    def test_calibrate_prints_the_rows_in_add_units(self):
        with tempfile.TemporaryDirectory() as folder:
            run, text = self.calibrate(folder)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn('    {"VoronoiTexture", 40.5},', run.stdout)
        self.assertIn('    {"NoiseTexture", 3, 6.5},', run.stdout)
        self.assertIn('    {"Mapping", 0.5},', run.stdout)  # at least MIN_COST
        self.assertIn('    {"Gamma", 0.5},', run.stdout)
        self.assertNotIn('"Add"', run.stdout)  # the unit, not a kNodeCosts row
        kept = run.stdout[run.stdout.index("kept the estimate"):]
        for node in ("MusgraveTexture", "Geometry", "BrickTexture"):
            self.assertIn(node, kept)
        self.assertNotIn("VoronoiTexture", kept)
        self.assertEqual(text, CUT_CPP.read_text())  # without --write, nothing changes

    def test_calibrate_write_sets_the_timed_rows_and_keeps_the_others(self):
        with tempfile.TemporaryDirectory() as folder:
            run, text = self.calibrate(folder, "--write")
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn('{"VoronoiTexture", 40.5},', text)
        self.assertIn('{"NoiseTexture", 3, 6.5},', text)
        self.assertIn('{"Mapping", 0.5},', text)
        # Untimed rows and their comments stay as they were.
        original = CUT_CPP.read_text()
        for node in ("MusgraveTexture", "Geometry", "UVInput", "BrickTexture"):
            row = re.search(r'\{"' + node + r'",[^}]*\},.*', original).group(0)
            self.assertIn(row, text)
        self.assertEqual(len(text.splitlines()), len(original.splitlines()))

    def test_timings_without_an_add_row_are_refused(self):
        with tempfile.TemporaryDirectory() as folder:
            timings = Path(folder) / "node_timings.txt"
            timings.write_text("VoronoiTexture 0.81 16 40.5 60 0.68\n")
            run = subprocess.run(
                [sys.executable, SCRIPT, "calibrate", "--timings", timings, "--costs", CUT_CPP],
                capture_output=True, text=True)
        self.assertEqual(run.returncode, 1)
        self.assertIn("positive Add row", run.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: node_cost_graphs_test.py MEMOGRAPH")
    MEMOGRAPH = sys.argv.pop(1)
    unittest.main()

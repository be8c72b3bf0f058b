#!/usr/bin/env python3
"""Tests of tools/bench/node_cost_graphs.py without a GPU: every graph it writes compiles
(`memograph check`), every node with a nonzero estimate is timed or skipped with a reason,
and the table turns made-up times into the costs they stand for.
Run: python3 tools/bench/node_cost_graphs_test.py build/tools/memograph
(ctest runs it as tools.node_cost_graphs)."""
import json
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

SCRIPT = Path(__file__).resolve().parent / "node_cost_graphs.py"
MEMOGRAPH = None  # argv[1]


def write_graphs(folder):
    subprocess.run(
        [sys.executable, SCRIPT, "write", "--memograph", MEMOGRAPH, "--out", folder,
         "--copies", "1"],
        check=True, capture_output=True, text=True)
    return json.loads((Path(folder) / "plan.json").read_text())


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
            for graph in plan["graphs"].values():
                if graph["node"]:
                    self.assertIn(graph["baseline"], plan["graphs"])

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
            fields = line.rsplit(None, 4)
            if len(fields) == 5 and not line.startswith("#") and fields[1] != "ns/eval":
                rows[fields[0].strip()] = fields[1:]
        self.assertEqual(rows["Add"][1], "1.00")
        self.assertEqual(rows["Mul"][1], "1.00")
        self.assertEqual(rows["NoiseTexture"][1], "7.00")
        self.assertEqual(rows["NoiseTexture per octave"][1], "11.00")
        self.assertEqual(rows["VoronoiTexture"][1], "3.00")
        self.assertIn('    {"NoiseTexture", 7, 11},', table)
        self.assertIn('    {"VoronoiTexture", 3},', table)

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


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: node_cost_graphs_test.py MEMOGRAPH")
    MEMOGRAPH = sys.argv.pop(1)
    unittest.main()

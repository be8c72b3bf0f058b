#!/usr/bin/env python3
"""Graphs that time each node of compiler/cut.cpp's cost table, and the table of the timings.

tools/bench/node_costs_device.sh drives it (docs/design/memoization.md, "Measuring the node
costs"):

  node_cost_graphs.py write --memograph M --out DIR [--copies K]
      writes DIR/<Node>.mgraph for every node with a nonzero estimate in kNodeCosts (an fBm
      node twice, at Detail 2 and 8, for its octave term), Add and Mul (the unit), and a
      baseline per output type and K; DIR/plan.json says which graph times what.
  node_cost_graphs.py table --plan DIR/plan.json --times BAKE_OUTPUT
      reads `memograph bake --time`'s lines and prints, per node: ns per evaluation, its
      cost in Add units, kNodeCosts' estimate and measured / estimate.

Each graph evaluates its node K times per pixel (K = --copies for a node estimated at 8 Add
units or more, 4 K below, 16 K for a one-operation node, so that a cheap node's time stands
out of its baseline's). Copy i reads inputs that vary with uv (u, v scaled into the
socket's useful range and shifted by i), so that no copy equals another and none folds to
a constant. Every graph sums all its inputs into the emission (so the driver computes the
same inputs in every graph) and the copies' first float, float2 or float3 output into the
base colour (so that no copy is dead code). A baseline graph of the same output type and K
sums the inputs themselves instead of the node's outputs: the node's time is the graph's
time minus its baseline's, divided by K.
"""

import argparse
import json
import math
import re
import struct
import subprocess
import sys
from pathlib import Path

# Octave counts for Detail d, as compiler/cut.cpp's octaves(): floor(d) + 1 for whole d.
DETAILS = (2, 8)
FLOATISH = {"float", "float2", "float3", "float4"}
# The output types a copy's result may have; each has its baseline.
OUTPUT_KINDS = ("float", "float2", "float3")
# The socket a copy varies, in order of preference; else the first float-ish input.
DRIVEN_SOCKETS = ("Vector", "UV", "Position", "Color", "Height", "Normal", "Fac", "In")
# (low, span) of a varied socket's values: where the node does its usual work (a Blackbody
# below 800 K or a Wavelength outside 380..780 nm would take a constant branch).
SOCKET_RANGES = {
    "Vector": (0.0, 16.0),
    "Position": (-1.0, 2.0),
    "Temperature": (1000.0, 11000.0),
    "Wavelength": (380.0, 400.0),
    "IOR": (1.1, 1.0),
    "Normal": (0.2, 0.6),
}
DEFAULT_RANGE = (0.0, 1.0)
TEXTURE = "cost_texture.pfm"
MIN_COST = 0.5  # Add units: the least cost a measured node is given
TEXTURE_SIZE = 256


def parse_cost_table(cut_cpp):
    """kNodeCosts' rows: {node: (base, perOctave)}."""
    text = Path(cut_cpp).read_text()
    body = text[text.index("kNodeCosts[]"):]
    body = body[: body.index("};")]
    costs = {}
    for name, base, per_octave in re.findall(
        r'\{"(\w+)",\s*([0-9.eE+-]+)(?:,\s*([0-9.eE+-]+))?\}', body
    ):
        costs[name] = (float(base), float(per_octave or 0))
    if not costs:
        sys.exit(f"node_cost_graphs.py: no kNodeCosts rows found in {cut_cpp}")
    return costs


def node_signatures(memograph, nodes):
    """Each node's inputs [(name, type, has_default)] and outputs [(name, type)] from one
    `memograph nodes NODE...`, its first overload's types (the one without derivatives)."""
    listing = subprocess.run(
        [memograph, "nodes", *nodes], capture_output=True, text=True, check=False
    )
    if listing.returncode != 0:
        sys.exit(f"node_cost_graphs.py: `memograph nodes` failed:\n{listing.stderr}")
    blocks = {}  # node: its lines; a block starts at an unindented "Name  (file.inc)"
    current = None
    for line in listing.stdout.splitlines():
        if line and not line[0].isspace():
            current = blocks.setdefault(line.split()[0], [])
        elif current is not None:
            current.append(line)
    return {node: parse_signature(node, blocks.get(node, [])) for node in nodes}


def parse_signature(node, lines):
    defaults = {}
    overload = None
    for line in lines:
        match = re.match(r"^  in  (\w+)( = .*)?$", line)
        if match:
            defaults[match.group(1)] = match.group(2) is not None
        if overload is None and line.startswith(f"    {node}("):
            overload = line.strip()
    if overload is None:
        sys.exit(f"node_cost_graphs.py: `memograph nodes {node}` lists no overload")
    match = re.match(rf"{node}\((.*)\)(?: -> (.*))?$", overload)
    inputs = []
    for item in filter(None, (s.strip() for s in match.group(1).split(","))):
        kind, name = item.split()
        inputs.append((name, kind, defaults.get(name, False)))
    outputs = [tuple(item.strip().split()) for item in (match.group(2) or "").split(",") if item]
    return inputs, [(name, kind) for kind, name in outputs]


class GraphText:
    """One .mgraph being written: statements and fresh link numbers."""

    def __init__(self, material):
        self.lines = [f"material {material};", "UVInput Out>0;", "Separate2 Vector<0 X>1 Y>2;"]
        self.next_link = 3
        self.u, self.v = 1, 2

    def link(self):
        self.next_link += 1
        return self.next_link - 1

    def add(self, statement):
        self.lines.append(statement + ";")

    def scalar(self, coordinate, scale, offset):
        out = self.link()
        self.add(f"MultiplyAdd A<{coordinate} B={scale:.9g} C={offset:.9g} Out>{out}")
        return out

    def text(self):
        return "\n".join(self.lines) + "\n"


def copy_inputs(graph, index, copies, value_range):
    """Copy `index`'s three varied scalars in `value_range`: u, v and a mix, each shifted by
    the copy's index so that no two copies read the same value."""
    low, span = value_range
    shift = index / copies
    su = graph.scalar(graph.u, span / 2, low + span * shift / 2)
    sv = graph.scalar(graph.v, span / 2, low + span * (1 - shift) / 2)
    sw = graph.scalar(graph.u, span / 4, low + span * (0.25 + shift / 2) / 2)
    return su, sv, sw


def as_type(graph, scalars, kind):
    """The copy's scalars as a value of `kind` (float .. float4)."""
    su, sv, sw = scalars
    if kind == "float":
        return su
    out = graph.link()
    if kind == "float2":
        graph.add(f"Combine2 X<{su} Y<{sv} Vector>{out}")
    elif kind == "float3":
        graph.add(f"Combine3 X<{su} Y<{sv} Z<{sw} Vector>{out}")
    else:
        graph.add(f"Combine4 X<{su} Y<{sv} Z<{sw} W=1 Vector>{out}")
    return out


def accumulate(graph, total, value):
    if total is None:
        return value
    out = graph.link()
    graph.add(f"Add A<{total} B<{value} Out>{out}")
    return out


def finish(graph, inputs_total, outputs_total, output_kind):
    """Every input into the emission, every copy's output into the base colour."""
    graph.add(f"EmissionOutput Color<{inputs_total} Strength=1")
    if output_kind == "float":
        colour = graph.link()
        graph.add(
            f"Combine3 X<{outputs_total} Y<{outputs_total} Z<{outputs_total} Vector>{colour}"
        )
        outputs_total = colour
    elif output_kind == "float2":
        x, y, colour = graph.link(), graph.link(), graph.link()
        graph.add(f"Separate2 Vector<{outputs_total} X>{x} Y>{y}")
        graph.add(f"Combine3 X<{x} Y<{y} Z=0 Vector>{colour}")
        outputs_total = colour
    graph.add(f"BaseColorOutput In<{outputs_total}")


def ramp_table():
    """A 256-entry RGBA ramp from black to white (Table sockets take exactly 1024 numbers)."""
    values = []
    for i in range(256):
        t = i / 255
        values += [t, t * t, 1 - t, 1]
    return "[" + " ".join(f"{x:.6g}" for x in values) + "]"


def write_texture(path):
    """A grey-scale gradient PFM for ImageTexture (the device bundle reads only PFM)."""
    size = TEXTURE_SIZE
    pixels = bytearray()
    for y in range(size):
        for x in range(size):
            r = (x ^ y) / size
            pixels += struct.pack("<fff", r, x / size, y / size)
    path.write_bytes(f"PF\n{size} {size}\n-1.0\n".encode() + bytes(pixels))


def required_value(name, kind):
    """A value for a socket without a default that the copy does not vary: the texture's
    size for the texel nodes' Width and Height."""
    if name in ("Width", "Height"):
        return TEXTURE_SIZE
    return 0 if kind == "int" else 0.5


def driven_socket(inputs):
    floatish = [name for name, kind, _ in inputs if kind.removesuffix("_D") in FLOATISH]
    for preferred in DRIVEN_SOCKETS:
        if preferred in floatish:
            return preferred
    return floatish[0] if floatish else None


def timed_node_graph(material, node, inputs, outputs, copies, extra):
    """`copies` evaluations of `node` with its driven socket varied; None when the node has
    no float-ish input (it reads only MaterialInputs: its copies would be one) or output."""
    driven = driven_socket(inputs)
    result = next(((n, k) for n, k in outputs if k.removesuffix("_D") in OUTPUT_KINDS), None)
    if driven is None or result is None:
        return None
    driven_kind = next(k for n, k, _ in inputs if n == driven).removesuffix("_D")
    output_name, output_kind = result[0], result[1].removesuffix("_D")
    graph = GraphText(material)
    inputs_total = outputs_total = None
    for index in range(copies):
        scalars = copy_inputs(graph, index, copies, SOCKET_RANGES.get(driven, DEFAULT_RANGE))
        vector = as_type(graph, scalars, "float3")
        inputs_total = accumulate(graph, inputs_total, vector)
        value = vector if driven_kind == "float3" else as_type(graph, scalars, driven_kind)
        items = [f"{driven}<{value}"]
        for name, kind, has_default in inputs:
            if name == driven or name in extra:
                continue
            if kind == "Table":
                items.append(f"{name}={ramp_table()}")
            elif kind == "TextureRef":
                items.insert(0, f'"{TEXTURE}"')
            elif not has_default:
                items.append(f"{name}={required_value(name, kind)}")
        items += [f"{name}={value}" for name, value in extra.items()]
        out = graph.link()
        graph.add(f"{node} {' '.join(items)} {output_name}>{out}")
        outputs_total = accumulate(graph, outputs_total, out)
    finish(graph, inputs_total, outputs_total, output_kind)
    return graph.text(), output_kind


def baseline_graph(material, copies, output_kind):
    """The timed graphs' inputs and sums without a node: each copy's input is its output."""
    graph = GraphText(material)
    inputs_total = outputs_total = None
    for index in range(copies):
        scalars = copy_inputs(graph, index, copies, DEFAULT_RANGE)
        vector = as_type(graph, scalars, "float3")
        inputs_total = accumulate(graph, inputs_total, vector)
        value = vector if output_kind == "float3" else as_type(graph, scalars, output_kind)
        outputs_total = accumulate(graph, outputs_total, value)
    finish(graph, inputs_total, outputs_total, output_kind)
    return graph.text()


def copies_factor(base, per_octave):
    """How many times --copies a node is evaluated: more for cheap nodes, so that their
    time stands out of the baseline's (which makes and sums the inputs) at any size."""
    estimate = base + per_octave * octaves(DETAILS[0])
    if estimate <= 1:
        return 16
    return 4 if estimate < 8 else 1


def baseline_name(output_kind, copies):
    return f"baseline_{output_kind}_{copies}"


def write_graphs(args):
    costs = parse_cost_table(args.costs)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    write_texture(out / TEXTURE)
    plan = {"copies": args.copies, "graphs": {}, "skipped": {}, "estimates": costs}
    measured = ["Add", "Mul"] + sorted(n for n, (b, p) in costs.items() if b > 0 or p > 0)
    signatures = node_signatures(args.memograph, measured)
    for node in measured:
        inputs, outputs = signatures[node]
        input_names = {name for name, _, _ in inputs}
        variants = [({}, None)]
        if costs.get(node, (0, 0))[1] > 0 and "Detail" in input_names:
            # Wave adds its fBm only where Distortion is nonzero.
            distortion = {"Distortion": 1} if node == "WaveTexture" else {}
            variants = [({"Detail": d, **distortion}, d) for d in DETAILS]
        for extra, detail in variants:
            material = node if detail is None else f"{node}_detail{detail}"
            copies = args.copies * copies_factor(*costs.get(node, (1.0, 0.0)))
            graph = timed_node_graph(material, node, inputs, outputs, copies, extra)
            if graph is None:
                plan["skipped"][node] = (
                    "an output node: one a material"
                    if not outputs
                    else "reads only MaterialInputs: its copies would be one"
                    if driven_socket(inputs) is None
                    else "no float, float2 or float3 output"
                )
                break
            text, output_kind = graph
            (out / f"{material}.mgraph").write_text(text)
            plan["graphs"][material] = {
                "node": node,
                "output": output_kind,
                "detail": detail,
                "copies": copies,
                "baseline": baseline_name(output_kind, copies),
            }
    for kind, copies in sorted({(g["output"], g["copies"]) for g in plan["graphs"].values()}):
        material = baseline_name(kind, copies)
        (out / f"{material}.mgraph").write_text(baseline_graph(material, copies, kind))
        plan["graphs"][material] = {"node": None, "output": kind, "copies": copies}
    (out / "plan.json").write_text(json.dumps(plan, indent=1) + "\n")
    print(f"wrote {len(plan['graphs'])} graphs to {out} ({len(plan['skipped'])} nodes skipped)")


def octaves(detail):
    """compiler/cut.cpp's octaves() for a whole Detail."""
    return math.floor(detail) + 1


def read_times(path):
    """`memograph bake --time` lines: {material: ns per pixel}."""
    times = {}
    for line in Path(path).read_text().splitlines():
        match = re.match(r"^time (\w+) ([0-9.eE+-]+) ns/pixel", line)
        if match:
            times[match.group(1)] = float(match.group(2))
    return times


def print_table(args):
    plan = json.loads(Path(args.plan).read_text())
    times = read_times(args.times)
    missing = [m for m in plan["graphs"] if m not in times]
    if missing:
        print(f"node_cost_graphs.py: no time for {', '.join(missing)}", file=sys.stderr)
    if "Add" not in times or plan["graphs"]["Add"]["baseline"] not in times:
        sys.exit("node_cost_graphs.py: Add and its baseline must be timed")

    def per_evaluation(material):
        graph = plan["graphs"][material]
        return (times[material] - times[graph["baseline"]]) / graph["copies"]

    unit = per_evaluation("Add")
    rows = []  # (label, ns, estimate)
    by_node = {}
    for material, graph in plan["graphs"].items():
        if graph["node"] and material in times and graph["baseline"] in times:
            by_node.setdefault(graph["node"], {})[graph.get("detail")] = per_evaluation(material)
    for node, measured in sorted(by_node.items()):
        base, per_octave = plan["estimates"].get(node, (1.0, 0.0))
        if None in measured:
            rows.append((node, measured[None], base))
            continue
        low, high = DETAILS
        if low not in measured or high not in measured:
            continue
        octave_ns = (measured[high] - measured[low]) / (octaves(high) - octaves(low))
        rows.append((node, measured[low] - octave_ns * octaves(low), base))
        rows.append((f"{node} per octave", octave_ns, per_octave))
    copies = plan["copies"]
    print(
        f"# {copies}, {4 * copies} or {16 * copies} evaluations a pixel (costlier nodes fewer); "
        f"1 Add unit = {unit:.4f} ns per evaluation"
    )
    print(f"{'node':34} {'ns/eval':>9} {'Add units':>10} {'estimate':>9} {'ratio':>7}")
    for label, ns, estimate in rows:
        units = ns / unit if unit > 0 else float("nan")
        ratio = units / estimate if estimate > 0 else float("nan")
        print(f"{label:34} {ns:9.4f} {units:10.2f} {estimate:9.2f} {ratio:7.2f}")
    for node, why in sorted(plan["skipped"].items()):
        print(f"{node:34} {'-':>9} {'-':>10} {'-':>9} {'-':>7}  skipped: {why}")
    print_cost_rows(rows, unit, plan["estimates"])


def print_cost_rows(rows, unit, estimates):
    """The measured costs as compiler/cut.cpp's kNodeCosts rows, to paste over the
    estimates: Add units to one decimal. A cost below MIN_COST units (at the noise of the
    measurement, or below it) is written as MIN_COST, as a node is never free."""
    if unit <= 0:
        return
    measured = {}
    for label, ns, _ in rows:
        node, _, octave = label.partition(" per octave")
        base, per_octave = measured.get(node, (None, 0.0))
        units = max(round(ns / unit, 1), MIN_COST)
        measured[node] = (base, units) if label != node else (units, per_octave)
    print("\n# kNodeCosts rows from this run (compiler/cut.cpp):")
    for node, (base, per_octave) in measured.items():
        if node not in estimates:
            continue  # Add and Mul: the unit, at the default cost 1
        row = f'{{"{node}", {base:g}' + (f", {per_octave:g}}}," if per_octave else "},")
        print("    " + row)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    write = sub.add_parser("write", help="write the timing graphs and plan.json")
    write.add_argument("--memograph", required=True, help="the memograph binary")
    write.add_argument("--out", required=True, help="folder for the graphs")
    write.add_argument(
        "--copies",
        type=int,
        default=16,
        help="evaluations a pixel of a node estimated at 8 units or more; 4x that below 8, "
        "16x at 1 (16)",
    )
    write.add_argument(
        "--costs",
        default=str(Path(__file__).resolve().parents[2] / "compiler" / "cut.cpp"),
        help="the file holding kNodeCosts (compiler/cut.cpp)",
    )
    table = sub.add_parser("table", help="print the costs from `bake --time` output")
    table.add_argument("--plan", required=True, help="plan.json written by `write`")
    table.add_argument("--times", required=True, help="the output of `memograph bake --time`")
    args = parser.parse_args()
    if args.command == "write":
        if args.copies < 1:
            parser.error("--copies must be at least 1")
        write_graphs(args)
    else:
        print_table(args)


if __name__ == "__main__":
    main()

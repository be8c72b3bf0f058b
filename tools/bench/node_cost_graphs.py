#!/usr/bin/env python3
"""Graphs that time each node of compiler/cut.cpp's cost table, their table, and the
calibration of the cost table from a committed table.

tools/bench/node_costs_device.sh drives the first two (docs/design/memoization.md,
"Measuring the node costs"):

  node_cost_graphs.py write --memograph M --out DIR [--work W]
      writes DIR/<Node>.mgraph for every node with a nonzero estimate in kNodeCosts (an fBm
      node twice, at Detail 2 and 8, for its octave term), Add and Mul (the unit), and a
      baseline per link kind and copy count; DIR/plan.json says which graph times what.
  node_cost_graphs.py table --plan DIR/plan.json --times BAKE_OUTPUT
      reads `memograph bake --time`'s lines and prints, per node: ns per evaluation, its
      copies, its cost in Add units, kNodeCosts' estimate and measured / estimate.
  node_cost_graphs.py calibrate --timings TABLE [--costs compiler/cut.cpp] [--write]
      turns a committed table (the lines `table` printed) into kNodeCosts' values in Add
      units: prints the rows, and with --write sets them in the cost file; a node the table
      does not time keeps its estimate, and the step lists those.

A graph evaluates its node as a dependent chain of K copies a pixel: copy i's driven input
is a uv-varying base plus the previous copy's output times a gain (a scalar output is
splatted; a vector one, where the input is narrower or wider, is first reduced by a dot
product), so that the copies can be neither folded nor hoisted nor run side by side, and
the last value is the pixel's one stored float (`bake --time` stores one sum a pixel). The
dispatch is then bound by the chain's arithmetic, not by memory. A baseline graph makes the
same links with the node left out (a free swizzle in its place where the node changes the
value's width), so the node's time per evaluation is (graph - baseline) / K. K is the
power of two nearest W / estimate (W Add units of work a pixel), at least 8: hundreds of
copies for a one-operation node, tens for a texture.
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
WIDTH = {"float": 1, "float2": 2, "float3": 3, "float4": 4}
# The output types a copy's result may have.
OUTPUT_KINDS = ("float", "float2", "float3")
# The socket a copy drives, in order of preference; else the first float-ish input.
DRIVEN_SOCKETS = ("Vector", "UV", "Position", "Color", "Height", "Normal", "Fac", "In")
# (low, span) of a driven socket's values: where the node does its usual work (a Blackbody
# below 800 K or a Wavelength outside 380..780 nm would take a constant branch). The base
# covers the lower half of the span, the fed-back output at most about the upper half.
SOCKET_RANGES = {
    "Vector": (0.0, 16.0),
    "Position": (-1.0, 2.0),
    "Temperature": (1000.0, 11000.0),
    "Wavelength": (380.0, 400.0),
    "IOR": (1.1, 1.0),
    "Normal": (0.2, 0.6),
}
DEFAULT_RANGE = (0.0, 1.0)
# Constants for sockets whose defaults make the node an identity the driver would fold
# (Mul by 1, Add of 0, Gamma 1, a Mapping without a transform, a mix of equal colours).
NODE_SETTINGS = {
    "Add": {"B": "0.25"},
    "Mul": {"B": "0.75"},
    "Gamma": {"Gamma": "2.2"},
    "BrightnessContrast": {"Bright": "0.1", "Contrast": "0.2"},
    "Mapping": {
        "Location": "(0.1, 0.2, 0.3)",
        "Rotation": "(0.3, 0.2, 0.1)",
        "Scale": "(1.5, 1.2, 0.8)",
    },
    "VectorRotate": {"Angle": "0.5"},
    "MixColor": {"B": "(0.9, 0.6, 0.3)"},
}
# Per-component gains of the fed-back value (distinct, so that no two components share a
# product the driver could compute once).
GAINS = (0.5, 0.45, 0.4, 0.35)
TEXTURE = "cost_texture.pfm"
MIN_COST = 0.5  # Add units: the least cost a measured node is given
MIN_COPIES = 8
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


def vector_constant(values):
    return values[0] if len(values) == 1 else "(" + ", ".join(f"{x:.9g}" for x in values) + ")"


def base_value(graph, kind, value_range):
    """The chain's uv-varying base of `kind` in the lower half of `value_range`: u, v and
    two mixes of them, computed once a pixel."""
    low, span = value_range
    u, v = graph.u, graph.v
    spans = ((u, span / 2, low), (v, span / 2, low), (u, span / 4, low + span / 8),
             (v, span / 4, low + span / 4))
    components = [graph.scalar(*s) for s in spans[: WIDTH[kind]]]
    if kind == "float":
        return components[0]
    out = graph.link()
    names = ("X", "Y", "Z", "W")
    items = " ".join(f"{n}<{c}" for n, c in zip(names, components))
    graph.add(f"Combine{WIDTH[kind]} {items} Vector>{out}")
    return out


def link_kind(driven_kind, output_kind):
    """How a copy's output becomes the next copy's input: "same" (a multiply-add per
    component), "splat" (a scalar output, a multiply-add per input component) or "reduce"
    (a dot product of the output, then an add per input component)."""
    if output_kind == driven_kind:
        return "same"
    return "splat" if output_kind == "float" else "reduce"


def narrowing(driven_kind, output_kind):
    """A node whose vector output is narrower than its input: its baseline's stand-in
    would drop a component (whose add then dies, and whose derivative-free chain the
    compiler's type inference may carry with derivatives), so its baseline is the input
    kind's own chain and its time includes its link's dot product."""
    return output_kind != "float" and WIDTH[output_kind] < WIDTH[driven_kind]


def feed(graph, value, value_kind, base, driven_kind, value_range):
    """The next copy's input: `base` plus `value` (of `value_kind`) times a gain that keeps
    the sum in `value_range` for outputs of about [0, 1] (or inputs fed back as they are)."""
    _, span = value_range
    width = WIDTH[driven_kind]
    out = graph.link()
    kind = link_kind(driven_kind, value_kind)
    if kind == "same":
        gains = vector_constant(GAINS[:width])
        graph.add(f"MultiplyAdd A<{value} B={gains} C<{base} Out>{out}")
    elif kind == "splat":
        gains = vector_constant([g * span for g in GAINS[:width]])
        graph.add(f"MultiplyAdd A<{value} B={gains} C<{base} Out>{out}")
    else:
        width_out = WIDTH[value_kind]
        weights = vector_constant([g * span / width_out for g in GAINS[:width_out]])
        scalar = graph.link()
        graph.add(f"Dot A<{value} B={weights} Out>{scalar}")
        graph.add(f"Add A<{scalar} B<{base} Out>{out}")
    return out


def reduce(graph, value, kind):
    if kind == "float":
        return value
    scalar = graph.link()
    graph.add(f"Dot A<{value} B={vector_constant(GAINS[: WIDTH[kind]])} Out>{scalar}")
    return scalar


def store(graph, value, kind, derivatives):
    """The chain's last value as the pixel's roughness, the one output the graph writes.
    A chain that carries derivatives (its node's driven socket takes them) ends in a Bump
    of it, so that its baseline carries them too: once a graph, in both."""
    value = reduce(graph, value, kind)
    if derivatives:
        normal = graph.link()
        graph.add(f"Bump Height<{value} Strength=0.5 Distance=1 Normal>{normal}")
        value = reduce(graph, normal, "float3")
    graph.add(f"RoughnessOutput In<{value}")


def stand_in(graph, value, driven_kind, output_kind):
    """A baseline's free replacement of a node that widens the value: the input's
    components, repeated (a scalar is splatted where it is linked)."""
    if driven_kind == "float":
        return value  # a scalar linked to a vector socket is splatted
    names = ("X", "Y", "Z", "W")[: WIDTH[driven_kind]]
    parts = [graph.link() for _ in names]
    outs = " ".join(f"{n}>{p}" for n, p in zip(names, parts))
    graph.add(f"Separate{WIDTH[driven_kind]} Vector<{value} {outs}")
    width = WIDTH[output_kind]
    out = graph.link()
    names = ("X", "Y", "Z", "W")[:width]
    items = " ".join(f"{n}<{parts[i % len(parts)]}" for i, n in enumerate(names))
    graph.add(f"Combine{width} {items} Vector>{out}")
    return out


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
    """A value for a socket without a default that the copy does not drive: the texture's
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


# Nodes that compute their output from their input's derivatives: a chain through one
# would need second derivatives, which memograph does not generate.
FROM_DERIVATIVES = {"Bump", "NormalFromPosition"}


def chain_shape(inputs, outputs):
    """(driven socket, its kind, whether it takes derivatives, output socket, its kind) of a
    node's chain; None when the node has no float-ish input (it reads only MaterialInputs:
    its copies would be one) or no float, float2 or float3 output."""
    driven = driven_socket(inputs)
    result = next(((n, k) for n, k in outputs if k.removesuffix("_D") in OUTPUT_KINDS), None)
    if driven is None or result is None:
        return None
    driven_type = next(k for n, k, _ in inputs if n == driven)
    derivatives = driven_type.endswith("_D")
    return (driven, driven_type.removesuffix("_D"), derivatives, result[0],
            result[1].removesuffix("_D"))


def skip_reason(node, inputs, outputs):
    if not outputs:
        return "an output node: one a material"
    if node in FROM_DERIVATIVES:
        return "computes its output from its input's derivatives: a chain would need second ones"
    if driven_socket(inputs) is None:
        return "reads only MaterialInputs: its copies would be one"
    return "no float, float2 or float3 output"


def timed_node_graph(material, node, inputs, shape, copies, extra):
    """`copies` evaluations of `node` as a dependent chain through its driven socket."""
    driven, driven_kind, derivatives, output_name, output_kind = shape
    value_range = SOCKET_RANGES.get(driven, DEFAULT_RANGE)
    settings = {**NODE_SETTINGS.get(node, {}), **{k: str(v) for k, v in extra.items()}}
    fixed = []
    for name, kind, has_default in inputs:
        if name == driven or name in settings:
            continue
        if kind == "Table":
            fixed.append(f"{name}={ramp_table()}")
        elif kind == "TextureRef":
            fixed.insert(0, f'"{TEXTURE}"')
        elif not has_default:
            fixed.append(f"{name}={required_value(name, kind)}")
    fixed += [f"{name}={value}" for name, value in settings.items()]
    graph = GraphText(material)
    base = base_value(graph, driven_kind, value_range)
    value = base
    for _ in range(copies):
        out = graph.link()
        graph.add(f"{node} {driven}<{value} {' '.join(fixed)} {output_name}>{out}")
        value = feed(graph, out, output_kind, base, driven_kind, value_range)
    store(graph, value, driven_kind, derivatives)
    return graph.text()


def baseline_graph(material, copies, driven_kind, output_kind, derivatives):
    """The timed graphs' chain of `copies` links without the node: a "same" or "splat" link
    feeds the input back as it is (a splat of a scalar costs nothing, so its adds are a
    same link's); a "reduce" link reduces a free stand-in of the node's output."""
    graph = GraphText(material)
    base = base_value(graph, driven_kind, DEFAULT_RANGE)
    value = base
    for _ in range(copies):
        if link_kind(driven_kind, output_kind) == "reduce":
            out = stand_in(graph, value, driven_kind, output_kind)
            value = feed(graph, out, output_kind, base, driven_kind, DEFAULT_RANGE)
        else:
            value = feed(graph, value, driven_kind, base, driven_kind, DEFAULT_RANGE)
    store(graph, value, driven_kind, derivatives)
    return graph.text()


def baseline_key(driven_kind, output_kind, derivatives):
    """The baseline a chain needs: its driven kind, its output kind where the link is a
    reduce (a same or splat link costs one multiply-add per input component), and whether
    it carries derivatives."""
    if link_kind(driven_kind, output_kind) == "reduce" and not narrowing(driven_kind, output_kind):
        return driven_kind, output_kind, derivatives
    return driven_kind, driven_kind, derivatives


def baseline_name(driven_kind, output_kind, derivatives, copies):
    kinds = driven_kind if driven_kind == output_kind else f"{driven_kind}_to_{output_kind}"
    return f"baseline_{kinds}{'_D' if derivatives else ''}_{copies}"


def estimate_units(base, per_octave, detail):
    return base + (per_octave * octaves(detail) if detail is not None else 0.0)


def chain_copies(estimate, work):
    """The power of two nearest `work` / `estimate`, from MIN_COPIES (or `work`, if less) to
    `work`: about `work` Add units a pixel, so that every dispatch is long against the
    timer's resolution and the chain's links are a small part of a costly node's time."""
    ideal = work / max(estimate, 1.0)
    copies = 2 ** round(math.log2(ideal)) if ideal >= 1 else 1
    return max(min(MIN_COPIES, work), min(copies, work))


def write_graphs(args):
    costs = parse_cost_table(args.costs)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    write_texture(out / TEXTURE)
    plan = {"work": args.work, "graphs": {}, "skipped": {}, "estimates": costs}
    measured = ["Add", "Mul"] + sorted(n for n, (b, p) in costs.items() if b > 0 or p > 0)
    signatures = node_signatures(args.memograph, measured)
    baselines = set()
    for node in measured:
        inputs, outputs = signatures[node]
        input_names = {name for name, _, _ in inputs}
        shape = chain_shape(inputs, outputs)
        if shape is None or node in FROM_DERIVATIVES:
            plan["skipped"][node] = skip_reason(node, inputs, outputs)
            continue
        base, per_octave = costs.get(node, (1.0, 0.0))
        variants = [({}, None)]
        if per_octave > 0 and "Detail" in input_names:
            # Wave adds its fBm only where Distortion is nonzero.
            distortion = {"Distortion": 1} if node == "WaveTexture" else {}
            variants = [({"Detail": d, **distortion}, d) for d in DETAILS]
        # An fBm node's Details share one chain length (the longest Detail's), so that their
        # difference is the octaves' alone: chains of different lengths compile to code of
        # different shapes, whose cost per copy differs by more than an octave.
        longest = max((d for _, d in variants if d is not None), default=None)
        copies = chain_copies(estimate_units(base, per_octave, longest), args.work)
        for extra, detail in variants:
            material = node if detail is None else f"{node}_detail{detail}"
            (out / f"{material}.mgraph").write_text(
                timed_node_graph(material, node, inputs, shape, copies, extra)
            )
            key = baseline_key(shape[1], shape[4], shape[2])
            baselines.add((*key, copies))
            plan["graphs"][material] = {
                "node": node,
                "driven": shape[1] + ("_D" if shape[2] else ""),
                "output": shape[4],
                "detail": detail,
                "copies": copies,
                "baseline": baseline_name(*key, copies),
            }
            if narrowing(shape[1], shape[4]):
                plan["graphs"][material]["note"] = "includes its link's dot product"
    for driven_kind, output_kind, derivatives, copies in sorted(baselines):
        material = baseline_name(driven_kind, output_kind, derivatives, copies)
        (out / f"{material}.mgraph").write_text(
            baseline_graph(material, copies, driven_kind, output_kind, derivatives)
        )
        plan["graphs"][material] = {
            "node": None,
            "driven": driven_kind + ("_D" if derivatives else ""),
            "output": output_kind,
            "copies": copies,
        }
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


def measured_rows(plan, times):
    """[(label, ns per evaluation, copies, estimate)] of every node the times cover; an fBm
    node gives a base row (its Detail-2 time less its octaves) and a "per octave" row (the
    difference between its two Details over their octaves)."""

    def per_evaluation(material):
        graph = plan["graphs"][material]
        return (times[material] - times[graph["baseline"]]) / graph["copies"]

    by_node = {}
    for material, graph in plan["graphs"].items():
        if graph["node"] and material in times and graph["baseline"] in times:
            by_node.setdefault(graph["node"], {})[graph.get("detail")] = (
                per_evaluation(material),
                graph["copies"],
            )
    rows = []
    for node, measured in sorted(by_node.items()):
        base, per_octave = plan["estimates"].get(node, (1.0, 0.0))
        if None in measured:
            rows.append((node, *measured[None], base))
            continue
        low, high = DETAILS
        if low not in measured or high not in measured:
            continue
        octave_ns = (measured[high][0] - measured[low][0]) / (octaves(high) - octaves(low))
        rows.append((node, measured[low][0] - octave_ns * octaves(low), measured[low][1], base))
        rows.append((f"{node} per octave", octave_ns, measured[high][1], per_octave))
    return rows


def print_table(args):
    plan = json.loads(Path(args.plan).read_text())
    times = read_times(args.times)
    missing = [m for m in plan["graphs"] if m not in times]
    if missing:
        print(f"node_cost_graphs.py: no time for {', '.join(missing)}", file=sys.stderr)
    if "Add" not in times or plan["graphs"]["Add"]["baseline"] not in times:
        sys.exit("node_cost_graphs.py: Add and its baseline must be timed")
    rows = measured_rows(plan, times)
    unit = next(ns for label, ns, _, _ in rows if label == "Add")
    print(
        f"# node costs: dependent chains of about {plan['work']} Add units a pixel, "
        f"(graph - baseline) / copies; 1 Add unit = {unit:.6f} ns per evaluation"
    )
    print(
        f"# {'node':32} {'ns/eval':>10} {'copies':>6} {'Add units':>10} {'estimate':>9} "
        f"{'ratio':>7}"
    )
    for label, ns, copies, estimate in rows:
        units = ns / unit if unit > 0 else float("nan")
        ratio = units / estimate if estimate > 0 else float("nan")
        print(f"{label:34} {ns:10.6f} {copies:6d} {units:10.2f} {estimate:9.2f} {ratio:7.2f}")
    for node, why in sorted(plan["skipped"].items()):
        print(f"# not timed: {node}: {why}")


def read_timings(path):
    """A committed table (the lines `table` printed): {label: ns per evaluation}, where a
    label is a node or "<node> per octave"; lines starting with # are comments."""
    timings = {}
    for number, line in enumerate(Path(path).read_text().splitlines(), 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        match = re.match(r"^(\w+(?: per octave)?)\s+([-+0-9.eE]+|nan)(\s|$)", line)
        if not match:
            sys.exit(f"node_cost_graphs.py: {path}:{number}: not a table row: {line!r}")
        timings[match.group(1)] = float(match.group(2))
    return timings


def calibrated_costs(timings, estimates):
    """kNodeCosts' values from the timings, in Add units (the Add row's ns per evaluation)
    to one decimal and at least MIN_COST (a node at or below the noise of its measurement is
    never free): {node: (base, perOctave)} for the nodes the timings cover, and the sorted
    names of those they do not (which keep their estimates)."""
    unit = timings.get("Add")
    if unit is None or not unit > 0:
        sys.exit("node_cost_graphs.py: the timings need a positive Add row (the unit)")

    def units(ns):
        return max(round(ns / unit, 1), MIN_COST)

    costs = {}
    for node, (base, per_octave) in estimates.items():
        if base == 0 and per_octave == 0:
            continue  # a zero estimate (inputs, constants, outputs) is not timed
        if node not in timings or (per_octave > 0 and f"{node} per octave" not in timings):
            continue
        octave = units(timings[f"{node} per octave"]) if per_octave > 0 else 0.0
        costs[node] = (units(timings[node]), octave)
    kept = sorted(n for n, (b, p) in estimates.items() if (b > 0 or p > 0) and n not in costs)
    return costs, kept


def cost_row(node, base, per_octave):
    return f'{{"{node}", {base:g}' + (f", {per_octave:g}}}" if per_octave else "}")


def calibrate(args):
    estimates = parse_cost_table(args.costs)
    costs, kept = calibrated_costs(read_timings(args.timings), estimates)
    print(f"# kNodeCosts from {args.timings}, in Add units:")
    for node, (base, per_octave) in costs.items():
        print(f"    {cost_row(node, base, per_octave)},")
    print(f"# kept the estimate (not in the timings): {', '.join(kept) or 'none'}")
    if not args.write:
        return
    path = Path(args.costs)
    text = path.read_text()
    start = text.index("kNodeCosts[]")
    end = text.index("};", start)
    body = text[start:end]
    for node, (base, per_octave) in costs.items():
        body, count = re.subn(
            rf'\{{"{node}",\s*[0-9.eE+-]+(?:,\s*[0-9.eE+-]+)?\}}',
            cost_row(node, base, per_octave),
            body,
        )
        if count != 1:
            sys.exit(f"node_cost_graphs.py: {node} has {count} rows in {path}")
    path.write_text(text[:start] + body + text[end:])
    print(f"# wrote {len(costs)} rows to {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    default_costs = str(Path(__file__).resolve().parents[2] / "compiler" / "cut.cpp")
    write = sub.add_parser("write", help="write the timing graphs and plan.json")
    write.add_argument("--memograph", required=True, help="the memograph binary")
    write.add_argument("--out", required=True, help="folder for the graphs")
    write.add_argument(
        "--work",
        type=int,
        default=1024,
        help="Add units of estimated work a pixel: a node's copies are the power of two "
        f"nearest WORK / its estimate, at least {MIN_COPIES} (default 1024)",
    )
    write.add_argument(
        "--costs", default=default_costs, help="the file holding kNodeCosts (compiler/cut.cpp)"
    )
    table = sub.add_parser("table", help="print the costs from `bake --time` output")
    table.add_argument("--plan", required=True, help="plan.json written by `write`")
    table.add_argument("--times", required=True, help="the output of `memograph bake --time`")
    calibration = sub.add_parser(
        "calibrate", help="kNodeCosts' values in Add units from a committed table"
    )
    calibration.add_argument(
        "--timings", required=True, help="a table `table` printed (node, ns per evaluation, ...)"
    )
    calibration.add_argument(
        "--costs", default=default_costs, help="the file holding kNodeCosts (compiler/cut.cpp)"
    )
    calibration.add_argument(
        "--write", action="store_true", help="set the values in --costs (default: only print)"
    )
    args = parser.parse_args()
    if args.command == "write":
        if args.work < 1:
            parser.error("--work must be at least 1")
        write_graphs(args)
    elif args.command == "table":
        print_table(args)
    else:
        calibrate(args)


if __name__ == "__main__":
    main()

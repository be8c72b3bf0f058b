"""One per-node Cycles comparison case.

A case names one Blender shader node, its settings, its constant inputs and the inputs that
vary over the UV plane; the harness (../build_and_bake.py inside Blender, ../compare_nodes.py
outside) puts the chosen output on an Emission shader, bakes it with Cycles and with
`memograph bake`, and compares the two 64x64 images per channel.

This module is imported both by Blender's Python (3.10, no numpy) and by the system
python3: keep it standard-library only and never import bpy here. Family modules import it
as `from .case import Case`.
"""
from dataclasses import dataclass, field
import re
from typing import Any, Callable, Dict, Optional, Tuple

# Default tolerance by kind: the ceilings (max abs error per channel).
TOLERANCE = {'analytic': 1e-3, 'noise': 1e-2}

# What a `drive` entry may be (see Case.drive):
#   'uv3'                         (u, v, 0) from Texture Coordinate UV
#   ('uv3', scale, offset)        (u, v, 0) * scale + offset; scale/offset: number or 3-tuple
#                                 (Vector Math MULTIPLY_ADD after Texture Coordinate UV)
#   'u' | 'v'                     the scalar u or v (Separate XYZ of UV)
#   ('u'|'v', offset, scale)      offset + scale * u  (Separate XYZ + Math MULTIPLY_ADD)
#   'generated' | 'object' | 'normal' | 'uv'   a Texture Coordinate output as is
#   (one of those coordinate names, scale, offset)  scaled like 'uv3'
VECTOR_SOURCES = ('uv3', 'uv', 'generated', 'object', 'normal')
SCALAR_SOURCES = ('u', 'v')

_NAME = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')


@dataclass
class Case:
    name: str                      # unique over all families; a valid identifier, no '__'
    node: str                      # Blender node type, e.g. 'ShaderNodeTexNoise'
    props: Dict[str, Any] = field(default_factory=dict)    # node properties: enum names, bools, ...
    inputs: Dict[str, Any] = field(default_factory=dict)   # constant input values by identifier or name
    drive: Dict[str, Any] = field(default_factory=dict)    # inputs driven per pixel (see above)
    output: Optional[str] = None   # output identifier or name; None: the first enabled output
    tolerance: Optional[float] = None  # None: TOLERANCE[kind]
    kind: str = 'analytic'         # 'analytic' | 'noise' (noise, Voronoi, Musgrave)
    # Settings that are not simple props, run in Blender after props and inputs:
    # extra(node) or extra(node, node_tree) (e.g. ColorRamp stops, curve points).
    extra: Optional[Callable[..., None]] = None
    note: str = ''                 # free text shown in the table (e.g. why a tolerance differs)
    # The plane's normal (object = world space), None: its own +Z. For nodes that read the
    # normal (Box projection). Blender tilts the plane's mesh about the origin so that its
    # face normal is this (custom normals would not do: Blender stores them as 16-bit angles,
    # about 1e-4 off), and `memograph bake` gets it as --normal. The tilt moves the Object and
    # Generated coordinates, so such a case drives its inputs from UV.
    normal: Optional[Tuple[float, float, float]] = None
    family: str = ''               # filled in by discovery: the module's name

    @property
    def max_error(self) -> float:
        if self.tolerance is not None:
            return float(self.tolerance)
        return TOLERANCE[self.kind]

    def mode(self) -> str:
        """A short text for the table's mode column: the props, sorted."""
        if not self.props:
            return '-'
        return ', '.join('%s=%s' % (k, v) for k, v in sorted(self.props.items()))

    def validate(self) -> None:
        if not _NAME.match(self.name) or '__' in self.name:
            raise ValueError('case name %r must be an identifier without "__" (it becomes the '
                             'material name)' % self.name)
        if self.kind not in TOLERANCE:
            raise ValueError('case %s: kind must be one of %s' % (self.name, sorted(TOLERANCE)))
        if self.normal is not None and (
                not _num_or_vec(self.normal) or isinstance(self.normal, (int, float))
                or not any(self.normal)):
            raise ValueError('case %s: normal must be three numbers, not all zero: %r'
                             % (self.name, self.normal))
        for sock, spec in self.drive.items():
            if not drive_ok(spec):
                raise ValueError('case %s: bad drive for %r: %r' % (self.name, sock, spec))


def _num_or_vec(x) -> bool:
    if isinstance(x, (int, float)):
        return True
    return isinstance(x, (tuple, list)) and len(x) == 3 and all(
        isinstance(c, (int, float)) for c in x)


def drive_ok(spec) -> bool:
    if isinstance(spec, str):
        return spec in VECTOR_SOURCES or spec in SCALAR_SOURCES
    if isinstance(spec, tuple) and len(spec) == 3:
        src, a, b = spec
        if src in SCALAR_SOURCES:
            return isinstance(a, (int, float)) and isinstance(b, (int, float))
        if src in VECTOR_SOURCES:
            return _num_or_vec(a) and _num_or_vec(b)
    return False


def snapped_input(targets, step=0.0731, offset=(-32.0, -32.0, 5.0)):
    """extra() that drives inputs with floor(uv * 64 + offset) * step: the whole vector
    ('vec') or one component ('x', 'y', 'z') per target socket."""
    def extra(node, nt):
        tc = nt.nodes.new('ShaderNodeTexCoord')
        ma = nt.nodes.new('ShaderNodeVectorMath')
        ma.operation = 'MULTIPLY_ADD'
        ma.inputs[1].default_value = (64.0, 64.0, 64.0)
        ma.inputs[2].default_value = offset
        nt.links.new(tc.outputs['UV'], ma.inputs[0])
        fl = nt.nodes.new('ShaderNodeVectorMath')
        fl.operation = 'FLOOR'
        nt.links.new(ma.outputs[0], fl.inputs[0])
        mul = nt.nodes.new('ShaderNodeVectorMath')
        mul.operation = 'MULTIPLY'
        mul.inputs[1].default_value = (step, step, step)
        nt.links.new(fl.outputs[0], mul.inputs[0])
        sep = None
        for sock, comp in targets.items():
            if not node.inputs[sock].enabled:
                continue
            if comp == 'vec':
                nt.links.new(mul.outputs[0], node.inputs[sock])
            else:
                if sep is None:
                    sep = nt.nodes.new('ShaderNodeSeparateXYZ')
                    nt.links.new(mul.outputs[0], sep.inputs[0])
                nt.links.new(sep.outputs[comp.upper()], node.inputs[sock])
    return extra

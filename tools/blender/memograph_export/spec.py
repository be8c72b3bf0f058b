"""Declarative node specs: how one Blender shader node becomes one mgraph node.

A family module under ``specs/`` defines ``NODES = {'ShaderNodeX': NodeSpec(...)}``. The
loader (``load_specs``) imports every module of that package and merges the dicts; a node
type defined twice is an error, so two families can never silently disagree.

This module has no ``bpy`` import: specs and the loader are plain Python and are unit-tested
outside Blender (tests/blender/exporter_unit_test.py).
"""

import importlib
import pkgutil

# What an unlinked 'Vector' input means in Blender (Cycles' default texture coordinates).
IMPLICIT_VECTORS = (None, 'generated', 'uv', 'normal', 'position', 'object')


class SpecError(Exception):
    """A spec file is malformed (bad NodeSpec, duplicate node type, import failure)."""


class NodeSpec:
    """One Blender node type -> one mgraph node.

    mgraph:   the mgraph node name, or a callable(node) -> name (e.g. by data type).
    inputs:   Blender input socket identifier -> mgraph input socket. Unavailable
              (disabled) Blender sockets are skipped, so several identifiers may map to one
              mgraph socket (Mix's A_Float/A_Vector/A_Color -> A). Inputs not listed are not
              written (the mgraph node's @default applies); a linked input that is not
              listed gets a warning.
    outputs:  Blender output socket identifier -> mgraph output socket. A linked output
              that is not listed gets a warning and its consumers the socket's default.
    props:    Blender property name -> mgraph int/float socket. Enums are written as the
              0-based index of the item in the property's enum_items (Blender 3.4 order),
              booleans as 0/1, ints and floats as they are. A value may also be a pair
              (socket, callable(node) -> number) for anything computed.
    implicit_vector: what an unlinked 'Vector' input means in Blender: 'generated'
              (procedural textures), 'uv' (image texture), 'normal', 'position', 'object'
              or None (the socket's default_value is written).
    """

    __slots__ = ('mgraph', 'inputs', 'outputs', 'props', 'implicit_vector')

    def __init__(self, mgraph, inputs, outputs, props=None, implicit_vector=None):
        if not (isinstance(mgraph, str) or callable(mgraph)):
            raise SpecError('NodeSpec.mgraph must be a str or a callable(node) -> str')
        for what, table in (('inputs', inputs), ('outputs', outputs), ('props', props or {})):
            if not isinstance(table, dict):
                raise SpecError('NodeSpec.%s must be a dict' % what)
        for key, value in (props or {}).items():
            ok = isinstance(value, str) or (
                isinstance(value, tuple) and len(value) == 2 and isinstance(value[0], str)
                and callable(value[1]))
            if not ok:
                raise SpecError('NodeSpec.props[%r] must be a socket name or '
                                '(socket, callable(node))' % key)
        if implicit_vector not in IMPLICIT_VECTORS:
            raise SpecError('NodeSpec.implicit_vector must be one of %r' % (IMPLICIT_VECTORS,))
        self.mgraph = mgraph
        self.inputs = dict(inputs)
        self.outputs = dict(outputs)
        self.props = dict(props or {})
        self.implicit_vector = implicit_vector

    def mgraph_name(self, node):
        return self.mgraph(node) if callable(self.mgraph) else self.mgraph

    def __repr__(self):
        return 'NodeSpec(%r, inputs=%r, outputs=%r, props=%r, implicit_vector=%r)' % (
            self.mgraph, self.inputs, self.outputs, self.props, self.implicit_vector)


def load_specs(package=None):
    """Imports every module of the specs package and merges their NODES dicts.

    Returns {bl_idname: NodeSpec}. Raises SpecError on a duplicate node type, a module
    without a NODES dict, or a value that is not a NodeSpec.
    """
    if package is None:
        package = __package__ + '.specs' if __package__ else 'specs'
    pkg = importlib.import_module(package)
    merged = {}
    origin = {}
    for info in sorted(pkgutil.iter_modules(pkg.__path__), key=lambda i: i.name):
        if info.name.startswith('_'):
            continue
        module_name = package + '.' + info.name
        try:
            module = importlib.import_module(module_name)
        except Exception as exc:  # report which file broke, not a bare traceback
            raise SpecError('cannot import spec module %s: %s: %s' %
                            (module_name, type(exc).__name__, exc)) from exc
        nodes = getattr(module, 'NODES', None)
        if not isinstance(nodes, dict):
            raise SpecError('spec module %s has no NODES dict' % module_name)
        for bl_idname, spec in nodes.items():
            if not isinstance(spec, NodeSpec):
                raise SpecError('%s: NODES[%r] is not a NodeSpec' % (module_name, bl_idname))
            if bl_idname in merged:
                raise SpecError('node type %s is defined twice: in %s and in %s' %
                                (bl_idname, origin[bl_idname], module_name))
            merged[bl_idname] = spec
            origin[bl_idname] = module_name
    return merged

"""Blender-side graph walking: a material's node tree -> a flat graph of real nodes.

What the walk does, and whom it follows:
- Starts at the active Material Output (target ALL or CYCLES, is_active_output), as Cycles'
  sync does (intern/cycles/blender/shader.cpp: the output node the renderer uses).
- Node groups are inlined: a Group node's output continues at the matching input of the
  inner tree's active Group Output; a Group Input node's output continues at the matching
  input of the enclosing Group node (whose unlinked inputs carry the per-instance values).
- Reroutes are transparent.
- Muted nodes are bypassed through node.internal_links, as Blender/Cycles do (Cycles makes
  a conversion proxy per internal link); an output without an internal link is unlinked,
  so its consumers see their own socket value.
- Links that are invalid (link.is_valid False, e.g. shader -> float), muted
  (link.is_muted) or start/end at an unavailable (disabled) socket are ignored.
- Implicit conversions between socket types follow Cycles' ConvertNode
  (scene/shader_nodes.cpp): colour -> float is the luminance (written as RGBToBW),
  vector -> float the average of the components (VectorAverage, nodes/blender_conversions.inc),
  float -> vector/colour a splat, colour <-> vector unchanged, INT/BOOLEAN are floats.

The result is lazy: a FlatNode resolves an input when a writer asks for it, so only nodes
that reach the output are written. Sources are plain objects (Const, Out, Convert).
"""

FLOAT = 'float'
VECTOR = 'vector'
COLOR = 'color'
SHADER = 'shader'

_KINDS = {
    'VALUE': FLOAT,
    'INT': FLOAT,
    'BOOLEAN': FLOAT,
    'VECTOR': VECTOR,
    'RGBA': COLOR,
    'SHADER': SHADER,
}


def socket_kind(socket):
    """The memograph kind of a Blender socket (None for STRING/CUSTOM/OBJECT/...)."""
    return _KINDS.get(getattr(socket, 'type', None))


def type_default(kind):
    return (0.0, 0.0, 0.0) if kind in (VECTOR, COLOR) else 0.0


def _as_value(value, kind):
    """A Blender default_value as a float or a 3-tuple of floats for kind."""
    if value is None:
        return type_default(kind)
    try:
        seq = tuple(float(v) for v in value)
    except TypeError:
        seq = None
    if seq is None:
        value = float(value)
        return (value, value, value) if kind in (VECTOR, COLOR) else value
    if kind in (VECTOR, COLOR):
        seq = (seq + (0.0, 0.0, 0.0))[:3]
        return seq
    return seq[0] if seq else 0.0


class Const:
    """A literal: an unlinked input's default_value (or a group socket's value)."""

    def __init__(self, value, kind, unlinked=False):
        self.value = value
        self.kind = kind
        # True when the consuming socket itself had no link in its own tree: that is when
        # Blender substitutes implicit coordinates for a texture's Vector input.
        self.unlinked = unlinked

    def __repr__(self):
        return 'Const(%r, %s)' % (self.value, self.kind)


class Out:
    """An output socket of a real (written) node."""

    def __init__(self, node, socket, kind):
        self.node = node  # FlatNode
        self.socket = socket
        self.identifier = socket.identifier
        self.kind = kind

    def __repr__(self):
        return 'Out(%s.%s, %s)' % (self.node.label, self.identifier, self.kind)


class Convert:
    """An implicit conversion of source to kind: op is 'luminance', 'average', 'splat',
    'retag' (colour <-> vector, nothing to do) or 'to_shader' (a value into a shader
    socket, which Cycles treats as emission)."""

    def __init__(self, op, source, kind):
        self.op = op
        self.source = source
        self.kind = kind

    def __repr__(self):
        return 'Convert(%s, %r -> %s)' % (self.op, self.source, self.kind)


def convert(source, kind):
    """source converted to kind as Cycles' ConvertNode would (see module doc)."""
    if source is None or kind is None or source.kind == kind or source.kind is None:
        return source
    if isinstance(source, Const):
        # Fold the trivial cases; luminance/average stay nodes so the library computes them.
        if source.kind == FLOAT and kind in (VECTOR, COLOR):
            v = source.value
            return Const((v, v, v), kind, source.unlinked)
        if source.kind in (VECTOR, COLOR) and kind in (VECTOR, COLOR):
            return Const(source.value, kind, source.unlinked)
    if source.kind == SHADER:
        return None  # Blender marks shader -> value links invalid; treated as unlinked
    if kind == SHADER:
        return Convert('to_shader', source, SHADER)
    if kind == FLOAT:
        if source.kind == COLOR:
            return Convert('luminance', source, FLOAT)
        if source.kind == VECTOR:
            return Convert('average', source, FLOAT)
    if source.kind == FLOAT:
        return Convert('splat', source, kind)
    return Convert('retag', source, kind)


def _ptr(socket):
    return socket.as_pointer()


class TreeContext:
    """One (possibly nested) node tree: the group nodes leading to it and its links."""

    def __init__(self, tree, group_path=(), parent=None, group_node=None):
        self.tree = tree
        self.trees = (parent.trees if parent else ()) + (tree.as_pointer()
                                                          if hasattr(tree, 'as_pointer')
                                                          else id(tree),)
        self.group_path = group_path  # names of the group nodes, outermost first
        self.parent = parent
        self.group_node = group_node
        self._links = None

    def link_to(self, socket):
        """The link Blender evaluates into socket, or None."""
        if self._links is None:
            self._links = {}
            for link in self.tree.links:
                if not getattr(link, 'is_valid', True) or getattr(link, 'is_muted', False):
                    continue
                if not link.from_socket.enabled or not link.to_socket.enabled:
                    continue
                self._links[_ptr(link.to_socket)] = link
        return self._links.get(_ptr(socket))

    def child(self, group_node):
        return TreeContext(group_node.node_tree, self.group_path + (group_node.name,), self,
                           group_node)


class FlatNode:
    """A real node reached from the output, in the tree context it lives in."""

    def __init__(self, walker, ctx, node):
        self.walker = walker
        self.ctx = ctx
        self.node = node
        self.bl_idname = node.bl_idname
        self.key = ctx.group_path + (node.name,)
        self.label = '/'.join(self.key)
        self._inputs = {}

    def socket(self, identifier):
        """The enabled input socket with identifier, or None."""
        for s in self.node.inputs:
            if s.identifier == identifier:
                return s if s.enabled else None
        return None

    def enabled_inputs(self):
        return [s for s in self.node.inputs if s.enabled]

    def input(self, identifier):
        """The resolved Source of an enabled input (None when the socket is unavailable)."""
        if identifier not in self._inputs:
            socket = self.socket(identifier)
            self._inputs[identifier] = (None if socket is None else
                                        self.walker.resolve_input(self.ctx, socket))
        return self._inputs[identifier]

    def is_linked(self, identifier):
        src = self.input(identifier)
        return src is not None and not (isinstance(src, Const) and src.unlinked)


class Walker:
    """Resolves sockets of one material's tree. warn(node_label, message) reports."""

    def __init__(self, warn):
        self.warn = warn
        self._nodes = {}
        self._depth = 0

    def flat(self, ctx, node):
        key = ctx.group_path + (node.name,)
        if key not in self._nodes:
            self._nodes[key] = FlatNode(self, ctx, node)
        return self._nodes[key]

    def resolve_input(self, ctx, socket):
        kind = socket_kind(socket)
        link = ctx.link_to(socket)
        if link is None:
            return self._const(socket, kind, unlinked=True)
        src = self.resolve_output(ctx, link.from_node, link.from_socket)
        if src is None:
            # The producer gives nothing (a muted node's output without internal link,
            # an empty group): Cycles drops that link, so the socket's own value applies.
            return self._const(socket, kind, unlinked=False)
        converted = convert(src, kind)
        if converted is None:
            return self._const(socket, kind, unlinked=False)
        if isinstance(converted, Const) and converted.unlinked:
            # A value that came through a link (muted node, group socket) is not "unlinked".
            converted = Const(converted.value, converted.kind, unlinked=False)
        return converted

    def _const(self, socket, kind, unlinked):
        if kind == SHADER or kind is None:  # shader, string, object... sockets: no value
            return Const(None, kind, unlinked)
        return Const(_as_value(getattr(socket, 'default_value', None), kind), kind, unlinked)

    def resolve_output(self, ctx, node, socket):
        self._depth += 1
        try:
            if self._depth > 512:
                raise ExportError('node tree too deep or recursive at %s' % node.name)
            return self._resolve_output(ctx, node, socket)
        finally:
            self._depth -= 1

    def _resolve_output(self, ctx, node, socket):
        kind = socket_kind(socket)
        idname = node.bl_idname
        if idname == 'NodeReroute':
            return self.resolve_input(ctx, node.inputs[0]) if node.inputs else None
        if idname == 'NodeFrame':
            return None
        if getattr(node, 'mute', False):
            for il in node.internal_links:
                if il.to_socket.identifier == socket.identifier and il.to_socket.is_output:
                    src = self.resolve_input(ctx, il.from_socket)
                    return convert(src, kind)
            return None
        if idname == 'NodeGroupInput':
            if ctx.group_node is None:
                self.warn('/'.join(ctx.group_path + (node.name,)),
                          'Group Input outside a group: its value 0 is used')
                return Const(type_default(kind), kind)
            outer = None
            for s in ctx.group_node.inputs:
                if s.identifier == socket.identifier:
                    outer = s
            if outer is None:
                return None
            return convert(self.resolve_input(ctx.parent, outer), kind)
        if idname == 'ShaderNodeGroup' or getattr(node, 'node_tree', None) is not None and \
                idname.endswith('Group'):
            inner_tree = node.node_tree
            label = '/'.join(ctx.group_path + (node.name,))
            if inner_tree is None:
                self.warn(label, 'group node without a node tree: its outputs are unlinked')
                return None
            inner_id = (inner_tree.as_pointer() if hasattr(inner_tree, 'as_pointer')
                        else id(inner_tree))
            if inner_id in ctx.trees or len(ctx.group_path) > 64:
                raise ExportError('recursive node group at %s' % label)
            outputs = [n for n in inner_tree.nodes if n.bl_idname == 'NodeGroupOutput']
            active = [n for n in outputs if getattr(n, 'is_active_output', False)]
            out_node = (active or outputs or [None])[0]
            if out_node is None:
                self.warn(label, 'group has no Group Output: its outputs are unlinked')
                return None
            inner_socket = None
            for s in out_node.inputs:
                if s.identifier == socket.identifier:
                    inner_socket = s
            if inner_socket is None:
                return None
            return convert(self.resolve_input(ctx.child(node), inner_socket), kind)
        return Out(self.flat(ctx, node), socket, kind)


class ExportError(Exception):
    """A material (or file) cannot be exported at all."""


def find_output_node(tree):
    """The Material Output Cycles uses: active, target ALL or CYCLES."""
    outputs = [n for n in tree.nodes if n.bl_idname == 'ShaderNodeOutputMaterial']
    for want_active in (True, False):
        for n in outputs:
            if getattr(n, 'target', 'ALL') not in ('ALL', 'CYCLES'):
                continue
            if want_active and not getattr(n, 'is_active_output', False):
                continue
            return n
    return None

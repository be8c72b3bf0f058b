"""The .mgraph text builder (docs/guide/graph-format.md).

Deterministic by construction: nodes are written in the order the writers emit them (a
post-order walk from the material output, following Blender's socket order) and links are
numbered in the order they are created, so the same .blend gives byte-identical files.
"""

import math
import re
import struct


class Link:
    __slots__ = ('id',)

    def __init__(self, link_id):
        self.id = link_id

    def __repr__(self):
        return 'Link(%d)' % self.id


class Literal:
    """A constant for an input socket: float, int, 3-tuple, string or a 1024-number table."""

    __slots__ = ('value', 'form')

    def __init__(self, value, form='auto'):
        self.value = value
        self.form = form  # 'auto', 'int', 'string', 'table'

    def __repr__(self):
        return 'Literal(%r)' % (self.value,)


FLT_MAX = 3.4028234663852886e38


def format_number(value):
    """A float32 value with enough digits to round-trip ('%.9g'), as an mgraph NUMBER."""
    value = float(value)
    if math.isnan(value):
        value = 0.0
    elif math.isinf(value):
        value = FLT_MAX if value > 0 else -FLT_MAX
    # Round to float32 first: Blender stores float32; '%.9g' of that round-trips.
    value = struct.unpack('f', struct.pack('f', value))[0] if abs(value) <= FLT_MAX else value
    text = '%.9g' % value
    if text == '-0':
        text = '0'
    # '%.9g' may give '1e+10' (fine) or 'inf' (handled above); mgraph NUMBER has no bare '.5'
    return text


def format_literal(lit):
    v = lit.value
    if lit.form == 'string':
        s = str(v)
        if '"' in s or '\n' in s:
            raise ValueError('string literal cannot hold quotes or newlines: %r' % s)
        return '"%s"' % s
    if lit.form == 'int':
        return '%d' % int(v)
    if lit.form == 'table':
        nums = [format_number(x) for x in v]
        if len(nums) != 1024:
            raise ValueError('table literal needs 1024 numbers, got %d' % len(nums))
        rows = []
        for i in range(0, 1024, 16):  # four RGBA entries per line
            rows.append(' '.join(nums[i:i + 16]))
        return '[' + '\n    '.join(rows) + ']'
    if isinstance(v, (tuple, list)):
        return '(' + ', '.join(format_number(x) for x in v) + ')'
    if isinstance(v, bool):
        return '1' if v else '0'
    if isinstance(v, int):
        return '%d' % v
    return format_number(v)


_IDENT = re.compile(r'[^A-Za-z0-9_]')


def sanitize_identifier(name):
    """A valid mgraph material name: letters, digits, '_'; no leading digit; no '__'."""
    s = _IDENT.sub('_', name)
    s = re.sub('_+', '_', s).strip('_')
    if not s:
        s = 'Material'
    if s[0].isdigit():
        s = 'M' + s
    return s


class GraphBuilder:
    def __init__(self):
        self._lines = []
        self._next_link = 0

    def new_link(self):
        link = Link(self._next_link)
        self._next_link += 1
        return link

    def add(self, node_type, inputs=(), outputs=(), comment=None):
        """inputs: [(socket, Link | Literal)], outputs: [(socket, Link)]."""
        items = [node_type]
        for socket, operand in inputs:
            if isinstance(operand, Link):
                items.append('%s<%d' % (socket, operand.id))
            else:
                items.append('%s=%s' % (socket, format_literal(operand)))
        for socket, link in outputs:
            items.append('%s>%d' % (socket, link.id))
        line = ' '.join(items) + ';'
        if comment:
            line += '  # ' + comment.replace('\n', ' ')
        self._lines.append(line)

    def comment(self, text):
        for part in text.splitlines():
            self._lines.append('# ' + part)

    def text(self):
        return '\n'.join(self._lines) + '\n'

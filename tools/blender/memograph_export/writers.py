"""Node writers: the one table that maps a Blender node type to the code that writes it.

A writer is write(mw, flat, used) -> {blender output identifier: Link}. `mw` is the
MaterialWriter (operands, warnings, the builder), `flat` the graph.FlatNode, `used` the
output identifiers consumers asked for. A node type without a row is reported (material,
node, what was used instead) and its outputs become the socket's default value.

Declarative rows come from specs/<family>.py (spec.NodeSpec, written by the family
owners); the rows below that a spec cannot express are custom writers: ColorRamp, the three
curve nodes, Mix/MixRGB, Image Texture. Shader nodes live in shaders.py.
"""

from . import graph
from .graph import Const, Convert, Out, FLOAT, VECTOR, COLOR, SHADER
from .mgraph import Link, Literal
from .spec import NodeSpec, SpecError, load_specs

RAMP_TABLE_SIZE = 256  # Cycles' RAMP_TABLE_SIZE (scene/shader_nodes.h)


# -- helpers used by every writer -------------------------------------------------------


def prop_value(node, prop):
    """A node property as a number: enum -> 0-based index in enum_items, bool -> 0/1."""
    rna = node.bl_rna.properties.get(prop) if hasattr(node, 'bl_rna') else None
    value = getattr(node, prop)
    if rna is not None and rna.type == 'ENUM':
        items = [item.identifier for item in rna.enum_items]
        return Literal(items.index(value), 'int')
    if isinstance(value, bool):
        return Literal(1 if value else 0, 'int')
    if isinstance(value, int):
        return Literal(value, 'int')
    return Literal(float(value))


def _outputs(mw, flat, used, mapping, _unused=None):
    """Allocates links for the used outputs that mapping carries; warns for the others."""
    result = {}
    pairs = []
    for socket in flat.node.outputs:
        ident = socket.identifier
        if ident not in used or not socket.enabled:
            continue
        target = mapping.get(ident)
        if target is None:
            continue  # mw.node_output warns when the consumer asks
        link = mw.builder.new_link()
        pairs.append((target, link))
        result[ident] = link
    return result, pairs


def spec_writer(spec):
    def write(mw, flat, used):
        node = flat.node
        inputs = []
        bound = {}
        for socket in flat.enabled_inputs():
            ident = socket.identifier
            target = spec.inputs.get(ident)
            if target is None:
                if flat.is_linked(ident):
                    mw.warn(flat, 'input %r is linked but the exporter does not carry it; '
                            'it is ignored' % socket.name)
                continue
            if target in bound:
                continue  # two available sockets for one mgraph socket: the first one wins
            src = flat.input(ident)
            if (spec.implicit_vector and ident == 'Vector' and isinstance(src, Const)
                    and src.unlinked):
                operand = mw.implicit(spec.implicit_vector)
            else:
                operand = mw.operand(src)
            if operand is None:
                continue
            bound[target] = True
            inputs.append((target, operand))
        for prop, target in spec.props.items():
            if not isinstance(target, tuple) and not hasattr(node, prop):
                # A setting renamed or removed in this Blender version.
                mw.warn(flat, 'setting %r does not exist on this node (another Blender '
                        'version?): the memograph default of %s is used'
                        % (prop, target))
                continue
            if isinstance(target, tuple):
                target, fn = target
                value = fn(node)
                literal = value if isinstance(value, Literal) else (
                    Literal(value, 'int') if isinstance(value, (bool, int)) else Literal(value))
            else:
                literal = prop_value(node, prop)
            inputs.append((target, literal))
        result, pairs = _outputs(mw, flat, used, spec.outputs, None)
        mw.builder.add(spec.mgraph_name(node), inputs, pairs, comment=flat.label)
        return result

    write.spec = spec
    return write


# -- custom writers -----------------------------------------------------------------------


def _table_literal(entries):
    flat = []
    for entry in entries:
        e = tuple(float(x) for x in entry) + (0.0, 0.0, 0.0, 0.0)
        flat.extend(e[:4])
    return Literal(flat, 'table')


def write_color_ramp(mw, flat, used):
    """ShaderNodeValToRGB -> ColorRamp(Fac, Table, Interpolate) -> Color, Alpha.

    Table layout (as Cycles' ColorRampNode fills its ramp table, blender/shader.cpp
    colorramp_to_array): entry i (0..255) = color_ramp.evaluate(i / 255) as (r, g, b, a).
    Interpolate = 0 for CONSTANT, else 1 (Cycles then lerps entries i and i+1 at
    f = clamp(Fac, 0, 1) * 255, i = int(f), t = f - i). Every interpolation mode (EASE,
    CARDINAL, B_SPLINE) and every stop is carried through Blender's own evaluate().
    """
    ramp = flat.node.color_ramp
    n = RAMP_TABLE_SIZE
    entries = [tuple(ramp.evaluate(i / (n - 1))) for i in range(n)]
    inputs = [('Fac', mw.input_operand(flat, 'Fac')),
              ('Table', _table_literal(entries)),
              ('Interpolate', Literal(0 if ramp.interpolation == 'CONSTANT' else 1, 'int'))]
    result, pairs = _outputs(mw, flat, used, {'Color': 'Color', 'Alpha': 'Alpha'}, None)
    mw.builder.add('ColorRamp', inputs, pairs, comment=flat.label)
    return result


def curve_range(mapping, curves):
    """min/max x over the points of curves (Cycles' curvemapping_minmax)."""
    xs = [p.location[0] for c in curves for p in c.points]
    if not xs:
        return 0.0, 1.0
    lo, hi = min(xs), max(xs)
    if hi <= lo:
        hi = lo + 1.0  # a degenerate range would divide by zero in the shader
    return lo, hi


def curve_tables(mapping, kind):
    """The 256-entry table, MinX, MaxX and Extrapolate of an RGB/Vector/Float curve node.

    Follows Cycles (blender/shader.cpp + blender/util.h, curvemapping_color_to_array /
    curvemapping_float_to_array): x_i = MinX + i/255 * (MaxX - MinX), where MinX/MaxX are
    the smallest/largest point x over the curves used (RGB: R, G, B and C; vector: X, Y,
    Z; float: the one curve). Entry i:
      rgb:    (R(C(x_i)), G(C(x_i)), B(C(x_i)), 0)  -- the combined curve C applied first
      vector: (X(x_i), Y(x_i), Z(x_i), 0)
      float:  (F(x_i), F(x_i), F(x_i), 0)
    The shader looks each channel up at (value - MinX) / (MaxX - MinX) with linear
    interpolation; outside [0, 1] it extrapolates linearly from the two end entries when
    Extrapolate is 1 (mapping.extend == 'EXTRAPOLATED'), else clamps; the result is
    mixed with the input by Fac (Cycles svm_node_curves / svm_node_float_curve).
    """
    mapping.initialize()
    curves = list(mapping.curves)
    if kind == 'rgb':
        used = curves[:4]
    elif kind == 'vector':
        used = curves[:3]
    else:
        used = curves[:1]
    lo, hi = curve_range(mapping, used)
    n = RAMP_TABLE_SIZE
    entries = []
    for i in range(n):
        x = lo + (i / (n - 1)) * (hi - lo)
        if kind == 'rgb':
            c = mapping.evaluate(curves[3], x)
            entries.append((mapping.evaluate(curves[0], c), mapping.evaluate(curves[1], c),
                            mapping.evaluate(curves[2], c), 0.0))
        elif kind == 'vector':
            entries.append((mapping.evaluate(curves[0], x), mapping.evaluate(curves[1], x),
                            mapping.evaluate(curves[2], x), 0.0))
        else:
            v = mapping.evaluate(curves[0], x)
            entries.append((v, v, v, 0.0))
    extrapolate = 1 if getattr(mapping, 'extend', 'EXTRAPOLATED') == 'EXTRAPOLATED' else 0
    return entries, lo, hi, extrapolate


def _curve_writer(node_type, kind, fac, value, out):
    def write(mw, flat, used):
        entries, lo, hi, extrapolate = curve_tables(flat.node.mapping, kind)
        inputs = [(fac, mw.input_operand(flat, fac)),
                  (value, mw.input_operand(flat, value)),
                  ('Table', _table_literal(entries)),
                  ('MinX', Literal(lo)), ('MaxX', Literal(hi)),
                  ('Extrapolate', Literal(extrapolate, 'int'))]
        result, pairs = _outputs(mw, flat, used, {out: 'Out'}, None)
        mw.builder.add(node_type, inputs, pairs, comment=flat.label)
        return result

    return write


# mgraph outputs are all `Out` (nodes/converter.inc); `out` is the Blender output.
write_rgb_curves = _curve_writer('RGBCurves', 'rgb', 'Fac', 'Color', 'Color')
write_vector_curves = _curve_writer('VectorCurves', 'vector', 'Fac', 'Vector', 'Vector')
write_float_curve = _curve_writer('FloatCurve', 'float', 'Factor', 'Value', 'Value')

_MIX_NODES = {'FLOAT': ('MixFloat', 'Float'), 'VECTOR': ('MixVector', 'Vector'),
              'RGBA': ('MixColor', 'Color')}


def write_mix(mw, flat, used):
    """ShaderNodeMix -> MixFloat / MixVector / MixColor by data_type.

    Sockets: Factor, A, B -> Result; BlendType (blend_type index), ClampFactor,
    ClampResult (0/1) and, for vectors, NonUniform (factor_mode NON_UNIFORM = 1).
    """
    node = flat.node
    node_type, suffix = _MIX_NODES.get(node.data_type, ('MixColor', 'Color'))
    factor = 'Factor_Float'
    if node.data_type == 'VECTOR' and getattr(node, 'factor_mode', 'UNIFORM') == 'NON_UNIFORM':
        factor = 'Factor_Vector'
    inputs = [('Factor', mw.input_operand(flat, factor)),
              ('A', mw.input_operand(flat, 'A_' + suffix)),
              ('B', mw.input_operand(flat, 'B_' + suffix))]
    inputs.append(('BlendType', prop_value(node, 'blend_type')))
    inputs.append(('ClampFactor', Literal(int(bool(node.clamp_factor)), 'int')))
    inputs.append(('ClampResult', Literal(int(bool(node.clamp_result)), 'int')))
    if node.data_type == 'VECTOR':
        inputs.append(('NonUniform', Literal(1 if factor == 'Factor_Vector' else 0, 'int')))
    result, pairs = _outputs(mw, flat, used, {'Result_' + suffix: 'Result'}, None)
    mw.builder.add(node_type, inputs, pairs, comment=flat.label)
    return result


def write_mix_rgb(mw, flat, used):
    """Legacy ShaderNodeMixRGB -> MixColor (Fac -> Factor, Color1 -> A, Color2 -> B,
    use_clamp -> ClampResult, ClampFactor 1 as Cycles' MixNode clamps the legacy factor)."""
    node = flat.node
    if getattr(node, 'use_alpha', False):
        mw.warn(flat, 'Mix (Legacy) "Use Alpha" is not carried (Cycles ignores it too); '
                'the plain mix is used')
    inputs = [('Factor', mw.input_operand(flat, 'Fac')),
              ('A', mw.input_operand(flat, 'Color1')),
              ('B', mw.input_operand(flat, 'Color2')),
              ('BlendType', prop_value(node, 'blend_type')),
              ('ClampFactor', Literal(1, 'int')),
              ('ClampResult', Literal(int(bool(node.use_clamp)), 'int'))]
    result, pairs = _outputs(mw, flat, used, {'Color': 'Result'}, None)
    mw.builder.add('MixColor', inputs, pairs, comment=flat.label)
    return result


# Blender 3.4's Image Texture extensions as the Extension of ImageTextureClosest,
# ImageTextureBilinear and ImageTextureBicubic (Mirror came with Blender 3.5).
IMAGE_EXTENSIONS = {'REPEAT': 0, 'EXTEND': 1, 'CLIP': 2}


def image_premultiply(image, colorspace, used):
    """The Premultiply of the texel nodes (ImageTextureClosest/Bilinear/Bicubic/Box): how
    Cycles 3.4 associates the colour of an 8-bit image with its straight alpha. Its loaders
    premultiply byte images per texel, C * A / 255 rounded down ("byte images are always
    straight for Blender"), unless the colour space is data (Non-Color) or the alpha is
    channel-packed or ignored; its lookup divides the filtered colour back by the filtered
    alpha only when the Alpha output is linked (ImageTextureNode::compile,
    NODE_IMAGE_ALPHA_UNASSOCIATE). 0: not associated; 1: associated (Alpha unused); 2:
    associated, then divided (Alpha used). Float images (associated in float by Cycles) and
    images without an alpha channel get 0."""
    if colorspace == 'Non-Color' or getattr(image, 'alpha_mode', 'STRAIGHT') != 'STRAIGHT':
        return 0
    if getattr(image, 'is_float', False) or getattr(image, 'channels', 4) != 4:
        return 0
    return 2 if 'Alpha' in used else 1


def write_image(mw, flat, used):
    """ShaderNodeTexImage -> ImageTexture "textures/<name>.<ext>" UV -> Color, Alpha.

    The file is copied (or, when packed, unpacked) next to the graph by mw.assets. memograph
    reads image files as stored (PNG 8-bit as value/255, EXR as is) and filters linearly
    with mip-maps and repeat addressing, and its v points down the image, so: v is flipped
    (u, 1 - v); an image whose colour space is sRGB (8-bit or float) gets an
    SRGBToLinear after the sample (Cycles, too, filters an 8-bit sRGB image as stored and
    linearises each lookup: NODE_IMAGE_COMPRESS_AS_SRGB; measured by the image_*_srgb
    cases); Non-Color/Linear/Raw images are used as stored. Closest
    interpolation becomes ImageTextureClosest with the image's size in texels (the texel that
    holds the UV, unfiltered, as Cycles), with the node's extension. Linear with EXTEND or
    CLIP becomes ImageTextureBilinear (Cycles' bilinear filter from the four texels, no
    mip-maps); Linear with REPEAT stays the mip-mapped ImageTexture. Cubic and Smart become
    ImageTextureBicubic (Cycles' cubic B-spline over 4 x 4 texels, which Cycles also uses
    for Smart on the CPU). BOX projection becomes ImageTextureBox (Cycles'
    svm_node_tex_image_box: three axis-plane lookups blended by the normal and
    projection_blend, each filtered from the texels with the node's interpolation and
    extension, and, for an sRGB image, linearised per lookup inside the node, since Cycles
    converts before it blends the planes). SPHERE and TUBE map the vector to a UV first
    (ImageProjection: Cycles' map_to_sphere / map_to_tube), then look up as FLAT.
    """
    node = flat.node
    image = node.image
    if image is None:
        mw.warn(flat, 'Image Texture without an image: Cycles shows magenta (1, 0, 1), '
                'which is used')
        result = {}
        for socket in node.outputs:
            if socket.identifier in used:
                link = mw.builder.new_link()
                value = (1.0, 0.0, 1.0) if socket.identifier == 'Color' else 1.0
                node_type = 'Float3Constant' if socket.identifier == 'Color' else 'Float1Constant'
                mw.builder.add(node_type, [('Value', Literal(value))], [('Out', link)],
                               comment=flat.label + ' (no image)')
                result[socket.identifier] = link
        return result
    projection = node.projection
    if projection not in ('FLAT', 'BOX', 'SPHERE', 'TUBE'):  # Blender 3.4's four
        mw.warn(flat, 'projection %s is not supported: FLAT is used' % projection)
        projection = 'FLAT'
    # The texel-exact nodes: Closest, Cubic and Smart, and Linear with EXTEND or CLIP.
    extension = IMAGE_EXTENSIONS.get(node.extension)
    if extension is None:
        mw.warn(flat, 'extension %s is not supported: REPEAT is used' % node.extension)
        extension = IMAGE_EXTENSIONS['REPEAT']
    texel_node = None
    if node.interpolation == 'Closest':
        texel_node = 'ImageTextureClosest'
    elif node.interpolation in ('Cubic', 'Smart'):
        texel_node = 'ImageTextureBicubic'
    elif node.interpolation != 'Linear':
        mw.warn(flat, 'interpolation %s is not supported: memograph filters linearly'
                % node.interpolation)
    if texel_node is None and extension != IMAGE_EXTENSIONS['REPEAT']:
        texel_node = 'ImageTextureBilinear'
    texel_size = None
    if texel_node is not None or projection == 'BOX':
        width, height = (int(n) for n in image.size)
        if width > 0 and height > 0:
            texel_size = (width, height)
        elif projection == 'BOX':
            mw.warn(flat, 'projection BOX needs the image\'s size, which Blender does not know '
                    '(the image did not load): FLAT is used, filtered linearly (mip-mapped) '
                    'with REPEAT')
            projection = 'FLAT'
        else:
            mw.warn(flat, 'interpolation %s with extension %s needs the image\'s size, which '
                    'Blender does not know (the image did not load): memograph filters '
                    'linearly (mip-mapped) with REPEAT' % (node.interpolation, node.extension))
    path = mw.assets.image_path(image, lambda msg: mw.warn(flat, msg))
    if path is None:
        return {}
    src = flat.input('Vector')
    if isinstance(src, Const) and src.unlinked:
        uv = mw.implicit('uv2')
    else:
        uv = mw.operand(src)
    if projection in ('SPHERE', 'TUBE'):
        # Cycles maps the vector to a UV first (svm_node_tex_image), then looks up as Flat.
        projected = mw.builder.new_link()
        mw.builder.add('ImageProjection', [('Vector', uv),
                                           ('Projection', prop_value(node, 'projection'))],
                       [('UV', projected)],
                       comment='%s %s projection' % (flat.label, projection.lower()))
        uv = projected
    colorspace = getattr(image.colorspace_settings, 'name', 'sRGB')
    if colorspace not in ('sRGB', 'Non-Color', 'Linear', 'Raw', 'Linear Rec.709'):
        mw.warn(flat, 'colour space %s is not carried: the stored values are used' % colorspace)
    if projection == 'BOX':
        # Blender's coordinate goes in as is: the node projects it on the planes and flips
        # each plane's v itself.
        color_link = mw.builder.new_link()
        alpha_link = mw.builder.new_link()
        mw.builder.add('ImageTextureBox',
                       [('Image', Literal(path, 'string')), ('Vector', uv),
                        ('Blend', Literal(float(node.projection_blend))),
                        ('Width', Literal(texel_size[0], 'int')),
                        ('Height', Literal(texel_size[1], 'int')),
                        ('Interpolation', prop_value(node, 'interpolation')),
                        ('Extension', Literal(extension, 'int')),
                        ('Premultiply',
                         Literal(image_premultiply(image, colorspace, used), 'int')),
                        ('Srgb', Literal(1 if colorspace == 'sRGB' else 0, 'int'))],
                       [('Color', color_link), ('Alpha', alpha_link)],
                       comment=flat.label + ' box projection')
        return {'Color': color_link, 'Alpha': alpha_link}
    # Blender's v points up the image (row 0 at the bottom); memograph samples images with v
    # down (glTF's convention, top row first): sample at (u, 1 - v).
    flipped = mw.builder.new_link()
    mw.builder.add('MultiplyAdd', [('A', uv), ('B', Literal((1.0, -1.0, 1.0))),
                                   ('C', Literal((0.0, 1.0, 0.0)))], [('Out', flipped)],
                   comment=flat.label + ' v up -> v down')
    uv = flipped
    color_link = mw.builder.new_link()
    alpha_link = mw.builder.new_link()
    if texel_size is None:
        mw.builder.add('ImageTexture', [('Image', Literal(path, 'string')), ('UV', uv)],
                       [('Color', color_link), ('Alpha', alpha_link)], comment=flat.label)
    else:
        mw.builder.add(texel_node,
                       [('Image', Literal(path, 'string')), ('UV', uv),
                        ('Width', Literal(texel_size[0], 'int')),
                        ('Height', Literal(texel_size[1], 'int')),
                        ('Extension', Literal(extension, 'int')),
                        ('Premultiply',
                         Literal(image_premultiply(image, colorspace, used), 'int'))],
                       [('Color', color_link), ('Alpha', alpha_link)], comment=flat.label)
    if texel_size is None and image_premultiply(image, colorspace, used) == 1:
        # Cycles associates each texel with its alpha before filtering; the mip-mapped sample
        # can only be associated after it: the same at texel centres (but for Cycles' 8-bit
        # rounding down), apart between texels whose alpha differs.
        associated = mw.builder.new_link()
        mw.builder.add('MultiplyAdd', [('A', color_link), ('B', alpha_link),
                                       ('C', Literal((0.0, 0.0, 0.0)))], [('Out', associated)],
                       comment=flat.label + ' colour associated with alpha')
        color_link = associated
    result = {'Alpha': alpha_link}
    if colorspace == 'sRGB':  # Cycles linearises sRGB images, 8-bit or float
        linear = mw.builder.new_link()
        mw.builder.add('SRGBToLinear', [('Color', color_link)], [('Out', linear)],
                       comment=flat.label + ' colour space sRGB')
        result['Color'] = linear
    else:
        result['Color'] = color_link
    return result


def affine_rows(matrix):
    """The top three rows of a 4x4 matrix (mathutils.Matrix or nested sequences) as the
    float4 literals of AffineTransformPoint's Row0..Row2."""
    return [Literal(tuple(float(matrix[r][c]) for c in range(4))) for r in range(3)]


def write_tex_coord(mw, flat, used):
    """ShaderNodeTexCoord. Its outputs as the TEX_COORD spec writes them, except Object with
    an object set (an Empty placing a procedural texture): Cycles gives the hit's world
    position in that object's space, so it is PositionInput moved by the object's inverse
    world matrix (AffineTransformPoint), a constant of the export."""
    from .specs.vector import TEX_COORD
    node = flat.node
    target = getattr(node, 'object', None)
    if getattr(node, 'from_instancer', False):
        mw.warn(flat, '"From Instancer" is not carried: the coordinates of the shaded object '
                'itself are used')
    if target is None or 'Object' not in used:
        return spec_writer(TEX_COORD)(mw, flat, used)
    rest = set(used) - {'Object'}
    result = spec_writer(TEX_COORD)(mw, flat, rest) if rest else {}
    position = mw.builder.new_link()
    mw.builder.add('PositionInput', [], [('Out', position)],
                   comment='%s: world position' % flat.label)
    rows = affine_rows(target.matrix_world.inverted())
    link = mw.builder.new_link()
    mw.builder.add('AffineTransformPoint',
                   [('Vector', position), ('Row0', rows[0]), ('Row1', rows[1]),
                    ('Row2', rows[2])],
                   [('Out', link)], comment='%s: Object coordinates of %s'
                   % (flat.label, target.name))
    result['Object'] = link
    return result


def _tex_coord_spec():
    from .specs.vector import TEX_COORD
    return TEX_COORD


write_tex_coord.spec = _tex_coord_spec()


CUSTOM_WRITERS = {
    'ShaderNodeTexCoord': write_tex_coord,
    'ShaderNodeValToRGB': write_color_ramp,
    'ShaderNodeRGBCurve': write_rgb_curves,
    'ShaderNodeVectorCurve': write_vector_curves,
    'ShaderNodeFloatCurve': write_float_curve,
    'ShaderNodeMix': write_mix,
    'ShaderNodeMixRGB': write_mix_rgb,
    'ShaderNodeTexImage': write_image,
}


def build_table(specs=None):
    """{bl_idname: writer}: the spec rows plus the custom writers. A node type with both a
    spec and a custom writer is an error (the two would disagree silently)."""
    if specs is None:
        specs = load_specs()
    table = {}
    for bl_idname, spec in sorted(specs.items()):
        table[bl_idname] = spec_writer(spec)
    for bl_idname, writer in CUSTOM_WRITERS.items():
        if bl_idname in table:
            raise SpecError('node type %s has a spec and a custom writer; remove the spec '
                            '(the exporter writes it)' % bl_idname)
        table[bl_idname] = writer
    return table

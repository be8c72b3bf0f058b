"""Vector, Input and pattern-texture nodes against Cycles 3.4: Mapping (4 types), Vector
Rotate (5 types, inverted), Vector Transform (world <-> object), Normal Map (5 spaces,
strengths), Bump (strength, distance, invert, the valid-reflection clamp), Normal, Texture
Coordinate, UV Map, Geometry, Tangent, Object Info, Light Path (a bake's camera state),
Fresnel, Layer Weight, and the Checker, Gradient (7 types) and Brick textures.

What the bake can't reproduce, and so has no case here (docs/guide/nodes.md): Texture Coordinate
Camera and Window and Camera Data (a bake has no render camera); Vector Transform to or from
camera space; Geometry Parametric, Pointiness and Random Per Island; Object Info Random (the
bake helper's per-object value is not Cycles' name hash), Color, Alpha and indices;
Attribute and Color Attribute (the bake plane has no color attribute); the object-space
conversions of rotated or scaled objects (the bake plane's transform is the identity).
In the bake the direction towards the viewer equals the normal, so Fresnel and Layer Weight
are driven through their Normal input to see more than one angle.
"""
from .case import Case

# Coordinates over [-1, 1]^2 at z = 0, and a 3D one with z varying along u.
SIGNED = ('uv3', 2.0, -1.0)
TILTED = ('uv3', (2.0, 2.0, 0.0), (-1.0, -1.0, 0.5))
LOC = (0.1, -0.2, 0.3)
ROT = (0.3, -0.5, 0.7)
SCALE = (1.5, 0.5, 2.0)


def _direction(value):
    def setup(node):
        node.outputs['Normal'].default_value = value
    return setup


CASES = []

# --- Mapping ------------------------------------------------------------------------------
for _type in ('POINT', 'TEXTURE', 'VECTOR', 'NORMAL'):
    CASES.append(Case(name='mapping_%s' % _type.lower(), node='ShaderNodeMapping',
                      props={'vector_type': _type},
                      # Location is disabled (unused) for the Vector and Normal types.
                      inputs=dict({'Rotation': ROT, 'Scale': SCALE},
                                  **({'Location': LOC} if _type in ('POINT', 'TEXTURE') else {})),
                      drive={'Vector': TILTED}, output='Vector'))
CASES.append(Case(name='mapping_texture_zero_scale', node='ShaderNodeMapping',
                  props={'vector_type': 'TEXTURE'},
                  inputs={'Location': LOC, 'Rotation': ROT, 'Scale': (2.0, 0.0, 1.0)},
                  drive={'Vector': TILTED}, output='Vector',
                  note='a zero Scale component divides to 0'))

# --- Vector Rotate ------------------------------------------------------------------------
# Only the type's enabled sockets are set: Axis for Axis Angle, Angle for all but Euler,
# Rotation for Euler.
_ROTATE_INPUTS = {'AXIS_ANGLE': {'Axis': (1.0, 2.0, 0.5), 'Angle': 0.8},
                  'X_AXIS': {'Angle': 0.8}, 'Y_AXIS': {'Angle': -1.3}, 'Z_AXIS': {'Angle': 2.1},
                  'EULER_XYZ': {'Rotation': ROT}}
for _type in ('AXIS_ANGLE', 'X_AXIS', 'Y_AXIS', 'Z_AXIS', 'EULER_XYZ'):
    for _invert in (False, True):
        CASES.append(Case(
            name='vector_rotate_%s%s' % (_type.lower(), '_invert' if _invert else ''),
            node='ShaderNodeVectorRotate',
            props={'rotation_type': _type, 'invert': _invert},
            inputs=dict({'Center': (0.2, 0.1, -0.3)},
                        **_ROTATE_INPUTS[_type]),
            drive={'Vector': TILTED}, output='Vector'))
CASES.append(Case(name='vector_rotate_zero_axis', node='ShaderNodeVectorRotate',
                  props={'rotation_type': 'AXIS_ANGLE'},
                  inputs={'Center': (0.2, 0.1, -0.3), 'Axis': (0.0, 0.0, 0.0), 'Angle': 0.8},
                  drive={'Vector': TILTED}, output='Vector',
                  note='a zero axis returns the vector unchanged'))

# --- Vector Transform (the bake plane's object transform is the identity) ------------------
for _type in ('POINT', 'VECTOR', 'NORMAL'):
    for _from, _to in (('WORLD', 'OBJECT'), ('OBJECT', 'WORLD')):
        CASES.append(Case(
            name='vector_transform_%s_%s_%s' % (_type.lower(), _from.lower(), _to.lower()),
            node='ShaderNodeVectorTransform',
            props={'vector_type': _type, 'convert_from': _from, 'convert_to': _to},
            drive={'Vector': TILTED}, output='Vector'))

# --- Normal Map ---------------------------------------------------------------------------
_MAP_COLOR = ('uv3', (0.8, 0.8, 0.0), (0.1, 0.1, 0.75))
for _space in ('TANGENT', 'OBJECT', 'WORLD', 'BLENDER_OBJECT', 'BLENDER_WORLD'):
    CASES.append(Case(name='normal_map_%s' % _space.lower(), node='ShaderNodeNormalMap',
                      props={'space': _space}, drive={'Color': _MAP_COLOR}, output='Normal'))
for _strength in (0.0, 0.4, 2.5):
    CASES.append(Case(name='normal_map_tangent_strength_%s' % str(_strength).replace('.', '_'),
                      node='ShaderNodeNormalMap', props={'space': 'TANGENT'},
                      inputs={'Strength': _strength}, drive={'Color': _MAP_COLOR},
                      output='Normal'))
CASES.append(Case(name='normal_map_strength_driven', node='ShaderNodeNormalMap',
                  props={'space': 'WORLD'}, drive={'Color': _MAP_COLOR,
                                                   'Strength': ('u', -0.5, 3.0)},
                  output='Normal'))

# --- Bump (linear heights: Cycles' differences and memograph's derivatives agree) ---------
CASES += [
    Case(name='bump_u', node='ShaderNodeBump', inputs={'Distance': 0.1},
         drive={'Height': 'u'}, output='Normal'),
    Case(name='bump_v_invert', node='ShaderNodeBump', props={'invert': True},
         inputs={'Distance': 0.3}, drive={'Height': 'v'}, output='Normal'),
    Case(name='bump_strength', node='ShaderNodeBump', inputs={'Distance': 0.5, 'Strength': 0.4},
         drive={'Height': ('u', 0.0, 2.0)}, output='Normal'),
    Case(name='bump_strength_driven', node='ShaderNodeBump', inputs={'Distance': 0.5},
         drive={'Height': 'v', 'Strength': ('u', -0.5, 2.0)}, output='Normal'),
    Case(name='bump_steep', node='ShaderNodeBump', inputs={'Distance': 4.0},
         drive={'Height': 'u'}, output='Normal',
         note='tilted past 45 degrees: the valid-reflection clamp'),
    Case(name='bump_constant', node='ShaderNodeBump', inputs={'Height': 0.7}, output='Normal'),
]

# --- Normal -------------------------------------------------------------------------------
CASES += [
    Case(name='normal_dot', node='ShaderNodeNormal', drive={'Normal': TILTED}, output='Dot',
         extra=_direction((0.3, -0.4, 0.8))),
    Case(name='normal_normal', node='ShaderNodeNormal', output='Normal',
         extra=_direction((0.3, -0.4, 0.8))),
]

# --- Texture Coordinate, UV Map, Geometry, Tangent, Object Info ---------------------------
for _out in ('Generated', 'Normal', 'UV', 'Object', 'Reflection'):
    CASES.append(Case(name='tex_coord_%s' % _out.lower(), node='ShaderNodeTexCoord',
                      output=_out))


def _placed_empty(node, nt):
    """Texture Coordinate Object from an Empty that is moved, rotated about every axis and
    scaled unevenly: Cycles gives the world position in the Empty's space."""
    import bpy  # Blender only; the case modules stay importable by plain python3
    empty = bpy.data.objects.new('tex_coord_empty', None)
    bpy.context.scene.collection.objects.link(empty)
    empty.location = (0.7, -1.3, 0.4)
    empty.rotation_euler = (0.5, -0.3, 1.1)
    empty.scale = (0.5, 2.0, 1.5)
    bpy.context.view_layer.update()
    node.object = empty


CASES.append(Case(name='tex_coord_object_from_empty', node='ShaderNodeTexCoord',
                  output='Object', extra=_placed_empty))
# Object from the Empty next to another output of the same node (both written).
CASES.append(Case(name='tex_coord_object_from_empty_with_uv', node='ShaderNodeVectorMath',
                  props={'operation': 'ADD'},
                  extra=lambda node, nt: _empty_and_uv(node, nt), output='Vector'))


def _empty_and_uv(node, nt):
    coords = nt.nodes.new('ShaderNodeTexCoord')
    _placed_empty(coords, nt)
    nt.links.new(coords.outputs['Object'], node.inputs[0])
    nt.links.new(coords.outputs['UV'], node.inputs[1])


CASES.append(Case(name='uv_map', node='ShaderNodeUVMap', output='UV'))
# The radial tangents about Z turn fastest next to the plane's centre, where the bake's
# sampling offset (1.6e-5 in u, 3.1e-5 in v) turns them by up to 2.2e-3: the tolerance
# there is the offset's effect, not the node's (docs/guide/nodes.md).
_RADIAL_NOTE = 'bake sampling offset at the centre texels'
for _out in ('Position', 'Normal', 'Tangent', 'True Normal', 'Incoming', 'Backfacing'):
    CASES.append(Case(name='geometry_%s' % _out.lower().replace(' ', '_'),
                      node='ShaderNodeNewGeometry', output=_out,
                      tolerance=3e-3 if _out == 'Tangent' else None,
                      note=_RADIAL_NOTE if _out == 'Tangent' else ''))
for _axis in ('X', 'Y', 'Z'):
    CASES.append(Case(name='tangent_radial_%s' % _axis.lower(), node='ShaderNodeTangent',
                      props={'direction_type': 'RADIAL', 'axis': _axis}, output='Tangent',
                      tolerance=3e-3 if _axis == 'Z' else None,
                      note=_RADIAL_NOTE if _axis == 'Z' else
                      'tangent parallel to the normal: 0 (Cycles NaN, written as 0)'))
CASES.append(Case(name='tangent_uv_map', node='ShaderNodeTangent',
                  props={'direction_type': 'UV_MAP'}, output='Tangent'))
CASES.append(Case(name='object_info_location', node='ShaderNodeObjectInfo', output='Location'))
# A bake is Cycles' camera path at depth 0 whose hit lies at t = 1 (init_from_bake.h), and
# memograph's bake sets the same state; the path tracer's values are checked by the scene
# tests (light_path_camera, light_path_depth). Transparent Depth is not carried (warned, 0).
for _out in ('Is Camera Ray', 'Is Shadow Ray', 'Is Diffuse Ray', 'Is Glossy Ray',
             'Is Singular Ray', 'Is Reflection Ray', 'Is Transmission Ray', 'Ray Length',
             'Ray Depth', 'Diffuse Depth', 'Glossy Depth', 'Transmission Depth'):
    CASES.append(Case(name='light_path_%s' % _out.lower().replace(' ', '_'),
                      node='ShaderNodeLightPath', output=_out))

# --- Fresnel, Layer Weight ----------------------------------------------------------------
# A normal tilted over the plane (not normalized: Cycles takes it as given).
_NORMAL = ('uv3', (1.6, 1.6, 0.0), (-0.8, -0.8, 0.6))
CASES += [
    Case(name='fresnel_ior', node='ShaderNodeFresnel', drive={'IOR': ('u', 1.0, 2.0)},
         output='Fac'),
    Case(name='fresnel_normal', node='ShaderNodeFresnel', inputs={'IOR': 1.45},
         drive={'Normal': _NORMAL}, output='Fac'),
    Case(name='fresnel_ior_below_1', node='ShaderNodeFresnel',
         drive={'IOR': ('u', 0.2, 0.8), 'Normal': _NORMAL}, output='Fac',
         note='total internal reflection where eta < 1'),
    Case(name='layer_weight_fresnel', node='ShaderNodeLayerWeight',
         drive={'Blend': ('u', -0.1, 1.2), 'Normal': _NORMAL}, output='Fresnel'),
    Case(name='layer_weight_facing', node='ShaderNodeLayerWeight',
         drive={'Blend': ('u', -0.1, 1.2), 'Normal': _NORMAL}, output='Facing'),
    Case(name='layer_weight_facing_half', node='ShaderNodeLayerWeight', inputs={'Blend': 0.5},
         drive={'Normal': _NORMAL}, output='Facing'),
]

# --- Checker, Gradient, Brick -------------------------------------------------------------
CASES += [
    Case(name='checker_color', node='ShaderNodeTexChecker',
         inputs={'Color1': (0.9, 0.3, 0.1, 1.0), 'Color2': (0.1, 0.2, 0.7, 1.0)},
         drive={'Vector': 'uv3'}, output='Color'),
    Case(name='checker_fac_3d', node='ShaderNodeTexChecker', inputs={'Scale': 3.3},
         drive={'Vector': ('uv3', (2.0, 2.0, 1.5), (-1.0, -1.0, -0.7))}, output='Fac',
         note='negative cells and a z that changes cell'),
    Case(name='checker_generated', node='ShaderNodeTexChecker', inputs={'Scale': 4.0},
         drive={'Vector': 'generated'}, output='Fac'),
]
for _type in ('LINEAR', 'QUADRATIC', 'EASING', 'DIAGONAL', 'SPHERICAL', 'QUADRATIC_SPHERE',
              'RADIAL'):
    CASES.append(Case(name='gradient_%s' % _type.lower(), node='ShaderNodeTexGradient',
                      props={'gradient_type': _type},
                      drive={'Vector': ('uv3', (2.4, 2.4, 0.0), (-1.2, -1.1, 0.2))},
                      output='Fac'))
CASES.append(Case(name='gradient_color', node='ShaderNodeTexGradient',
                  props={'gradient_type': 'EASING'}, drive={'Vector': SIGNED}, output='Color'))

_BRICK_COLORS = {'Color1': (0.9, 0.5, 0.2, 1.0), 'Color2': (0.2, 0.4, 0.8, 1.0),
                 'Mortar': (0.05, 0.1, 0.02, 1.0)}
CASES += [
    Case(name='brick_default_fac', node='ShaderNodeTexBrick', drive={'Vector': 'uv3'},
         output='Fac'),
    Case(name='brick_color', node='ShaderNodeTexBrick', inputs=dict(_BRICK_COLORS),
         drive={'Vector': SIGNED}, output='Color', note='negative rows and bricks'),
    Case(name='brick_offset_squash', node='ShaderNodeTexBrick',
         props={'offset': 0.3, 'offset_frequency': 3, 'squash': 0.6, 'squash_frequency': 2},
         inputs=dict(_BRICK_COLORS, **{'Mortar Size': 0.05, 'Mortar Smooth': 0.0,
                                       'Bias': 0.2, 'Brick Width': 0.7, 'Row Height': 0.3}),
         drive={'Vector': SIGNED}, output='Color'),
    # A smooth mortar ramp: kept shallow (under 30 per unit of UV), because the bake's
    # sampling offset (3e-5 in v, tests/blender HARNESS notes) times a steep ramp is
    # otherwise more than the tolerance.
    Case(name='brick_smooth_mortar', node='ShaderNodeTexBrick',
         props={'offset': 0.25, 'offset_frequency': 2, 'squash': 1.5, 'squash_frequency': 3},
         inputs=dict(_BRICK_COLORS, **{'Scale': 1.0, 'Mortar Size': 0.05,
                                       'Mortar Smooth': 1.0, 'Brick Width': 0.3,
                                       'Row Height': 0.15}),
         drive={'Vector': ('uv3', 1.0, (-0.5, -0.5, 0.0))}, output='Color'),
    Case(name='brick_sharp_mortar', node='ShaderNodeTexBrick',
         inputs={'Mortar Size': 0.08, 'Mortar Smooth': 0.0, 'Bias': -0.3, 'Scale': 3.0},
         drive={'Vector': 'generated'}, output='Fac'),
    Case(name='brick_bias_tint', node='ShaderNodeTexBrick',
         inputs=dict(_BRICK_COLORS, Bias=0.4, Scale=7.0), drive={'Vector': 'uv3'},
         output='Color'),
]


# --- Bump over curved and discontinuous heights ---------------------------------------------
# Cycles differences the height over its own differentials: in a 64x64 bake of the size-2
# plane those are 1/64 long along the diagonals (1, -1, 0) and (1, 1, 0) (measured; Cycles'
# compact differential around the normal). memograph's Bump uses the height's derivatives:
# analytic ones agree with Cycles' forward differences to the change of slope over that step.
def _height_from(kind, **settings):
    def setup(node, nt):
        coords = nt.nodes.new('ShaderNodeTexCoord')
        tex = nt.nodes.new(kind)
        for key, value in settings.items():
            setattr(tex, key, value)
        nt.links.new(coords.outputs['Object'], tex.inputs['Vector'])
        nt.links.new(tex.outputs['Fac'], node.inputs['Height'])
    return setup


CASES += [
    Case(name='bump_gradient_quadratic', node='ShaderNodeBump', inputs={'Distance': 0.2},
         extra=_height_from('ShaderNodeTexGradient', gradient_type='QUADRATIC'),
         output='Normal', tolerance=3e-3,
         note='curved height (Gradient QUADRATIC of Object): Cycles forward difference '
              'over 1/64 vs the analytic slope, Distance * h\'\' * 0.0055'),
    # Finite-difference heights: Bump matches only with the bake's footprint equal to
    # Cycles' bake footprint (half a texel along the diagonals).
    Case(name='bump_over_noise', node='ShaderNodeBump', inputs={'Distance': 0.1},
         extra=_height_from('ShaderNodeTexNoise'), output='Normal', kind='noise',
         note='Noise Fac of Object as height: its _D forward-differences over the footprint'),
    Case(name='bump_over_brick', node='ShaderNodeBump', inputs={'Distance': 0.05},
         extra=_height_from('ShaderNodeTexBrick'), output='Normal',
         note='Brick Fac of Object as height: steps at the mortar edges'),
]


def _height_through(kind, component, **settings):
    """Height = one component of `kind` (Mapping, Vector Rotate) applied to Object
    coordinates: checks the node's derivative (_D) overload through Bump."""
    def setup(node, nt):
        coords = nt.nodes.new('ShaderNodeTexCoord')
        vec = nt.nodes.new(kind)
        for key, value in settings.items():
            if key.startswith('in_'):
                vec.inputs[key[3:]].default_value = value
            else:
                setattr(vec, key, value)
        split = nt.nodes.new('ShaderNodeSeparateXYZ')
        nt.links.new(coords.outputs['Object'], vec.inputs['Vector'])
        nt.links.new(vec.outputs['Vector'], split.inputs['Vector'])
        nt.links.new(split.outputs[component], node.inputs['Height'])
    return setup


CASES += [
    Case(name='bump_normal_input', node='ShaderNodeBump', inputs={'Distance': 0.4},
         drive={'Height': 'u', 'Normal': ('uv3', (0.4, 0.4, 0.0), (-0.2, -0.2, 1.0))},
         output='Normal', note='a linked, unnormalized Normal input'),
    Case(name='bump_through_mapping', node='ShaderNodeBump', inputs={'Distance': 0.3},
         extra=_height_through('ShaderNodeMapping', 'X', vector_type='POINT',
                               in_Rotation=(0.2, -0.4, 0.9), in_Scale=(1.5, 0.7, 1.0)),
         output='Normal', note='Mapping derivatives: height = Mapping(Object).x'),
    Case(name='bump_through_vector_rotate', node='ShaderNodeBump', inputs={'Distance': 0.3},
         extra=_height_through('ShaderNodeVectorRotate', 'Y', rotation_type='EULER_XYZ',
                               invert=True, in_Rotation=(0.5, 0.3, -1.1)),
         output='Normal', note='Vector Rotate derivatives: height = Rotate(Object).y'),
]

"""Specs for Blender's Vector menu nodes (Mapping, Vector Rotate, Vector Transform, Normal
Map, Bump, Normal), the surface-relevant Input menu nodes (Texture Coordinate, UV Map,
Geometry, Attribute, Color Attribute, Object Info, Light Path, Ambient Occlusion, Bevel, Fresnel,
Layer Weight, Value, RGB, Tangent) and the Checker, Gradient and Brick textures. The mgraph nodes live in
nodes/vector.inc, normal.inc, inputs.inc, blender_inputs.inc and pattern.inc; their
fidelity is documented in docs/guide/nodes.md.

Blender outputs named like one of the node's inputs ('Vector', 'Normal') are 'Out' or keep
the output's name while the input is renamed ('NormalIn'): an mgraph socket name is unique
per node. Outputs a memograph material cannot compute are left out of `outputs`, so the
exporter warns when they are linked:
  Texture Coordinate Camera and Window (need the render camera), Geometry Parametric,
  Pointiness and Random Per Island (need mesh data memograph does not keep), Object Info
  Color, Alpha, Object Index and Material Index (object settings). Camera Data has no spec
  (the exporter's unknown-node warning applies).
Settings the specs cannot check and the exporter should warn about (see docs/guide/nodes.md):
  Vector Transform to/from CAMERA (treated as world space), Attribute names other than the
  mesh's color attribute, Normal Map / Tangent / UV Map uv_map other than the active one.
"""
from ..spec import NodeSpec


def _tex_coord_node(node):
    # Only the UV output linked: UVMap reads nothing but the UV, which keeps a material that
    # uses it cacheable (thesis §4.2); TextureCoordinate also reads the normal and view.
    linked = [s.identifier for s in node.outputs if s.is_linked]
    return 'UVMap' if linked == ['UV'] else 'TextureCoordinate'


def _rgb(values):
    return tuple(float(v) for v in tuple(values)[:3])


def _ao_distance(node):
    # Cycles' svm_node_ao: Distance 0 with the socket unlinked takes the world's AO distance
    # (NODE_AO_GLOBAL_RADIUS: World > Light Paths > Fast GI > AO Distance); a linked socket
    # is not carried (warned), its own value stands in.
    socket = next(s for s in node.inputs if s.identifier == 'Distance')
    distance = float(socket.default_value)
    if distance == 0.0 and not getattr(socket, 'is_linked', False):
        try:
            import bpy
            world = bpy.context.scene.world
            if world is not None:
                distance = float(world.light_settings.distance)
        except (ImportError, AttributeError):
            pass
    return distance


# Texture Coordinate: the exporter's custom writer (writers.write_tex_coord) uses this spec
# for every output but Object with an object set, which it writes as that object's space.
TEX_COORD = NodeSpec(
    mgraph=_tex_coord_node,
    inputs={},
    outputs={'Generated': 'Generated', 'Normal': 'Normal', 'UV': 'UV', 'Object': 'Object',
             'Reflection': 'Reflection'})


NODES = {
    # --- Vector menu ---------------------------------------------------------------------
    'ShaderNodeMapping': NodeSpec(
        mgraph='Mapping',
        inputs={'Vector': 'Vector', 'Location': 'Location', 'Rotation': 'Rotation',
                'Scale': 'Scale'},
        outputs={'Vector': 'Out'},
        props={'vector_type': 'Type'}),
    'ShaderNodeVectorRotate': NodeSpec(
        mgraph='VectorRotate',
        inputs={'Vector': 'Vector', 'Center': 'Center', 'Axis': 'Axis', 'Angle': 'Angle',
                'Rotation': 'Rotation'},
        outputs={'Vector': 'Out'},
        props={'rotation_type': 'Type', 'invert': 'Invert'}),
    'ShaderNodeVectorTransform': NodeSpec(
        mgraph='VectorTransform',
        inputs={'Vector': 'Vector'},
        outputs={'Vector': 'Out'},
        props={'vector_type': 'Type', 'convert_from': 'ConvertFrom',
               'convert_to': 'ConvertTo'}),
    'ShaderNodeNormalMap': NodeSpec(
        mgraph='NormalMap',
        inputs={'Strength': 'Strength', 'Color': 'Color'},
        outputs={'Normal': 'Normal'},
        props={'space': 'Space'}),
    'ShaderNodeBump': NodeSpec(
        mgraph='Bump',
        inputs={'Strength': 'Strength', 'Distance': 'Distance', 'Height': 'Height',
                'Normal': 'NormalIn'},
        outputs={'Normal': 'Normal'},
        props={'invert': 'Invert'}),
    'ShaderNodeNormal': NodeSpec(
        mgraph='Normal',
        inputs={'Normal': 'NormalIn'},
        outputs={'Normal': 'Normal', 'Dot': 'Dot'},
        # Blender keeps the node's direction in its output socket's value.
        props={'direction': ('Direction',
                             lambda node: tuple(node.outputs['Normal'].default_value))}),

    # --- Input menu ----------------------------------------------------------------------
    'ShaderNodeUVMap': NodeSpec(
        mgraph='UVMap', inputs={}, outputs={'UV': 'UV'}),
    'ShaderNodeNewGeometry': NodeSpec(
        mgraph='Geometry',
        inputs={},
        outputs={'Position': 'Position', 'Normal': 'Normal', 'Tangent': 'Tangent',
                 'True Normal': 'TrueNormal', 'Incoming': 'Incoming',
                 'Backfacing': 'Backfacing'}),
    'ShaderNodeAttribute': NodeSpec(
        mgraph='Attribute',
        inputs={},
        outputs={'Color': 'Color', 'Vector': 'Vector', 'Fac': 'Fac', 'Alpha': 'Alpha'}),
    'ShaderNodeVertexColor': NodeSpec(
        mgraph='VertexColorInput', inputs={}, outputs={'Color': 'Out', 'Alpha': 'Alpha'}),
    'ShaderNodeObjectInfo': NodeSpec(
        mgraph='ObjectInfo', inputs={}, outputs={'Location': 'Location', 'Random': 'Random'}),
    # The path state the path tracer puts in MaterialInputs (docs/design/path-tracer.md,
    # "Light Path"). Transparent Depth is not carried: memograph's tracer has no transparent
    # bounces, so a linked one is warned and its consumers get the socket's default, 0.
    'ShaderNodeLightPath': NodeSpec(
        mgraph='LightPath',
        inputs={},
        outputs={'Is Camera Ray': 'IsCameraRay', 'Is Shadow Ray': 'IsShadowRay',
                 'Is Diffuse Ray': 'IsDiffuseRay', 'Is Glossy Ray': 'IsGlossyRay',
                 'Is Singular Ray': 'IsSingularRay', 'Is Reflection Ray': 'IsReflectionRay',
                 'Is Transmission Ray': 'IsTransmissionRay', 'Ray Length': 'RayLength',
                 'Ray Depth': 'RayDepth', 'Diffuse Depth': 'DiffuseDepth',
                 'Glossy Depth': 'GlossyDepth', 'Transmission Depth': 'TransmissionDepth'}),
    # The path tracer traces the AO rays from the hit before the graph runs
    # (docs/design/traced-inputs.md), so Distance and the settings must be constants: they
    # are written as such. A linked Distance or Normal gets the exporter's "linked but not
    # carried" warning (the rays leave about the interpolated normal; a linked Distance's
    # unlinked value is used).
    'ShaderNodeAmbientOcclusion': NodeSpec(
        mgraph='AmbientOcclusion',
        inputs={'Color': 'Color'},
        outputs={'Color': 'Out', 'AO': 'AO'},
        props={'samples': 'Samples', 'inside': 'Inside', 'only_local': 'OnlyLocal',
               'distance': ('Distance', lambda node: _ao_distance(node))}),
    # Bevel, traced like Ambient Occlusion: Radius and Samples written as constants; a
    # linked Radius or Normal is warned (not carried), the Radius's own value stands in.
    'ShaderNodeBevel': NodeSpec(
        mgraph='Bevel',
        inputs={},
        outputs={'Normal': 'Normal'},
        props={'samples': 'Samples',
               'radius': ('Radius', lambda node: float(
                   next(s for s in node.inputs if s.identifier == 'Radius').default_value))}),
    'ShaderNodeFresnel': NodeSpec(
        mgraph='Fresnel', inputs={'IOR': 'IOR', 'Normal': 'Normal'}, outputs={'Fac': 'Fac'}),
    'ShaderNodeLayerWeight': NodeSpec(
        mgraph='LayerWeight',
        inputs={'Blend': 'Blend', 'Normal': 'Normal'},
        outputs={'Fresnel': 'Fresnel', 'Facing': 'Facing'}),
    'ShaderNodeValue': NodeSpec(
        mgraph='Float1Constant',
        inputs={},
        outputs={'Value': 'Out'},
        props={'value': ('Value', lambda node: float(node.outputs['Value'].default_value))}),
    'ShaderNodeRGB': NodeSpec(
        mgraph='ColorConstant',
        inputs={},
        outputs={'Color': 'Out'},
        props={'color': ('Color', lambda node: _rgb(node.outputs['Color'].default_value))}),
    'ShaderNodeTangent': NodeSpec(
        mgraph='Tangent',
        inputs={},
        outputs={'Tangent': 'Tangent'},
        props={'direction_type': 'DirectionType', 'axis': 'Axis'}),

    # --- Texture menu: patterns ----------------------------------------------------------
    'ShaderNodeTexChecker': NodeSpec(
        mgraph='CheckerTexture',
        inputs={'Vector': 'Vector', 'Color1': 'Color1', 'Color2': 'Color2', 'Scale': 'Scale'},
        outputs={'Color': 'Color', 'Fac': 'Fac'},
        implicit_vector='generated'),
    'ShaderNodeTexGradient': NodeSpec(
        mgraph='GradientTexture',
        inputs={'Vector': 'Vector'},
        outputs={'Color': 'Color', 'Fac': 'Fac'},
        props={'gradient_type': 'Type'},
        implicit_vector='generated'),
    'ShaderNodeTexBrick': NodeSpec(
        mgraph='BrickTexture',
        inputs={'Vector': 'Vector', 'Color1': 'Color1', 'Color2': 'Color2', 'Mortar': 'Mortar',
                'Scale': 'Scale', 'Mortar Size': 'MortarSize', 'Mortar Smooth': 'MortarSmooth',
                'Bias': 'Bias', 'Brick Width': 'BrickWidth', 'Row Height': 'RowHeight'},
        outputs={'Color': 'Color', 'Fac': 'Fac'},
        props={'offset': 'Offset', 'offset_frequency': 'OffsetFrequency', 'squash': 'Squash',
               'squash_frequency': 'SquashFrequency'},
        implicit_vector='generated'),
}

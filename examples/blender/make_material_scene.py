"""The material-heavy Blender scene (issue 41, part 4): twelve procedural materials of the
kinds artists make, on a floor, a back wall and ten objects, lit by a sun, an area light
and a dim world, seen by a camera that moves along a keyframed path.

    blender -b --factory-startup --python examples/blender/make_material_scene.py -- \
        OUT.blend [--camera-path OUT.camera] [--frames N]

writes the .blend and, with --camera-path, the camera's animation sampled once per frame as a
memograph camera path (tools/cli `render --camera-path`; lines 'px py pz  tx ty tz  fov' in
memograph's y-up world). The glTF export carries one still camera, not its animation, so the
path is written here, from the same keyframes. Then (docs/guide/blender.md, "Example: a scene
where materials matter"):

    memograph import-blender OUT.blend --out DIR --scene
    memograph render DIR/scene.gltf --materials DIR --camera-path OUT.camera --size 64x36 ...

The materials are chosen so that shading, not tracing, dominates the frame: Noise and Musgrave
of detail 8-15 (the floor and the wall also under a 4D Noise grime pass), a 4D Voronoi, Wave,
Brick, ColorRamps, Bump, Fresnel and Layer Weight mixes, Generated and Object coordinates and
one UV image texture (packed into the .blend, so the file needs nothing beside it). Every node used is one the exporter supports
(docs/guide/blender-node-accuracy.md).
"""

import math
import os
import sys

import bpy
from mathutils import Vector

# 16:9 like the benchmark sizes; the glTF camera takes its aspect from this resolution.
RESOLUTION = (64, 36)
DEFAULT_FRAMES = 24


# --- node helpers -------------------------------------------------------------------------


def new_material(name):
    """An empty node tree with a Material Output; returns (material, tree, output node)."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    return m, nt, nt.nodes.new('ShaderNodeOutputMaterial')


def node(nt, kind, inputs=None, **props):
    """A node with its properties and unlinked input values set."""
    n = nt.nodes.new(kind)
    for k, v in props.items():
        setattr(n, k, v)
    for k, v in (inputs or {}).items():
        n.inputs[k].default_value = v
    return n


def link(nt, out_socket, in_socket):
    nt.links.new(out_socket, in_socket)


def ramp(nt, fac_socket, stops, interpolation='LINEAR'):
    """A ColorRamp fed by fac_socket; stops is [(position, (r, g, b)), ...]."""
    r = nt.nodes.new('ShaderNodeValToRGB')
    r.color_ramp.interpolation = interpolation
    elements = r.color_ramp.elements
    # A new ramp has two stops: move them, then add the rest.
    for i, (pos, rgb) in enumerate(stops):
        e = elements[i] if i < 2 else elements.new(pos)
        e.position = pos
        e.color = (*rgb, 1.0)
    link(nt, fac_socket, r.inputs['Fac'])
    return r


def coords(nt, kind):
    """Texture Coordinate's output ('Generated', 'Object' or 'UV')."""
    return node(nt, 'ShaderNodeTexCoord').outputs[kind]


def bump(nt, height_socket, strength, distance=0.1):
    b = node(nt, 'ShaderNodeBump', {'Strength': strength, 'Distance': distance})
    link(nt, height_socket, b.inputs['Height'])
    return b


def grime(nt, vector_socket, color_socket, w):
    """The weathering pass artists lay over large surfaces: a 4D Noise (detail 15; W picks
    the pattern) ramped into a mask that darkens color_socket towards a brown grime.
    Returns the grimed colour socket."""
    n = node(nt, 'ShaderNodeTexNoise', {'Scale': 1.5, 'Detail': 15.0, 'Roughness': 0.6,
                                        'W': w}, noise_dimensions='4D')
    link(nt, vector_socket, n.inputs['Vector'])
    mask = ramp(nt, n.outputs['Fac'], [(0.45, (0.0, 0.0, 0.0)), (0.75, (1.0, 1.0, 1.0))])
    mix = node(nt, 'ShaderNodeMixRGB', {'Color2': (0.23, 0.18, 0.13, 1)}, blend_type='MULTIPLY')
    link(nt, mask.outputs['Color'], mix.inputs['Fac'])
    link(nt, color_socket, mix.inputs['Color1'])
    return mix.outputs['Color']


# --- the materials ------------------------------------------------------------------------
# Each returns a bpy material. Detail counts are high on purpose: a Noise of detail 15 is
# sixteen octaves, the per-hit cost the cache is meant to take away.


def marble():
    """Noise (detail 15, Generated) through an eased ColorRamp: a white-grey marble."""
    m, nt, out = new_material('Marble')
    n = node(nt, 'ShaderNodeTexNoise', {'Scale': 3.0, 'Detail': 15.0, 'Roughness': 0.6,
                                        'Distortion': 1.5})
    link(nt, coords(nt, 'Generated'), n.inputs['Vector'])
    r = ramp(nt, n.outputs['Fac'], [(0.35, (0.9, 0.88, 0.85)), (0.5, (0.3, 0.3, 0.32)),
                                     (0.65, (0.95, 0.93, 0.9))], 'EASE')
    p = node(nt, 'ShaderNodeBsdfPrincipled', {'Roughness': 0.15})
    link(nt, r.outputs['Color'], p.inputs['Base Color'])
    link(nt, p.outputs[0], out.inputs['Surface'])
    return m


def ridged_rock():
    """Ridged Musgrave (detail 12, Object) for colour and Bump: weathered stone."""
    m, nt, out = new_material('RidgedRock')
    mg = node(nt, 'ShaderNodeTexMusgrave', {'Scale': 4.0, 'Detail': 12.0, 'Dimension': 1.2,
                                            'Lacunarity': 2.1, 'Offset': 1.0, 'Gain': 2.0},
              musgrave_type='RIDGED_MULTIFRACTAL', musgrave_dimensions='3D')
    link(nt, coords(nt, 'Object'), mg.inputs['Vector'])
    r = ramp(nt, mg.outputs['Fac'], [(0.2, (0.18, 0.16, 0.14)), (0.9, (0.62, 0.58, 0.5))])
    b = bump(nt, mg.outputs['Fac'], 0.4)
    p = node(nt, 'ShaderNodeBsdfPrincipled', {'Roughness': 0.8})
    link(nt, r.outputs['Color'], p.inputs['Base Color'])
    link(nt, b.outputs['Normal'], p.inputs['Normal'])
    link(nt, p.outputs[0], out.inputs['Surface'])
    return m


def cells_4d():
    """4D Voronoi (W animates the cells' phase) on Generated, F1 distance through a ramp."""
    m, nt, out = new_material('Cells4D')
    v = node(nt, 'ShaderNodeTexVoronoi', {'Scale': 7.0, 'W': 0.4, 'Randomness': 1.0},
             voronoi_dimensions='4D', feature='F1', distance='EUCLIDEAN')
    link(nt, coords(nt, 'Generated'), v.inputs['Vector'])
    r = ramp(nt, v.outputs['Distance'], [(0.0, (0.05, 0.25, 0.1)), (0.6, (0.55, 0.85, 0.3))])
    mix = node(nt, 'ShaderNodeMixRGB', {'Fac': 0.5}, blend_type='MULTIPLY')
    link(nt, r.outputs['Color'], mix.inputs['Color1'])
    link(nt, v.outputs['Color'], mix.inputs['Color2'])
    d = node(nt, 'ShaderNodeBsdfDiffuse')
    link(nt, mix.outputs['Color'], d.inputs['Color'])
    link(nt, d.outputs[0], out.inputs['Surface'])
    return m


def wood():
    """Wave rings (distortion, detail 8, Object) through a ramp: end-grain wood."""
    m, nt, out = new_material('Wood')
    w = node(nt, 'ShaderNodeTexWave', {'Scale': 2.5, 'Distortion': 6.0, 'Detail': 8.0,
                                       'Detail Scale': 1.5, 'Detail Roughness': 0.6},
             wave_type='RINGS', rings_direction='Z', wave_profile='SAW')
    link(nt, coords(nt, 'Object'), w.inputs['Vector'])
    r = ramp(nt, w.outputs['Fac'], [(0.1, (0.35, 0.17, 0.06)), (0.9, (0.7, 0.45, 0.22))])
    p = node(nt, 'ShaderNodeBsdfPrincipled', {'Roughness': 0.45})
    link(nt, r.outputs['Color'], p.inputs['Base Color'])
    link(nt, p.outputs[0], out.inputs['Surface'])
    return m


def bricks():
    """Brick (Generated) with its mortar factor bumped and a Noise (detail 8) dirt layer."""
    m, nt, out = new_material('Bricks')
    gen = coords(nt, 'Generated')
    b = node(nt, 'ShaderNodeTexBrick', {'Scale': 6.0, 'Mortar Size': 0.03,
                                        'Color1': (0.55, 0.2, 0.12, 1),
                                        'Color2': (0.4, 0.15, 0.1, 1),
                                        'Mortar': (0.7, 0.68, 0.62, 1)})
    link(nt, gen, b.inputs['Vector'])
    dirt = node(nt, 'ShaderNodeTexNoise', {'Scale': 8.0, 'Detail': 8.0})
    link(nt, gen, dirt.inputs['Vector'])
    mix = node(nt, 'ShaderNodeMixRGB', {'Fac': 0.35}, blend_type='MULTIPLY')
    link(nt, b.outputs['Color'], mix.inputs['Color1'])
    link(nt, dirt.outputs['Color'], mix.inputs['Color2'])
    # 1 - Fac: the mortar (Fac 1) becomes the low part of the height.
    inv = node(nt, 'ShaderNodeMath', {0: 1.0}, operation='SUBTRACT')
    link(nt, b.outputs['Fac'], inv.inputs[1])
    bm = bump(nt, inv.outputs['Value'], 0.6)
    p = node(nt, 'ShaderNodeBsdfPrincipled', {'Roughness': 0.9})
    link(nt, mix.outputs['Color'], p.inputs['Base Color'])
    link(nt, bm.outputs['Normal'], p.inputs['Normal'])
    link(nt, p.outputs[0], out.inputs['Surface'])
    return m


def car_paint():
    """Layer Weight (Facing) mixes two paint colours over a Noise (detail 10) flake."""
    m, nt, out = new_material('CarPaint')
    n = node(nt, 'ShaderNodeTexNoise', {'Scale': 40.0, 'Detail': 10.0})
    link(nt, coords(nt, 'Object'), n.inputs['Vector'])
    lw = node(nt, 'ShaderNodeLayerWeight', {'Blend': 0.4})
    mix = node(nt, 'ShaderNodeMixRGB', {'Color1': (0.5, 0.02, 0.05, 1),
                                        'Color2': (0.05, 0.02, 0.25, 1)})
    link(nt, lw.outputs['Facing'], mix.inputs['Fac'])
    flake = node(nt, 'ShaderNodeMixRGB', {'Fac': 0.15}, blend_type='OVERLAY')
    link(nt, mix.outputs['Color'], flake.inputs['Color1'])
    link(nt, n.outputs['Color'], flake.inputs['Color2'])
    p = node(nt, 'ShaderNodeBsdfPrincipled', {'Roughness': 0.25, 'Metallic': 0.6})
    link(nt, flake.outputs['Color'], p.inputs['Base Color'])
    link(nt, p.outputs[0], out.inputs['Surface'])
    return m


def glazed_ceramic():
    """Fresnel mixes a glossy glaze over a diffuse body coloured by Noise (detail 9)."""
    m, nt, out = new_material('GlazedCeramic')
    n = node(nt, 'ShaderNodeTexNoise', {'Scale': 5.0, 'Detail': 9.0, 'Roughness': 0.55})
    link(nt, coords(nt, 'Generated'), n.inputs['Vector'])
    r = ramp(nt, n.outputs['Fac'], [(0.4, (0.1, 0.35, 0.45)), (0.6, (0.75, 0.85, 0.8))])
    d = node(nt, 'ShaderNodeBsdfDiffuse')
    link(nt, r.outputs['Color'], d.inputs['Color'])
    g = node(nt, 'ShaderNodeBsdfGlossy', {'Roughness': 0.05})
    f = node(nt, 'ShaderNodeFresnel', {'IOR': 1.5})
    ms = node(nt, 'ShaderNodeMixShader')
    link(nt, f.outputs['Fac'], ms.inputs['Fac'])
    link(nt, d.outputs[0], ms.inputs[1])
    link(nt, g.outputs[0], ms.inputs[2])
    link(nt, ms.outputs[0], out.inputs['Surface'])
    return m


def rusted_metal():
    """fBm Musgrave (detail 14, Object) masks rust over brushed metal (Mix Shader)."""
    m, nt, out = new_material('RustedMetal')
    obj = coords(nt, 'Object')
    mg = node(nt, 'ShaderNodeTexMusgrave', {'Scale': 3.0, 'Detail': 14.0, 'Dimension': 0.5},
              musgrave_type='FBM', musgrave_dimensions='3D')
    link(nt, obj, mg.inputs['Vector'])
    mask = ramp(nt, mg.outputs['Fac'], [(0.45, (0.0, 0.0, 0.0)), (0.55, (1.0, 1.0, 1.0))])
    speck = node(nt, 'ShaderNodeTexNoise', {'Scale': 20.0, 'Detail': 8.0})
    link(nt, obj, speck.inputs['Vector'])
    rust_col = ramp(nt, speck.outputs['Fac'], [(0.3, (0.3, 0.08, 0.02)),
                                               (0.7, (0.6, 0.3, 0.08))])
    rust = node(nt, 'ShaderNodeBsdfDiffuse')
    link(nt, rust_col.outputs['Color'], rust.inputs['Color'])
    metal = node(nt, 'ShaderNodeBsdfPrincipled', {'Base Color': (0.8, 0.8, 0.82, 1),
                                                  'Metallic': 1.0, 'Roughness': 0.3})
    ms = node(nt, 'ShaderNodeMixShader')
    link(nt, mask.outputs['Color'], ms.inputs['Fac'])
    link(nt, metal.outputs[0], ms.inputs[1])
    link(nt, rust.outputs[0], ms.inputs[2])
    link(nt, ms.outputs[0], out.inputs['Surface'])
    return m


def label_image():
    """The one UV material: an Image Texture (a packed 32x32 sRGB image) on UVs."""
    m, nt, out = new_material('Label')
    img = bpy.data.images.new('label', 32, 32, alpha=False)
    # Stripes and a dot, so that a flipped or shifted lookup shows.
    px = []
    for y in range(32):
        for x in range(32):
            dot = (x - 20) ** 2 + (y - 12) ** 2 < 36
            stripe = (x // 4) % 2 == 0
            px += [0.9, 0.1, 0.1, 1.0] if dot else ([0.9, 0.85, 0.3, 1.0] if stripe
                                                    else [0.1, 0.2, 0.6, 1.0])
    img.pixels[:] = px
    img.pack()  # into the .blend (as PNG): the exporter unpacks it to textures/
    t = node(nt, 'ShaderNodeTexImage', interpolation='Linear')
    t.image = img
    link(nt, coords(nt, 'UV'), t.inputs['Vector'])
    p = node(nt, 'ShaderNodeBsdfPrincipled', {'Roughness': 0.5})
    link(nt, t.outputs['Color'], p.inputs['Base Color'])
    link(nt, p.outputs[0], out.inputs['Surface'])
    return m


def moss():
    """Noise (detail 15) distorted by a Voronoi, as Bump height and ramped colour."""
    m, nt, out = new_material('Moss')
    gen = coords(nt, 'Generated')
    v = node(nt, 'ShaderNodeTexVoronoi', {'Scale': 12.0}, voronoi_dimensions='3D')
    link(nt, gen, v.inputs['Vector'])
    n = node(nt, 'ShaderNodeTexNoise', {'Scale': 6.0, 'Detail': 15.0, 'Distortion': 0.5})
    offset = node(nt, 'ShaderNodeVectorMath', operation='ADD')
    link(nt, gen, offset.inputs[0])
    link(nt, v.outputs['Color'], offset.inputs[1])
    link(nt, offset.outputs['Vector'], n.inputs['Vector'])
    r = ramp(nt, n.outputs['Fac'], [(0.35, (0.08, 0.15, 0.03)), (0.7, (0.35, 0.5, 0.12))])
    b = bump(nt, n.outputs['Fac'], 0.5)
    d = node(nt, 'ShaderNodeBsdfDiffuse')
    link(nt, grime(nt, gen, r.outputs['Color'], 1.7), d.inputs['Color'])
    link(nt, b.outputs['Normal'], d.inputs['Normal'])
    link(nt, d.outputs[0], out.inputs['Surface'])
    return m


def terrazzo_floor():
    """Floor: Brick tiles multiplied by hybrid Musgrave (detail 15) and a Voronoi fleck, under
    grime."""
    m, nt, out = new_material('TerrazzoFloor')
    gen = coords(nt, 'Generated')
    b = node(nt, 'ShaderNodeTexBrick', {'Scale': 4.0, 'Mortar Size': 0.01,
                                        'Color1': (0.75, 0.72, 0.66, 1),
                                        'Color2': (0.6, 0.58, 0.55, 1),
                                        'Mortar': (0.15, 0.15, 0.15, 1)},
              offset=0.0)
    link(nt, gen, b.inputs['Vector'])
    mg = node(nt, 'ShaderNodeTexMusgrave', {'Scale': 10.0, 'Detail': 15.0, 'Offset': 0.8},
              musgrave_type='HYBRID_MULTIFRACTAL', musgrave_dimensions='3D')
    link(nt, gen, mg.inputs['Vector'])
    fleck = node(nt, 'ShaderNodeTexVoronoi', {'Scale': 40.0}, voronoi_dimensions='3D')
    link(nt, gen, fleck.inputs['Vector'])
    r = ramp(nt, mg.outputs['Fac'], [(0.0, (0.5, 0.5, 0.5)), (1.0, (1.0, 1.0, 1.0))])
    mix = node(nt, 'ShaderNodeMixRGB', {'Fac': 1.0}, blend_type='MULTIPLY')
    link(nt, b.outputs['Color'], mix.inputs['Color1'])
    link(nt, r.outputs['Color'], mix.inputs['Color2'])
    mix2 = node(nt, 'ShaderNodeMixRGB', {'Fac': 0.2}, blend_type='MIX')
    link(nt, mix.outputs['Color'], mix2.inputs['Color1'])
    link(nt, fleck.outputs['Color'], mix2.inputs['Color2'])
    # Worn terrazzo: a Noise (detail 15) varies the polish between 0.15 and 0.6.
    wear = node(nt, 'ShaderNodeTexNoise', {'Scale': 2.0, 'Detail': 15.0, 'Roughness': 0.55})
    link(nt, gen, wear.inputs['Vector'])
    rough = node(nt, 'ShaderNodeMapRange', {'To Min': 0.15, 'To Max': 0.6})
    link(nt, wear.outputs['Fac'], rough.inputs['Value'])
    p = node(nt, 'ShaderNodeBsdfPrincipled')
    link(nt, rough.outputs['Result'], p.inputs['Roughness'])
    link(nt, grime(nt, gen, mix2.outputs['Color'], 0.3), p.inputs['Base Color'])
    link(nt, p.outputs[0], out.inputs['Surface'])
    return m


def plaster_wall():
    """Back wall: Wave bands (detail 15) and hetero-terrain Musgrave (detail 15), ramped, with
    Bump, under grime."""
    m, nt, out = new_material('PlasterWall')
    gen = coords(nt, 'Generated')
    w = node(nt, 'ShaderNodeTexWave', {'Scale': 3.0, 'Distortion': 4.0, 'Detail': 15.0},
             wave_type='BANDS', bands_direction='DIAGONAL', wave_profile='SIN')
    link(nt, gen, w.inputs['Vector'])
    mg = node(nt, 'ShaderNodeTexMusgrave', {'Scale': 6.0, 'Detail': 15.0, 'Offset': 0.5},
              musgrave_type='HETERO_TERRAIN', musgrave_dimensions='3D')
    link(nt, gen, mg.inputs['Vector'])
    add = node(nt, 'ShaderNodeMath', operation='MULTIPLY_ADD')
    link(nt, w.outputs['Fac'], add.inputs[0])
    add.inputs[1].default_value = 0.3
    link(nt, mg.outputs['Fac'], add.inputs[2])
    r = ramp(nt, add.outputs['Value'], [(0.2, (0.55, 0.5, 0.45)), (1.0, (0.85, 0.8, 0.72))])
    b = bump(nt, add.outputs['Value'], 0.2)
    d = node(nt, 'ShaderNodeBsdfDiffuse')
    link(nt, r.outputs['Color'], d.inputs['Color'])
    link(nt, b.outputs['Normal'], d.inputs['Normal'])
    link(nt, d.outputs[0], out.inputs['Surface'])
    return m


# --- the scene ----------------------------------------------------------------------------


def place(mesh_op, name, mat, **kw):
    """Adds a primitive (smooth-shaded, with UVs) and gives it one material."""
    mesh_op(**kw)
    o = bpy.context.object
    o.name = o.data.name = name
    o.data.materials.append(mat)
    if hasattr(o.data, 'polygons'):
        for poly in o.data.polygons:
            poly.use_smooth = name != 'Crate'
    return o


def build(frames):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    w = bpy.data.worlds.new('World')
    w.use_nodes = True
    w.node_tree.nodes['Background'].inputs['Color'].default_value = (0.35, 0.45, 0.6, 1)
    w.node_tree.nodes['Background'].inputs['Strength'].default_value = 0.4
    sc.world = w

    m = bpy.ops.mesh
    place(m.primitive_plane_add, 'Floor', terrazzo_floor(), size=14)
    place(m.primitive_plane_add, 'BackWall', plaster_wall(), size=14, location=(0, 3, 7),
          rotation=(math.radians(90), 0, 0))
    place(m.primitive_uv_sphere_add, 'MarbleBall', marble(), radius=0.6,
          location=(-1.6, 0.4, 0.6), segments=32, ring_count=16)
    place(m.primitive_ico_sphere_add, 'Boulder', ridged_rock(), radius=0.7,
          location=(0.0, 1.4, 0.65), subdivisions=3)
    place(m.primitive_uv_sphere_add, 'CellBall', cells_4d(), radius=0.45,
          location=(1.5, 0.9, 0.45), segments=32, ring_count=16)
    place(m.primitive_cylinder_add, 'Log', wood(), radius=0.35, depth=1.4,
          location=(-0.4, -0.6, 0.35), rotation=(0, math.radians(90), math.radians(20)))
    place(m.primitive_cube_add, 'Crate', bricks(), size=0.8, location=(-2.6, 1.6, 0.4))
    place(m.primitive_monkey_add, 'Suzanne', car_paint(), size=0.9, location=(0.9, -0.4, 0.55),
          rotation=(0, 0, math.radians(200)))
    place(m.primitive_torus_add, 'Vase', glazed_ceramic(), major_radius=0.4, minor_radius=0.15,
          location=(2.4, -0.2, 0.15))
    place(m.primitive_cylinder_add, 'Drum', rusted_metal(), radius=0.4, depth=1.0,
          location=(2.6, 1.9, 0.5))
    # The UV material on a cube, whose default UVs unwrap each face onto part of the image.
    place(m.primitive_cube_add, 'LabelBox', label_image(), size=0.5,
          location=(-1.2, -1.3, 0.25), rotation=(0, 0, math.radians(30)))
    place(m.primitive_uv_sphere_add, 'MossMound', moss(), radius=0.8,
          location=(-2.8, -0.2, 0.0), segments=32, ring_count=16)

    sun = bpy.data.lights.new('Sun', 'SUN')
    sun.energy, sun.angle = 2.5, 0.0
    so = bpy.data.objects.new('Sun', sun)
    so.rotation_euler = (math.radians(45), 0, math.radians(-35))
    sc.collection.objects.link(so)
    area = bpy.data.lights.new('SoftBox', 'AREA')
    area.energy, area.size = 150.0, 1.0
    ao = bpy.data.objects.new('SoftBox', area)
    ao.location = (-1.5, -2.0, 3.5)
    sc.collection.objects.link(ao)

    # The camera: a dolly from left to right in front of the objects, always looking at the
    # middle of the group (a Track To constraint), keyframed at the ends.
    cam = bpy.data.cameras.new('Camera')
    cam.lens = 30
    co = bpy.data.objects.new('Camera', cam)
    sc.collection.objects.link(co)
    target = bpy.data.objects.new('CameraTarget', None)
    target.location = (0.0, 0.6, 0.5)
    sc.collection.objects.link(target)
    track = co.constraints.new('TRACK_TO')
    track.target, track.track_axis, track.up_axis = target, 'TRACK_NEGATIVE_Z', 'UP_Y'
    sc.frame_start, sc.frame_end = 1, frames
    co.location = (-3.0, -5.5, 2.0)
    co.keyframe_insert('location', frame=1)
    co.location = (3.0, -5.0, 1.6)
    co.keyframe_insert('location', frame=frames)
    sc.camera = co
    sc.render.resolution_x, sc.render.resolution_y = RESOLUTION
    sc.render.resolution_percentage = 100
    sc.frame_set(1)
    return co


def write_camera_path(path, co, frames):
    """The camera at each frame, in memograph's y-up world ((x, y, z) -> (x, z, -y), as the
    --scene import rotates the glTF root), looking at a point one metre ahead."""
    sc = bpy.context.scene
    aspect = RESOLUTION[0] / RESOLUTION[1]
    lines = ['# %s: %d frames, written by make_material_scene.py' % (co.name, frames)]
    for f in range(1, frames + 1):
        sc.frame_set(f)
        mw = co.matrix_world
        pos = mw.translation
        ahead = pos + mw.to_quaternion() @ Vector((0.0, 0.0, -1.0))
        # Sensor fit AUTO on a wide image: Blender's angle is horizontal; memograph's is
        # vertical.
        fov = math.degrees(2 * math.atan(math.tan(co.data.angle / 2) / aspect))

        def yup(v):
            return (v.x, v.z, -v.y)

        lines.append('%.6f %.6f %.6f  %.6f %.6f %.6f  %.4f' % (*yup(pos), *yup(ahead), fov))
    sc.frame_set(1)
    with open(path, 'w') as f:
        f.write('\n'.join(lines) + '\n')


def main(argv):
    out = os.path.abspath(argv[0])
    frames = int(argv[argv.index('--frames') + 1]) if '--frames' in argv else DEFAULT_FRAMES
    co = build(frames)
    if '--camera-path' in argv:
        write_camera_path(os.path.abspath(argv[argv.index('--camera-path') + 1]), co, frames)
    # No OUT.blend1 backup beside a rebuilt file (the committed example is overwritten).
    bpy.context.preferences.filepaths.save_version = 0
    bpy.ops.wm.save_as_mainfile(filepath=out, compress=True)
    print('make_material_scene: wrote %s (%d materials)' % (out, len(bpy.data.materials)))
    return 0


if __name__ == '__main__':
    code = main(sys.argv[sys.argv.index('--') + 1:])
    sys.stdout.flush()
    os._exit(code)

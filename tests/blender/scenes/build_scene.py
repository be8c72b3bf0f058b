"""Builds one Blender test scene, renders it with Cycles and exports it for memograph.

    blender -b --factory-startup --python build_scene.py -- --scene NAME --out DIR
            [--size N] [--samples S]

Writes DIR/NAME.blend, DIR/cycles.pfm (Cycles CPU, no denoiser, box filter one pixel wide,
no clamping, no light threshold) and DIR/export/ (the memograph exporter with --scene:
<material>.mgraph, scene.gltf, scene.memograph). The scenes (all Blender units, z up):

- units_point / units_sun / units_spot / units_area: a 4 m white Diffuse plane (albedo 1)
  seen from above by a camera (memograph has no orthographic camera), lit by one light of that type and nothing else.
- emission: procedural emission only (Noise and Checker into Emission), no lights, black world.
- room: a diffuse room (floor and two walls, Diffuse BSDF with procedural albedo) with a
  point light, a sun and an emissive panel.
- principled: nine Principled BSDF tiles side by side (PRINCIPLED_TILES: coloured bases at
  a few Metallic / Specular / Specular Tint / Roughness values) lit by one sun, seen near
  the sun's mirror direction so the highlights are in view. principled_retro: the same
  tiles with the sun behind the camera, both far from the normal (back-scattering, where
  Principled diffuse's retro-reflection shows). Both also write DIR/tiles.json:
  each tile's material and the pixel box (x0, y0, x1, y1, inclusive, row 0 at the bottom as
  in PFM) of its middle, which compare_scene.py averages per tile.
- light_path_camera: (a) an emissive panel whose colour Light Path's Is Camera Ray picks
  (red to the camera, blue to every other ray) over a grey floor, which it lights blue.
- bsdf_<tree> (BSDF_TREES: diffuse, oren_nayar, glossy_ggx, glossy_beckmann, velvet, mix,
  add, glass, glass_rough, refraction, transparent, translucent, principled_sheen,
  principled_clearcoat, principled_transmission, principled_mix, principled_add): a smooth
  sphere of that BSDF (or Mix/Add Shader of BSDFs) on a checker floor under a sky and a sun,
  with Cycles' Filter Glossy off (unbiased_glossy); bsdf_glossy_filtered: bsdf_glossy_ggx's
  scene with Filter Glossy at Blender's default 1 (and a box of the floor beside the ball);
  bsdf_room: a room of several of them (docs/design/closures.md). The principled_* scenes
  also write DIR/tiles.json with the ball's box.
- light_path_depth: (b) an emissive panel that emits only for Ray Depth 1 (black to the
  camera, lighting the floor and a wall directly, no bounced light). Both write
  DIR/tiles.json with their regions (panel, floor, wall) as the Principled scenes do.
- ao, ao_local: a cube on a floor whose emission is their Ambient Occlusion node's Color
  (ao: plain; ao_local: the floor Only Local, the cube Inside), regions in DIR/tiles.json.
- bevel: a cube emitting the tilt of its Bevel node's normal from the shading normal;
  regions: the top and front faces' middles and the strips along the edge between them.
- alpha_cutout: leaf cards whose Principled Alpha is a cut-out texture, and a Principled
  BSDF of Alpha 0.5 under a Mix with a Glossy, before a wall over a floor, under a sun.
- object_normal: Texture Coordinate Normal as emission on a rotated, unevenly scaled sphere
  and plane, black world (the object-space normal through the object's transform).
"""

import argparse
import json
import math
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, '..', '..', '..', 'tools', 'blender'))
sys.dont_write_bytecode = True

from cycles_reference import render_reference_pfm  # noqa: E402 (needs the path above)


def diffuse(name, color=(1, 1, 1), albedo_node=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    d = nt.nodes.new('ShaderNodeBsdfDiffuse')
    d.inputs['Color'].default_value = (*color, 1)
    d.inputs['Roughness'].default_value = 0.0
    o = nt.nodes.new('ShaderNodeOutputMaterial')
    nt.links.new(d.outputs[0], o.inputs['Surface'])
    if albedo_node is not None:
        albedo_node(nt, d.inputs['Color'])
    return m


def emission(name, color=(1, 1, 1), strength=1.0, color_node=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    e = nt.nodes.new('ShaderNodeEmission')
    e.inputs['Color'].default_value = (*color, 1)
    e.inputs['Strength'].default_value = strength
    o = nt.nodes.new('ShaderNodeOutputMaterial')
    nt.links.new(e.outputs[0], o.inputs['Surface'])
    if color_node is not None:
        color_node(nt, e.inputs['Color'], e.inputs['Strength'])
    return m


def principled(name, base_color, metallic, specular, specular_tint, roughness):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes['Principled BSDF']
    p.inputs['Base Color'].default_value = (*base_color, 1)
    p.inputs['Metallic'].default_value = metallic
    p.inputs['Specular'].default_value = specular
    p.inputs['Specular Tint'].default_value = specular_tint
    p.inputs['Roughness'].default_value = roughness
    return m


def plane(name, size, material, location=(0, 0, 0), rotation=(0, 0, 0)):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.object
    obj.name = name
    obj.data.name = name
    obj.data.materials.append(material)
    return obj


def light(kind, name, location, rotation=(0, 0, 0), **props):
    data = bpy.data.lights.new(name, kind)
    for k, v in props.items():
        setattr(data, k, v)
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    obj.rotation_euler = rotation
    bpy.context.scene.collection.objects.link(obj)
    return obj


def camera(location, rotation=(0, 0, 0), ortho_scale=None, lens=None):
    cam = bpy.data.cameras.new('Camera')
    if ortho_scale is not None:
        cam.type = 'ORTHO'
        cam.ortho_scale = ortho_scale
    if lens is not None:
        cam.lens = lens
    cam.sensor_fit = 'HORIZONTAL'
    obj = bpy.data.objects.new('Camera', cam)
    obj.location = location
    obj.rotation_euler = rotation
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    return obj


def world(color=(0, 0, 0), strength=1.0):
    w = bpy.data.worlds.new('World')
    w.use_nodes = True
    bg = w.node_tree.nodes['Background']
    bg.inputs['Color'].default_value = (*color, 1)
    bg.inputs['Strength'].default_value = strength
    bpy.context.scene.world = w


def units_scene(kind):
    world()
    plane('Ground', 4.0, diffuse('White'))
    if kind == 'point':
        light('POINT', 'Lamp', (0.1, -0.05, 2.0), energy=100.0, color=(1.0, 0.9, 0.8),
              shadow_soft_size=0.0)
        camera((0, 0, 1), lens=70)
    elif kind == 'sun':
        light('SUN', 'Sun', (0, 0, 3), rotation=(math.radians(30), 0, math.radians(20)),
              energy=3.0, color=(0.9, 0.95, 1.0), angle=0.0)
        camera((0, 0, 1), lens=70)
    elif kind == 'spot':
        light('SPOT', 'Spot', (0, 0, 2.0), energy=200.0, spot_size=math.radians(50),
              spot_blend=0.3, shadow_soft_size=0.0)
        camera((0, 0, 1), lens=12)  # the cone's edge (r = 0.93 m) is in view
    elif kind == 'area':
        light('AREA', 'Panel', (0, 0, 1.5), energy=50.0, size=0.5, shape='SQUARE')
        camera((0, 0, 1), lens=35)


def checker(nt, target, c1=(0.8, 0.3, 0.2), c2=(0.2, 0.6, 0.8), scale=4.0):
    t = nt.nodes.new('ShaderNodeTexChecker')
    t.inputs['Color1'].default_value = (*c1, 1)
    t.inputs['Color2'].default_value = (*c2, 1)
    t.inputs['Scale'].default_value = scale
    nt.links.new(t.outputs['Color'], target)


def emission_scene():
    world()

    def noisy(nt, color, strength):
        n = nt.nodes.new('ShaderNodeTexNoise')
        n.inputs['Scale'].default_value = 3.0
        ramp = nt.nodes.new('ShaderNodeValToRGB')
        ramp.color_ramp.elements[0].color = (0.05, 0.1, 0.4, 1)
        ramp.color_ramp.elements[1].color = (1.0, 0.7, 0.2, 1)
        nt.links.new(n.outputs['Fac'], ramp.inputs['Fac'])
        nt.links.new(ramp.outputs['Color'], color)

    plane('Glow', 2.0, emission('Glow', strength=1.5, color_node=noisy))
    plane('Tiles', 0.8, emission('Tiles', color_node=lambda nt, c, s: checker(nt, c, scale=3)),
          location=(0.3, 0.3, 0.2))
    camera((0, 0, 2), lens=40)


def room_scene():
    world()
    floor = diffuse('Floor', albedo_node=lambda nt, c: checker(nt, c, (0.8, 0.8, 0.75),
                                                            (0.3, 0.35, 0.4), 5.0))
    wall = diffuse('Wall', color=(0.7, 0.6, 0.5))
    plane('Floor', 4.0, floor)
    plane('BackWall', 4.0, wall, location=(0, 2, 2), rotation=(math.radians(90), 0, 0))
    plane('SideWall', 4.0, diffuse('SideWall', color=(0.4, 0.6, 0.4)), location=(-2, 0, 2),
          rotation=(0, math.radians(90), 0))
    panel = plane('Panel', 1.0, emission('Panel', color=(1.0, 0.9, 0.7), strength=4.0),
                  location=(1.2, 1.98, 1.8), rotation=(math.radians(90), 0, 0))
    panel.scale = (1.0, 0.5, 1.0)
    light('POINT', 'Bulb', (0.5, 0.0, 2.5), energy=150.0, shadow_soft_size=0.0)
    light('SUN', 'Sun', (0, 0, 5), rotation=(math.radians(40), 0, math.radians(-30)),
          energy=2.0, angle=0.0)
    camera((1.2, -4.5, 1.8), rotation=(math.radians(80), 0, math.radians(12)), lens=28)


ORANGE = (0.8, 0.3, 0.08)
BLUE = (0.15, 0.35, 0.8)
GREEN = (0.2, 0.6, 0.15)
# (base colour, Metallic, Specular, Specular Tint, Roughness), row-major from the camera's
# top-left tile: tint off and on at one setting, high Specular with tint, half metal, a
# rough tile (Principled diffuse's retro-reflection), a metal, no specular at all.
PRINCIPLED_TILES = (
    (ORANGE, 0.0, 0.5, 0.0, 0.3), (ORANGE, 0.0, 0.5, 1.0, 0.3), (ORANGE, 0.0, 1.0, 1.0, 0.2),
    (BLUE, 0.0, 1.0, 0.5, 0.4), (BLUE, 0.5, 0.5, 1.0, 0.3), (BLUE, 0.0, 0.5, 0.0, 1.0),
    (ORANGE, 1.0, 0.5, 0.0, 0.35), (GREEN, 0.0, 0.0, 0.0, 0.5), (GREEN, 0.2, 0.8, 0.8, 0.6),
)


def principled_scene(view='mirror'):
    world()
    tiles = []
    for k, (color, metallic, specular, tint, roughness) in enumerate(PRINCIPLED_TILES):
        row, col = divmod(k, 3)
        name = 'P%d' % k
        # The camera looks towards -y: its left is +x, its top (the far side) is -y.
        x, y = (1 - col) * 1.0, (row - 1) * 1.0
        plane(name, 0.9, principled(name, color, metallic, specular, tint, roughness),
              location=(x, y, 0))
        tiles.append((name, x, y))
    if view == 'mirror':
        # The sun shines towards +y and down, 55 degrees from the normal; the camera sits near
        # the mirror direction (40 degrees from the normal), towards -y.
        light('SUN', 'Sun', (0, 0, 3), rotation=(math.radians(55), 0, 0), energy=3.0,
              angle=0.0)
        camera((0, 3.6, 3.3), rotation=(math.radians(47.5), 0, math.radians(180)), lens=55)
    else:
        # Back-scattering: the sun behind the camera, 65 degrees from the normal, the camera
        # 60 degrees from it, where Principled diffuse's retro-reflection is strong.
        light('SUN', 'Sun', (0, 0, 3), rotation=(math.radians(-65), 0, 0), energy=3.0,
              angle=0.0)
        camera((0, 4.33, 2.5), rotation=(math.radians(60), 0, math.radians(180)), lens=50)
    return tiles


def bsdf_node(nt, kind, **inputs):
    n = nt.nodes.new(kind)
    for name, value in inputs.items():
        if name == 'distribution':
            n.distribution = value
        else:
            n.inputs[name].default_value = (*value, 1) if isinstance(value, tuple) else value
    return n


# One BSDF (or Mix/Add Shader of BSDFs) per scene, nodes/bsdf.inc's lobes: the node tree's
# root shader, built in a new material's tree.
BSDF_TREES = {
    'diffuse': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfDiffuse', Color=(0.8, 0.3, 0.1),
                                    Roughness=0.0),
    'oren_nayar': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfDiffuse', Color=(0.2, 0.4, 0.8),
                                       Roughness=1.0),
    'glossy_ggx': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfGlossy', Color=(0.9, 0.7, 0.3),
                                       Roughness=0.3, distribution='GGX'),
    'glossy_beckmann': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfGlossy', Color=(0.9, 0.7, 0.3),
                                            Roughness=0.3, distribution='BECKMANN'),
    # Roughness 0: Cycles' perfect mirror (alpha^2 <= 1e-7), which light sampling cannot see.
    'glossy_sharp': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfGlossy', Color=(0.9, 0.9, 0.9),
                                         Roughness=0.0, distribution='GGX'),
    'velvet': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfVelvet', Color=(0.8, 0.2, 0.5),
                                   Sigma=0.5),
    'mix': lambda nt: mix_tree(nt),
    'add': lambda nt: add_tree(nt),
    # Transmission: the path goes through the ball (docs/design/closures.md).
    'glass': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfGlass', Color=(0.95, 0.95, 0.95),
                                  Roughness=0.0, IOR=1.45, distribution='GGX'),
    'glass_rough': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfGlass', Color=(0.9, 0.95, 1.0),
                                        Roughness=0.3, IOR=1.5, distribution='BECKMANN'),
    'refraction': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfRefraction',
                                       Color=(0.9, 0.9, 0.7), Roughness=0.2, IOR=1.33,
                                       distribution='GGX'),
    'transparent': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfTransparent',
                                        Color=(0.9, 0.6, 0.3)),
    'translucent': lambda nt: bsdf_node(nt, 'ShaderNodeBsdfTranslucent',
                                        Color=(0.3, 0.7, 0.4)),
    # The Principled BSDF v1's layers (PrincipledLayers), each over a dark base so that the
    # layer is much of what the ball reflects: a dark blue cloth's sheen (tinted halfway to
    # its hue) and a dark red lacquer's clearcoat, sharper than the base's own specular.
    'principled_sheen': lambda nt: bsdf_node(
        nt, 'ShaderNodeBsdfPrincipled', distribution='GGX',
        **{'Base Color': (0.02, 0.02, 0.06), 'Roughness': 0.6, 'Sheen': 1.0,
           'Sheen Tint': 0.5}),
    'principled_clearcoat': lambda nt: bsdf_node(
        nt, 'ShaderNodeBsdfPrincipled', distribution='GGX',
        **{'Base Color': (0.05, 0.01, 0.01), 'Roughness': 0.6, 'Clearcoat': 1.0,
           'Clearcoat Roughness': 0.1}),
    # Principled BSDFs under Mix and Add Shader (PrincipledBsdf; a Mix of two Principled
    # BSDFs chooses one per hit, ChooseShader): red plastic with a clearcoat and gold metal
    # mixed by a noise texture, and a dark Principled BSDF with a sheen and a clearcoat plus a
    # Glossy GGX (four lobes: both at every hit).
    'principled_mix': lambda nt: principled_mix_tree(nt),
    'principled_add': lambda nt: principled_add_tree(nt),
    # A tinted glass ball whose refraction is rougher than its reflection.
    'principled_transmission': lambda nt: bsdf_node(
        nt, 'ShaderNodeBsdfPrincipled', distribution='GGX',
        **{'Base Color': (0.8, 0.9, 1.0), 'Roughness': 0.1, 'Transmission': 1.0,
           'Transmission Roughness': 0.2, 'IOR': 1.45}),
}


def mix_tree(nt):
    """Mix Shader with a textured factor (a checker) between Diffuse and Glossy GGX."""
    mix = nt.nodes.new('ShaderNodeMixShader')
    t = nt.nodes.new('ShaderNodeTexChecker')
    t.inputs['Scale'].default_value = 3.0
    t.inputs['Color1'].default_value = (0.8, 0.8, 0.8, 1)
    t.inputs['Color2'].default_value = (0.2, 0.2, 0.2, 1)
    nt.links.new(t.outputs['Fac'], mix.inputs['Fac'])
    nt.links.new(bsdf_node(nt, 'ShaderNodeBsdfDiffuse', Color=(0.2, 0.6, 0.2)).outputs[0],
                 mix.inputs[1])
    nt.links.new(bsdf_node(nt, 'ShaderNodeBsdfGlossy', Color=(0.9, 0.9, 0.9), Roughness=0.2,
                           distribution='GGX').outputs[0], mix.inputs[2])
    return mix


def add_tree(nt):
    """Add Shader of a dark red Diffuse and a grey Glossy Beckmann."""
    add = nt.nodes.new('ShaderNodeAddShader')
    nt.links.new(bsdf_node(nt, 'ShaderNodeBsdfDiffuse', Color=(0.4, 0.1, 0.1)).outputs[0],
                 add.inputs[0])
    nt.links.new(bsdf_node(nt, 'ShaderNodeBsdfGlossy', Color=(0.5, 0.5, 0.5), Roughness=0.4,
                           distribution='BECKMANN').outputs[0], add.inputs[1])
    return add


def principled_mix_tree(nt):
    """Mix Shader by a noise factor of red plastic with a clearcoat and gold metal."""
    mix = nt.nodes.new('ShaderNodeMixShader')
    noise = nt.nodes.new('ShaderNodeTexNoise')
    noise.inputs['Scale'].default_value = 3.0
    noise.inputs['Detail'].default_value = 2.0
    ramp = nt.nodes.new('ShaderNodeMapRange')  # noise's 0.3-0.7 stretched to 0-1
    ramp.inputs['From Min'].default_value = 0.35
    ramp.inputs['From Max'].default_value = 0.65
    nt.links.new(noise.outputs['Fac'], ramp.inputs['Value'])
    nt.links.new(ramp.outputs['Result'], mix.inputs['Fac'])
    red = bsdf_node(nt, 'ShaderNodeBsdfPrincipled', distribution='GGX',
                    **{'Base Color': (0.8, 0.05, 0.03), 'Roughness': 0.4, 'Clearcoat': 1.0,
                       'Clearcoat Roughness': 0.1})
    gold = bsdf_node(nt, 'ShaderNodeBsdfPrincipled', distribution='GGX',
                     **{'Base Color': (1.0, 0.77, 0.34), 'Metallic': 1.0, 'Roughness': 0.3})
    nt.links.new(red.outputs[0], mix.inputs[1])
    nt.links.new(gold.outputs[0], mix.inputs[2])
    return mix


def principled_add_tree(nt):
    """Add Shader of a dark blue Principled BSDF with a sheen and a clearcoat and a grey Glossy
    GGX."""
    add = nt.nodes.new('ShaderNodeAddShader')
    nt.links.new(bsdf_node(nt, 'ShaderNodeBsdfPrincipled', distribution='GGX',
                           **{'Base Color': (0.05, 0.08, 0.3), 'Roughness': 0.5, 'Sheen': 1.0,
                              'Clearcoat': 0.5, 'Clearcoat Roughness': 0.2}).outputs[0],
                 add.inputs[0])
    nt.links.new(bsdf_node(nt, 'ShaderNodeBsdfGlossy', Color=(0.3, 0.3, 0.3), Roughness=0.25,
                           distribution='GGX').outputs[0], add.inputs[1])
    return add


def bsdf_material(name, tree):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    o = nt.nodes.new('ShaderNodeOutputMaterial')
    nt.links.new(BSDF_TREES[tree](nt).outputs[0], o.inputs['Surface'])
    return m


def sphere(name, material, location, radius):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=radius,
                                         location=location)
    obj = bpy.context.object
    obj.name = name
    obj.data.name = name
    bpy.ops.object.shade_smooth()
    obj.data.materials.append(material)
    return obj


def unbiased_glossy():
    """Cycles' Filter Glossy off, so that a scene compares its lobes alone: its default (1)
    widens glossy lobes after a diffuse bounce (light that the room's Glossy ball reflects onto
    the floor comes 3-5 % darker with it). The export carries the 0, so memograph renders
    without the blur too; bsdf_glossy_filtered keeps the default in both."""
    bpy.context.scene.cycles.blur_glossy = 0.0


def bsdf_scene(tree, filter_glossy=False):
    """A sphere of one BSDF tree on a grey checker floor, under a blue-grey sky and a sun.
    With `filter_glossy`, Cycles' Filter Glossy stays at Blender's default (1), which the export
    carries; the floor beside the ball, which sees the ball's glossy reflections after its
    diffuse bounce, is compared as a box too."""
    if not filter_glossy:
        unbiased_glossy()
    world(color=(0.3, 0.35, 0.45))
    plane('Floor', 6.0, diffuse('Floor', albedo_node=lambda nt, c: checker(
        nt, c, (0.7, 0.7, 0.7), (0.25, 0.25, 0.25), 6.0)))
    sphere('Ball', bsdf_material('Ball', tree), (0, 0, 0.8), 0.8)
    light('SUN', 'Sun', (0, 0, 5), rotation=(math.radians(35), 0, math.radians(-40)),
          energy=3.0, angle=0.0)
    camera((0, -3.6, 1.6), rotation=(math.radians(80), 0, 0), lens=40)
    if filter_glossy:
        # The floor in front of the ball (0.45 m to 0.95 m from its foot, 1.2 m either side).
        return [('FloorNearBall', [(x, y, 0.0) for x in (-1.2, 1.2) for y in (-0.95, -0.45)])]
    if tree.startswith('principled_'):
        # A Principled layer is a small part of the whole image: the ball's own box (the
        # square around it, through its centre, facing the camera) is compared too.
        return [('Ball', [(x, 0.0, z) for x in (-0.8, 0.8) for z in (0.0, 1.6)])]
    return None


def noise_bump(nt, scale, distance):
    """A Bump node over smooth Noise (Detail 0, of the object's Generated coordinates): a
    low-frequency bump, which Cycles' dP differences and memograph's footprint derivatives
    both follow (docs/guide/blender-node-accuracy.md)."""
    tex = nt.nodes.new('ShaderNodeTexNoise')
    tex.inputs['Scale'].default_value = scale
    tex.inputs['Detail'].default_value = 0.0
    bump = nt.nodes.new('ShaderNodeBump')
    bump.inputs['Distance'].default_value = distance
    nt.links.new(tex.outputs['Fac'], bump.inputs['Height'])
    return bump


def normals_material(name, kind):
    """Per-BSDF normals (docs/design/closures.md): a lacquered Principled BSDF whose base is
    bumped under a smooth clearcoat (Clearcoat Normal unlinked: Cycles' sd->N), the same with
    its clearcoat bumped otherwise (Clearcoat Normal linked to a finer bump), and a Mix Shader
    of a bumped Diffuse and a smooth (unbumped) Glossy. The glossy parts are rough enough
    that the sun's highlight spreads over several pixels: a one-pixel highlight would weigh
    each renderer's pixel filter (Cycles' Blackman-Harris, memograph's box) more than the
    normals."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    o = nt.nodes.new('ShaderNodeOutputMaterial')
    if kind == 'mix':
        mix = nt.nodes.new('ShaderNodeMixShader')
        mix.inputs['Fac'].default_value = 0.5
        diffuse_bsdf = bsdf_node(nt, 'ShaderNodeBsdfDiffuse', Color=(0.2, 0.5, 0.8))
        nt.links.new(noise_bump(nt, 4.0, 0.3).outputs['Normal'], diffuse_bsdf.inputs['Normal'])
        nt.links.new(diffuse_bsdf.outputs[0], mix.inputs[1])
        nt.links.new(bsdf_node(nt, 'ShaderNodeBsdfGlossy', Color=(0.9, 0.9, 0.9),
                               Roughness=0.35, distribution='GGX').outputs[0], mix.inputs[2])
        nt.links.new(mix.outputs[0], o.inputs['Surface'])
        return m
    p = bsdf_node(nt, 'ShaderNodeBsdfPrincipled', distribution='GGX',
                  **{'Base Color': (0.05, 0.01, 0.01), 'Roughness': 0.6, 'Clearcoat': 1.0,
                     'Clearcoat Roughness': 0.15})
    nt.links.new(noise_bump(nt, 4.0, 0.3).outputs['Normal'], p.inputs['Normal'])
    if kind == 'coat_bumped':
        nt.links.new(noise_bump(nt, 2.0, 0.2).outputs['Normal'], p.inputs['Clearcoat Normal'])
    nt.links.new(p.outputs[0], o.inputs['Surface'])
    return m


def bsdf_normals_scene():
    """Three balls of per-BSDF normals (normals_material: smooth coat, bumped coat, Mix of a
    bumped Diffuse and a smooth Glossy) on bsdf_scene's floor, sky and sun; each ball's box
    is compared too."""
    unbiased_glossy()
    world(color=(0.3, 0.35, 0.45))
    plane('Floor', 6.0, diffuse('Floor', albedo_node=lambda nt, c: checker(
        nt, c, (0.7, 0.7, 0.7), (0.25, 0.25, 0.25), 6.0)))
    balls = (('CoatSmooth', 'coat_smooth', -1.1), ('CoatBumped', 'coat_bumped', 0.0),
             ('MixBumpedDiffuse', 'mix', 1.1))
    for name, kind, x in balls:
        sphere(name, normals_material(name, kind), (x, 0, 0.5), 0.5)
    light('SUN', 'Sun', (0, 0, 5), rotation=(math.radians(35), 0, math.radians(-40)),
          energy=3.0, angle=0.0)
    camera((0, -3.0, 0.9), rotation=(math.radians(82.4), 0, 0), lens=26)
    # The middle of each ball (its box through the centre, facing the camera, 0.3 m either
    # side): the floor and its glossy caustics around a ball stay out.
    return [(name, [(x + dx, 0.0, 0.5 + dz) for dx in (-0.3, 0.3) for dz in (-0.3, 0.3)])
            for name, _, x in balls]


def bsdf_room_scene():
    """A lit room of several BSDFs: a Mix-Shader floor (checker between Diffuse and Glossy),
    Oren-Nayar walls, a Velvet ball and a Glossy GGX ball; a point light and a panel."""
    unbiased_glossy()
    world()
    floor = bpy.data.materials.new('Floor')
    floor.use_nodes = True
    nt = floor.node_tree
    nt.nodes.clear()
    nt.links.new(mix_tree(nt).outputs[0], nt.nodes.new('ShaderNodeOutputMaterial').inputs[0])
    plane('Floor', 4.0, floor)
    plane('BackWall', 4.0, bsdf_material('Wall', 'oren_nayar'), location=(0, 2, 2),
          rotation=(math.radians(90), 0, 0))
    plane('SideWall', 4.0, diffuse('SideWall', color=(0.6, 0.55, 0.4)), location=(-2, 0, 2),
          rotation=(0, math.radians(90), 0))
    sphere('Velvet', bsdf_material('Velvet', 'velvet'), (-0.7, 0.6, 0.5), 0.5)
    sphere('Gold', bsdf_material('Gold', 'glossy_ggx'), (0.7, 0.3, 0.5), 0.5)
    panel = plane('Panel', 1.0, emission('Panel', color=(1.0, 0.9, 0.7), strength=4.0),
                  location=(1.2, 1.98, 1.8), rotation=(math.radians(90), 0, 0))
    panel.scale = (1.0, 0.5, 1.0)
    light('POINT', 'Bulb', (0.3, -0.5, 2.5), energy=150.0, shadow_soft_size=0.0)
    camera((0.6, -4.0, 1.6), rotation=(math.radians(82), 0, math.radians(8)), lens=28)


def light_path_emission(name, camera_color, other_color, strength):
    """Emission whose colour Blender's Light Path picks: `camera_color` for camera rays
    (Is Camera Ray 1), `other_color` for every other ray and for light samples."""
    def by_ray(nt, color, _strength):
        lp = nt.nodes.new('ShaderNodeLightPath')
        mix = nt.nodes.new('ShaderNodeMixRGB')
        mix.inputs['Color1'].default_value = (*other_color, 1)
        mix.inputs['Color2'].default_value = (*camera_color, 1)
        nt.links.new(lp.outputs['Is Camera Ray'], mix.inputs['Fac'])
        nt.links.new(mix.outputs['Color'], color)
    return emission(name, strength=strength, color_node=by_ray)


def light_path_camera_scene():
    """(a) Is Camera Ray: a panel the camera sees red lights the floor in front of it blue."""
    world()
    plane('Floor', 4.0, diffuse('Floor', color=(0.8, 0.8, 0.8)))
    plane('Panel', 1.2, light_path_emission('Panel', (1.0, 0.15, 0.05), (0.05, 0.25, 1.0), 3.0),
          location=(0, 0.6, 0.7), rotation=(math.radians(90), 0, 0))
    camera((0, -1.9, 1.1), rotation=(math.radians(74), 0, 0), lens=24)
    # The panel's middle and the floor in front of it (x, y, z corners of each region).
    return [('panel', [(x, 0.6, z) for x in (-0.45, 0.45) for z in (0.25, 1.15)]),
            ('floor', [(x, y, 0.0) for x in (-0.7, 0.7) for y in (-0.6, 0.4)])]


def light_path_depth_scene():
    """(b) Ray Depth: a panel that emits only for rays of depth exactly 1 (Math Compare with
    1, epsilon 0.5): the camera sees it black, it lights the floor and the wall directly, and
    no light that bounced (depth 2 and on) reaches the camera."""
    world()

    def first_bounce_only(nt, _color, strength):
        lp = nt.nodes.new('ShaderNodeLightPath')
        cmp = nt.nodes.new('ShaderNodeMath')
        cmp.operation = 'COMPARE'
        cmp.inputs[1].default_value = 1.0
        cmp.inputs[2].default_value = 0.5
        scale = nt.nodes.new('ShaderNodeMath')
        scale.operation = 'MULTIPLY'
        scale.inputs[1].default_value = 4.0
        nt.links.new(lp.outputs['Ray Depth'], cmp.inputs[0])
        nt.links.new(cmp.outputs[0], scale.inputs[0])
        nt.links.new(scale.outputs[0], strength)

    plane('Floor', 4.0, diffuse('Floor', color=(0.8, 0.8, 0.8)))
    plane('Wall', 4.0, diffuse('Wall', color=(0.7, 0.6, 0.5)), location=(0, 1.5, 2),
          rotation=(math.radians(90), 0, 0))
    plane('Panel', 0.8, emission('Panel', color=(1.0, 0.95, 0.9),
                                 color_node=first_bounce_only),
          location=(0.5, 0.7, 1.0), rotation=(math.radians(60), 0, 0))
    camera((0, -2.8, 1.4), rotation=(math.radians(75), 0, 0), lens=28)
    return [('floor', [(x, y, 0.0) for x in (-1.2, 0.4) for y in (-0.5, 0.6)]),
            ('wall', [(x, 1.5, z) for x in (-1.4, -0.3) for z in (0.4, 1.8)]),
            ('panel', [(0.5 + x, 0.7 + y, 1.0 + z) for x in (-0.3, 0.3)
                       for (y, z) in ((-0.15, -0.26), (0.15, 0.26))])]


def ao_emission(name, distance, inside=False, only_local=False, samples=16):
    """Emission whose colour is Blender's Ambient Occlusion of the hit (strength 1), so a
    pixel holds the node's fraction itself: no lights, a black world, no BSDF to reflect."""
    def by_ao(nt, color, _strength):
        ao = nt.nodes.new('ShaderNodeAmbientOcclusion')
        ao.samples = samples
        ao.inside = inside
        ao.only_local = only_local
        ao.inputs['Distance'].default_value = distance
        ao.inputs['Color'].default_value = (1, 1, 1, 1)
        nt.links.new(ao.outputs['Color'], color)
    return emission(name, color_node=by_ao)


def cube(name, size, material, location):
    bpy.ops.mesh.primitive_cube_add(size=size, location=location)
    obj = bpy.context.object
    obj.name = name
    obj.data.name = name
    obj.data.materials.append(material)
    return obj


def ao_scene(local):
    """The Ambient Occlusion node (traced inputs, docs/design/traced-inputs.md): a 1 m cube on
    a floor, both emitting their AO (distance 0.6). ao: the floor darkens towards the cube,
    the cube's sides towards the floor. ao_local: the floor with Only Local (the cube is
    another object: no darkening), the cube with Inside (rays into the cube find its far
    faces within 0.6 m near its edges)."""
    world()
    plane('Floor', 6.0, ao_emission('FloorAo', 0.6, only_local=local))
    cube('Cube', 1.0, ao_emission('CubeAo', 0.6, inside=local), location=(0, 0, 0.5))
    camera((0, -3.0, 2.2), rotation=(math.radians(53), 0, 0), lens=50)
    # The floor just in front of the cube (0.05..0.25 m from it), the floor 0.6 m and more
    # from it (nothing within the AO distance), and the cube's front face near the floor and
    # 0.6 m and more above it.
    return [('floor_near', [(x, y, 0.0) for x in (-0.35, 0.35) for y in (-0.75, -0.55)]),
            ('floor_far', [(x, y, 0.0) for x in (-1.0, -0.7) for y in (-1.4, -1.15)]),
            ('cube_low', [(x, -0.5, z) for x in (-0.35, 0.35) for z in (0.05, 0.3)]),
            ('cube_high', [(x, -0.5, z) for x in (-0.35, 0.35) for z in (0.65, 0.9)])]


def bevel_scene():
    """The Bevel node (a traced input): a 1 m cube emitting how far its Bevel normal (radius
    0.25) tilts from the face's normal, |Bevel x Geometry True Normal| (the sine of the tilt;
    a flat cube's true normal is its shading normal, both world-space), as a grey, under a
    black world. A world vector itself would not compare: memograph renders
    the export in its y-up world (docs/guide/blender.md, Scene export), the tilt is the same
    in both. The faces' middles keep the face normal (0); strips along the top front edge
    tilt towards the other face."""
    world()
    m = bpy.data.materials.new('Rounded')
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    bevel = nt.nodes.new('ShaderNodeBevel')
    bevel.samples = 16
    bevel.inputs['Radius'].default_value = 0.25
    geometry = nt.nodes.new('ShaderNodeNewGeometry')
    cross = nt.nodes.new('ShaderNodeVectorMath')
    cross.operation = 'CROSS_PRODUCT'
    length = nt.nodes.new('ShaderNodeVectorMath')
    length.operation = 'LENGTH'
    e = nt.nodes.new('ShaderNodeEmission')
    o = nt.nodes.new('ShaderNodeOutputMaterial')
    nt.links.new(bevel.outputs['Normal'], cross.inputs[0])
    nt.links.new(geometry.outputs['True Normal'], cross.inputs[1])
    nt.links.new(cross.outputs['Vector'], length.inputs[0])
    nt.links.new(length.outputs['Value'], e.inputs['Color'])
    nt.links.new(e.outputs[0], o.inputs['Surface'])
    cube('Cube', 1.0, m, location=(0, 0, 0.5))
    camera((0, -2.6, 2.3), rotation=(math.radians(55), 0, 0), lens=50)
    return [('top_middle', [(x, y, 1.0) for x in (-0.2, 0.2) for y in (-0.2, 0.2)]),
            ('top_edge', [(x, y, 1.0) for x in (-0.3, 0.3) for y in (-0.5, -0.32)]),
            ('front_edge', [(x, -0.5, z) for x in (-0.3, 0.3) for z in (0.86, 1.0)]),
            ('front_middle', [(x, -0.5, z) for x in (-0.2, 0.2) for z in (0.3, 0.7)])]
def object_normal_scene():
    """Texture Coordinate Normal as emitted colour (N / 2 + 1/2) on a smooth sphere and a
    plane, each rotated and scaled unevenly: the object-space normal, which Box projection's
    weights read too. (Geometry Normal is world space, which the scene export turns y-up, so
    it is not compared here: the bakes compare it.)"""
    world()

    def normal_of(node_type, socket):
        def by_normal(nt, color, _strength):
            tc = nt.nodes.new(node_type)
            half = nt.nodes.new('ShaderNodeVectorMath')
            half.operation = 'MULTIPLY_ADD'
            half.inputs[1].default_value = (0.5, 0.5, 0.5)
            half.inputs[2].default_value = (0.5, 0.5, 0.5)
            nt.links.new(tc.outputs[socket], half.inputs[0])
            nt.links.new(half.outputs[0], color)
        return by_normal

    material = emission('ObjectNormal', color_node=normal_of('ShaderNodeTexCoord', 'Normal'))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.6, location=(-0.7, 0, 0.6),
                                         rotation=(math.radians(40), math.radians(-25),
                                                   math.radians(60)))
    sphere = bpy.context.object
    sphere.scale = (1.0, 0.6, 1.4)
    sphere.data.materials.append(material)
    bpy.ops.object.shade_smooth()
    tilted = plane('Tilted', 1.0, material, location=(0.8, 0, 0.6),
                   rotation=(math.radians(60), math.radians(20), math.radians(30)))
    tilted.scale = (1.5, 0.7, 1.0)
    camera((0, -4, 0.6), rotation=(math.radians(90), 0, 0), lens=35)
    return []


def transparent_shadows_scene():
    """Transparent shadows and their limit (transparent_shadow.glsl): three stacks of 0.8 m
    Transparent planes over a diffuse floor, one plane of (0.9, 0.6, 0.3) and eight and nine
    of (0.9, 0.8, 0.7), 3 cm apart from 3 m up, under a sun at 45 degrees that puts each
    stack's shadow 3 m beside it. Cycles 3.4 (Max Transparent Bounces 8) lets the light
    through the one plane and the eight tinted and stops it at the ninth. The camera looks
    straight down on the shadows and sees no plane (a camera ray through the stacks would
    meet Cycles' transparent bounce limit on the path, which memograph does not count); the
    regions are the three shadows and the lit floor between two of them."""
    world()
    plane('Floor', 16.0, diffuse('Floor', (0.8, 0.8, 0.8)))
    tinted = bpy.data.materials.new('Tinted')
    layer = bpy.data.materials.new('Layer')
    for m, color in ((tinted, (0.9, 0.6, 0.3)), (layer, (0.9, 0.8, 0.7))):
        m.use_nodes = True
        nt = m.node_tree
        nt.nodes.clear()
        o = nt.nodes.new('ShaderNodeOutputMaterial')
        nt.links.new(bsdf_node(nt, 'ShaderNodeBsdfTransparent', Color=color).outputs[0],
                     o.inputs['Surface'])
    stacks = (('one', -1.3, tinted, 1), ('eight', 0.0, layer, 8), ('nine', 1.3, layer, 9))
    for name, x, material, count in stacks:
        for k in range(count):
            plane('%s_%d' % (name, k), 0.8, material, location=(x, 0.0, 3.0 + 0.03 * k))
    # Light travelling towards -y and down: a plane h above the floor shades y in
    # [-0.4 - h, 0.4 - h], so every layer of a stack (h up to 3.24) shades y in [-3.4, -2.84].
    light('SUN', 'Sun', (0, 0, 5), rotation=(math.radians(-45), 0, 0), energy=2.0, angle=0.0)
    camera((0, -3.1, 12.0), lens=100)
    y0, y1 = -3.3, -2.95
    return [(name, [(x + dx, y, 0.0) for dx in (-0.25, 0.25) for y in (y0, y1)])
            for name, x, _, _ in stacks] + \
        [('lit', [(x, y, 0.0) for x in (-0.8, -0.5) for y in (y0, y1)])]


def leaf_card(name, color, alpha_node):
    """A Principled BSDF leaf card whose Alpha is alpha_node(nt) (a cut-out: 0 or 1)."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    p = nt.nodes['Principled BSDF']
    p.inputs['Base Color'].default_value = (*color, 1)
    p.inputs['Roughness'].default_value = 0.6
    nt.links.new(alpha_node(nt), p.inputs['Alpha'])
    return m


def thresholded_noise(nt):
    """Noise Texture Fac > 0.5: irregular holes, as an artist cuts a leaf out."""
    noise = nt.nodes.new('ShaderNodeTexNoise')
    noise.inputs['Scale'].default_value = 4.0
    noise.inputs['Detail'].default_value = 2.0
    cut = nt.nodes.new('ShaderNodeMath')
    cut.operation = 'GREATER_THAN'
    cut.inputs[1].default_value = 0.5
    nt.links.new(noise.outputs['Fac'], cut.inputs[0])
    return cut.outputs[0]


def checker_fac(nt):
    """Checker Texture Fac (0 or 1): a fence of square holes."""
    tex = nt.nodes.new('ShaderNodeTexChecker')
    tex.inputs['Scale'].default_value = 5.0
    return tex.outputs['Fac']


def alpha_cutout_scene():
    """Alpha (stochastic_opacity.glsl): two vertical leaf cards whose Principled Alpha is a
    cut-out (thresholded Noise, Checker), and a third card of a Principled BSDF of Alpha 0.5
    mixed with a Glossy BSDF (the exporter writes the Alpha as a Transparent lobe), before a
    blue wall over a grey floor, under a sky and a sun that casts the cards' shadows on both."""
    unbiased_glossy()
    world(color=(0.3, 0.35, 0.45), strength=0.3)
    plane('Floor', 8.0, diffuse('Floor', (0.6, 0.6, 0.6)))
    plane('Wall', 8.0, diffuse('Wall', (0.2, 0.35, 0.7)), location=(0, 1.5, 2),
          rotation=(math.radians(90), 0, 0))
    upright = (math.radians(90), 0, 0)
    plane('LeafNoise', 1.0, leaf_card('LeafNoise', (0.15, 0.5, 0.1), thresholded_noise),
          location=(-1.1, 0.9, 0.75), rotation=upright)
    plane('LeafChecker', 1.0, leaf_card('LeafChecker', (0.6, 0.4, 0.1), checker_fac),
          location=(0.0, 1.0, 0.75), rotation=upright)
    mixed = bpy.data.materials.new('MixedAlpha')
    mixed.use_nodes = True
    nt = mixed.node_tree
    nt.nodes.clear()
    p = nt.nodes.new('ShaderNodeBsdfPrincipled')
    p.inputs['Base Color'].default_value = (0.8, 0.15, 0.1, 1)
    p.inputs['Roughness'].default_value = 0.5
    p.inputs['Alpha'].default_value = 0.5
    glossy = bsdf_node(nt, 'ShaderNodeBsdfGlossy', Color=(0.8, 0.8, 0.8), Roughness=0.3)
    mix = nt.nodes.new('ShaderNodeMixShader')
    mix.inputs['Fac'].default_value = 0.3
    nt.links.new(p.outputs[0], mix.inputs[1])
    nt.links.new(glossy.outputs[0], mix.inputs[2])
    nt.links.new(mix.outputs[0], nt.nodes.new('ShaderNodeOutputMaterial').inputs['Surface'])
    plane('MixedAlpha', 1.0, mixed, location=(1.1, 0.9, 0.75), rotation=upright)
    # Light travelling towards the wall (+y) and +x, down at 35 degrees: each card's shadow
    # falls on the wall and the floor half a metre to its right.
    light('SUN', 'Sun', (0, 0, 5), rotation=(math.radians(55), 0, math.radians(-40)),
          energy=4.0, angle=0.0)
    camera((0, -3.0, 1.0), rotation=(math.radians(85), 0, 0), lens=30)
    return None


def region_boxes(regions, size):
    """Pixel boxes of regions given by four world-space corners each: the box inside their
    projection, so no pixel sees an edge."""
    from bpy_extras.object_utils import world_to_camera_view
    from mathutils import Vector
    sc = bpy.context.scene
    sc.render.resolution_x = sc.render.resolution_y = size  # the view's aspect
    sc.render.resolution_percentage = 100
    boxes = []
    for name, corners in regions:
        pts = [world_to_camera_view(sc, sc.camera, Vector(c)) for c in corners]
        xs = sorted(p.x * size for p in pts)
        ys = sorted(p.y * size for p in pts)
        # Inner box: the second smallest and second largest of the corners' coordinates.
        box = [math.ceil(xs[1]), math.ceil(ys[1]), math.floor(xs[2]) - 1,
               math.floor(ys[2]) - 1]
        boxes.append({'material': name, 'box': box})
    return boxes


def tile_boxes(tiles, size, half=0.3):
    """Pixel boxes of each tile's middle (half-width `half` m around its centre)."""
    return region_boxes([(name, [(x + dx, y + dy, 0.0) for dx in (-half, half)
                                 for dy in (-half, half)]) for name, x, y in tiles], size)


def render(out_dir, size, samples):
    render_reference_pfm(os.path.join(out_dir, 'cycles.pfm'), size, samples, max_bounces=8)


SCENES = {
    'units_point': lambda: units_scene('point'),
    'units_sun': lambda: units_scene('sun'),
    'units_spot': lambda: units_scene('spot'),
    'units_area': lambda: units_scene('area'),
    'emission': emission_scene,
    'room': room_scene,
    'principled': principled_scene,
    'principled_retro': lambda: principled_scene('retro'),
    'light_path_camera': light_path_camera_scene,
    'light_path_depth': light_path_depth_scene,
    'ao': lambda: ao_scene(local=False),
    'ao_local': lambda: ao_scene(local=True),
    'bevel': bevel_scene,
    'object_normal': object_normal_scene,
    'bsdf_room': bsdf_room_scene,
    'bsdf_normals': bsdf_normals_scene,
    'transparent_shadows': transparent_shadows_scene,
    'bsdf_glossy_filtered': lambda: bsdf_scene('glossy_ggx', filter_glossy=True),
    'alpha_cutout': alpha_cutout_scene,
}
SCENES.update({'bsdf_' + tree: (lambda tree=tree: bsdf_scene(tree)) for tree in BSDF_TREES})


def main(argv):
    p = argparse.ArgumentParser(prog='build_scene.py')
    p.add_argument('--scene', required=True, choices=sorted(SCENES))
    p.add_argument('--out', required=True)
    p.add_argument('--size', type=int, default=16)
    p.add_argument('--samples', type=int, default=256)
    p.add_argument('--no-render', action='store_true')
    args = p.parse_args(argv)
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    tiles = SCENES[args.scene]()
    bpy.context.view_layer.update()
    if tiles:
        # Principled tiles as (name, x, y); the light-path scenes' regions as (name, corners).
        boxes = (region_boxes(tiles, args.size) if len(tiles[0]) == 2
                 else tile_boxes(tiles, args.size))
        with open(os.path.join(out, 'tiles.json'), 'w') as f:
            json.dump(boxes, f, indent=1)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, args.scene + '.blend'))
    if not args.no_render:
        render(out, args.size, args.samples)
    from memograph_export import exporter, scene as scene_export
    export_dir = os.path.join(out, 'export')
    result = exporter.export_materials(list(bpy.data.materials), export_dir)
    for material, node, message in result.warnings:
        print('warning: %s: %s: %s' % (material, node, message), file=sys.stderr)
    if result.errors:
        print('error: %s' % result.errors, file=sys.stderr)
        return 1
    _, _, warnings = scene_export.export_scene(export_dir, result.names)
    for message in warnings:
        print('warning: scene: %s' % message, file=sys.stderr)
    print('build_scene: %s written to %s' % (args.scene, out))
    return 0


if __name__ == '__main__':
    code = main(sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else [])
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)

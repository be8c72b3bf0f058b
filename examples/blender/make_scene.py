"""The Blender scene example: a small room with procedural materials, lit by a
point light, a sun, an area light and an emissive panel under a dim blue world.

    blender -b --factory-startup --python examples/blender/make_scene.py -- OUT.blend [--reference OUT.pfm --size N --samples S]

writes the .blend (and, with --reference, Cycles' render of it as a PFM with the reference
settings of tools/blender/cycles_reference.py, for the side-by-side in docs/). Then (docs/guide/blender.md, "Example: a whole scene"):

    memograph import-blender OUT.blend --out DIR --scene
    memograph render DIR/scene.gltf --materials DIR --size 96x96 --frames 64 --out memograph.pfm
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tools',
                                'blender'))
from cycles_reference import render_reference_pfm  # noqa: E402 (needs the path above)


def material(name, shader, inputs, texture=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    s = nt.nodes.new(shader)
    for k, v in inputs.items():
        s.inputs[k].default_value = v
    out = nt.nodes.new('ShaderNodeOutputMaterial')
    nt.links.new(s.outputs[0], out.inputs['Surface'])
    if texture:
        texture(nt, s)
    return m


def checker(nt, s):
    t = nt.nodes.new('ShaderNodeTexChecker')
    t.inputs['Color1'].default_value = (0.8, 0.78, 0.7, 1)
    t.inputs['Color2'].default_value = (0.25, 0.3, 0.4, 1)
    t.inputs['Scale'].default_value = 6.0
    nt.links.new(t.outputs['Color'], s.inputs['Color'])


def noise_wall(nt, s):
    n = nt.nodes.new('ShaderNodeTexNoise')
    n.inputs['Scale'].default_value = 4.0
    r = nt.nodes.new('ShaderNodeValToRGB')
    r.color_ramp.elements[0].color = (0.55, 0.35, 0.25, 1)
    r.color_ramp.elements[1].color = (0.85, 0.8, 0.7, 1)
    nt.links.new(n.outputs['Fac'], r.inputs['Fac'])
    nt.links.new(r.outputs['Color'], s.inputs['Base Color'])


def plane(name, size, mat, location=(0, 0, 0), rotation=(0, 0, 0), scale=(1, 1, 1)):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    o = bpy.context.object
    o.name = o.data.name = name
    o.scale = scale
    o.data.materials.append(mat)


def light(kind, name, location, rotation=(0, 0, 0), **props):
    d = bpy.data.lights.new(name, kind)
    for k, v in props.items():
        setattr(d, k, v)
    o = bpy.data.objects.new(name, d)
    o.location, o.rotation_euler = location, rotation
    bpy.context.scene.collection.objects.link(o)


def build():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    w = bpy.data.worlds.new('World')
    w.use_nodes = True
    w.node_tree.nodes['Background'].inputs['Color'].default_value = (0.2, 0.3, 0.5, 1)
    w.node_tree.nodes['Background'].inputs['Strength'].default_value = 0.3
    bpy.context.scene.world = w
    plane('Floor', 4, material('Floor', 'ShaderNodeBsdfDiffuse', {'Roughness': 0.0}, checker))
    plane('BackWall', 4, material('BackWall', 'ShaderNodeBsdfPrincipled',
                                  {'Roughness': 0.6, 'Specular': 0.3}, noise_wall),
          location=(0, 2, 2), rotation=(math.radians(90), 0, 0))
    plane('SideWall', 4, material('SideWall', 'ShaderNodeBsdfDiffuse',
                                  {'Color': (0.35, 0.55, 0.4, 1)}),
          location=(-2, 0, 2), rotation=(0, math.radians(90), 0))
    plane('Panel', 1, material('Panel', 'ShaderNodeEmission',
                               {'Color': (1.0, 0.85, 0.6, 1), 'Strength': 5.0}),
          location=(1.0, 1.98, 1.6), rotation=(math.radians(90), 0, 0), scale=(1, 0.4, 1))
    light('POINT', 'Bulb', (0.4, -0.3, 2.4), energy=120.0, shadow_soft_size=0.0)
    light('SUN', 'Sun', (0, 0, 5), rotation=(math.radians(40), 0, math.radians(-30)),
          energy=1.5, angle=0.0)
    light('AREA', 'SoftBox', (-1.0, 0.5, 3.0), energy=80.0, size=0.6)
    cam = bpy.data.cameras.new('Camera')
    cam.lens = 28
    co = bpy.data.objects.new('Camera', cam)
    co.location, co.rotation_euler = (1.2, -4.5, 1.8), (math.radians(80), 0, math.radians(12))
    bpy.context.scene.collection.objects.link(co)
    bpy.context.scene.camera = co


def main(argv):
    out = os.path.abspath(argv[0])
    size = int(argv[argv.index('--size') + 1]) if '--size' in argv else 96
    build()
    # glTF's camera gets its aspect ratio from the render resolution saved in the .blend:
    # render with memograph at the same aspect.
    sc = bpy.context.scene
    sc.render.resolution_x = sc.render.resolution_y = size
    sc.render.resolution_percentage = 100
    bpy.ops.wm.save_as_mainfile(filepath=out)
    if '--reference' in argv:
        samples = int(argv[argv.index('--samples') + 1]) if '--samples' in argv else 1024
        render_reference_pfm(os.path.abspath(argv[argv.index('--reference') + 1]), size, samples)
    return 0


if __name__ == '__main__':
    code = main(sys.argv[sys.argv.index('--') + 1:])
    sys.stdout.flush()
    os._exit(code)

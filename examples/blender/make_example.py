"""Builds examples/blender/procedural.blend (and procedural.obj/.mtl, the same objects for
`memograph render`, written by Blender's own OBJ exporter):

    blender -b --factory-startup --python examples/blender/make_example.py

Four procedural materials, the kind the issue's users ask to carry over: noise on Generated
coordinates through a colour ramp (Marble), Voronoi cells with math (Stones), a node group
of vector math and math with a Mix (Rings), a wave texture through a ramp (Floor). Material
names are identifiers, so `memograph render --materials DIR` finds DIR/<name>.mgraph by the
OBJ/MTL material name (the exporter's index.json maps other names).
"""

import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))


def material(name):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    return mat, nt, nt.nodes['Principled BSDF']


def ramp(nt, stops):
    r = nt.nodes.new('ShaderNodeValToRGB')
    elems = r.color_ramp.elements
    elems[0].position, elems[0].color = stops[0]
    elems[1].position, elems[1].color = stops[-1]
    for pos, color in stops[1:-1]:
        e = elems.new(pos)
        e.color = color
    return r


def marble():
    mat, nt, bsdf = material('Marble')
    noise = nt.nodes.new('ShaderNodeTexNoise')  # Vector unlinked: Generated coordinates
    noise.inputs['Scale'].default_value = 3.0
    noise.inputs['Detail'].default_value = 6.0
    noise.inputs['Distortion'].default_value = 1.5
    r = ramp(nt, [(0.35, (0.95, 0.94, 0.9, 1)), (0.5, (0.55, 0.55, 0.6, 1)),
                  (0.65, (0.15, 0.15, 0.18, 1))])
    r.color_ramp.interpolation = 'EASE'
    nt.links.new(noise.outputs['Fac'], r.inputs['Fac'])
    nt.links.new(r.outputs['Color'], bsdf.inputs['Base Color'])
    bsdf.inputs['Roughness'].default_value = 0.15
    return mat


def stones():
    mat, nt, bsdf = material('Stones')
    vor = nt.nodes.new('ShaderNodeTexVoronoi')
    vor.feature = 'F1'
    vor.inputs['Scale'].default_value = 6.0
    r = ramp(nt, [(0.0, (0.45, 0.4, 0.35, 1)), (0.45, (0.3, 0.27, 0.24, 1)),
                  (0.5, (0.05, 0.05, 0.05, 1))])
    nt.links.new(vor.outputs['Distance'], r.inputs['Fac'])
    tint = nt.nodes.new('ShaderNodeMix')
    tint.data_type = 'RGBA'
    tint.blend_type = 'MULTIPLY'
    tint.inputs['Factor'].default_value = 0.4
    nt.links.new(r.outputs['Color'], tint.inputs[6])     # A (colour)
    nt.links.new(vor.outputs['Color'], tint.inputs[7])   # B (colour)
    nt.links.new(tint.outputs[2], bsdf.inputs['Base Color'])
    rough = nt.nodes.new('ShaderNodeMath')
    rough.operation = 'MULTIPLY_ADD'
    rough.inputs[1].default_value = 0.6
    rough.inputs[2].default_value = 0.3
    nt.links.new(vor.outputs['Distance'], rough.inputs[0])
    nt.links.new(rough.outputs[0], bsdf.inputs['Roughness'])
    return mat


def rings_group():
    g = bpy.data.node_groups.new('RingsFactor', 'ShaderNodeTree')
    gi = g.nodes.new('NodeGroupInput')
    go = g.nodes.new('NodeGroupOutput')
    g.inputs.new('NodeSocketFloat', 'Frequency').default_value = 20.0
    g.outputs.new('NodeSocketFloat', 'Factor')
    coords = g.nodes.new('ShaderNodeTexCoord')
    centre = g.nodes.new('ShaderNodeVectorMath')
    centre.operation = 'SUBTRACT'
    centre.inputs[1].default_value = (0.5, 0.5, 0.5)
    g.links.new(coords.outputs['Generated'], centre.inputs[0])
    length = g.nodes.new('ShaderNodeVectorMath')
    length.operation = 'LENGTH'
    g.links.new(centre.outputs[0], length.inputs[0])
    mul = g.nodes.new('ShaderNodeMath')
    mul.operation = 'MULTIPLY'
    g.links.new(length.outputs['Value'], mul.inputs[0])
    g.links.new(gi.outputs['Frequency'], mul.inputs[1])
    sine = g.nodes.new('ShaderNodeMath')
    sine.operation = 'SINE'
    g.links.new(mul.outputs[0], sine.inputs[0])
    remap = g.nodes.new('ShaderNodeMath')
    remap.operation = 'MULTIPLY_ADD'
    remap.inputs[1].default_value = 0.5
    remap.inputs[2].default_value = 0.5
    g.links.new(sine.outputs[0], remap.inputs[0])
    g.links.new(remap.outputs[0], go.inputs['Factor'])
    return g


def rings(group):
    mat, nt, bsdf = material('Rings')
    node = nt.nodes.new('ShaderNodeGroup')
    node.node_tree = group
    node.inputs['Frequency'].default_value = 30.0
    mix = nt.nodes.new('ShaderNodeMix')
    mix.data_type = 'RGBA'
    mix.inputs[6].default_value = (0.6, 0.35, 0.15, 1)
    mix.inputs[7].default_value = (0.9, 0.75, 0.5, 1)
    nt.links.new(node.outputs['Factor'], mix.inputs['Factor'])
    nt.links.new(mix.outputs[2], bsdf.inputs['Base Color'])
    bsdf.inputs['Roughness'].default_value = 0.4
    return mat


def floor():
    mat, nt, bsdf = material('Floor')
    wave = nt.nodes.new('ShaderNodeTexWave')
    wave.inputs['Scale'].default_value = 2.0
    wave.inputs['Distortion'].default_value = 4.0
    r = ramp(nt, [(0.0, (0.2, 0.1, 0.05, 1)), (1.0, (0.5, 0.3, 0.15, 1))])
    nt.links.new(wave.outputs['Fac'], r.inputs['Fac'])
    nt.links.new(r.outputs['Color'], bsdf.inputs['Base Color'])
    bsdf.inputs['Roughness'].default_value = 0.6
    return mat


def main():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = 'CYCLES'
    mats = [marble(), stones(), rings(rings_group()), floor()]
    bpy.ops.mesh.primitive_plane_add(size=8, location=(0, 0, 0))
    bpy.context.active_object.name = 'Floor'
    bpy.context.active_object.data.materials.append(mats[3])
    for i, mat in enumerate(mats[:3]):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=1, location=(-2.5 + 2.5 * i, 0, 1),
                                             segments=32, ring_count=16)
        obj = bpy.context.active_object
        obj.name = mat.name + 'Sphere'
        obj.data.materials.append(mat)
        bpy.ops.object.shade_smooth()
    bpy.ops.object.camera_add(location=(0, -9, 4), rotation=(1.2, 0, 0))
    scene.camera = bpy.context.active_object
    bpy.ops.object.light_add(type='SUN', location=(3, -3, 6), rotation=(0.6, 0.2, 0.5))
    blend = os.path.join(HERE, 'procedural.blend')
    bpy.context.preferences.filepaths.save_version = 0  # no procedural.blend1 backup
    bpy.ops.wm.save_as_mainfile(filepath=blend, compress=True)
    # Blender's glTF exporter needs numpy, which Debian's Blender lacks: OBJ (+ .mtl, whose
    # material names the renderer maps to graphs) carries the meshes and UVs.
    bpy.ops.wm.obj_export(filepath=os.path.join(HERE, 'procedural.obj'), export_materials=True,
                          export_uv=True, export_normals=True)  # Y up, as the renderer
    # The camera above, in the OBJ's Y-up frame, for `memograph render --camera-path`.
    with open(os.path.join(HERE, 'procedural.camera'), 'w') as f:
        f.write('0 4 9  0 0.8 0  40\n')
    # OBJ carries no lights: a small sky for `memograph render --environment` (bright
    # above, darker towards the horizon, ground brown), equirectangular, linear.
    sky = bpy.data.images.new('sky', 32, 16, float_buffer=True)
    px = []
    for j in range(16):
        up = (j + 0.5) / 16  # row 0 is the bottom (straight down)
        for i in range(32):
            if up < 0.5:
                px += [0.25, 0.2, 0.15, 1.0]
            else:
                t = (up - 0.5) * 2.0
                px += [0.6 + 0.6 * t, 0.75 + 0.6 * t, 1.0 + 0.8 * t, 1.0]
    sky.pixels = px
    sky.filepath_raw = os.path.join(HERE, 'sky.exr')
    sky.file_format = 'OPEN_EXR'
    sky.save()
    print('make_example: wrote %s, procedural.obj, sky.exr' % blend)


if __name__ == '__main__':
    main()
    sys.stdout.flush()
    os._exit(0)

"""Builds the exporter's combined-graph and warning scenes INSIDE Blender 3.4 and bakes the
combined ones with Cycles:

    blender -b --factory-startup --python tests/blender/combined/build_scenes.py -- --out DIR

Writes DIR/combined.blend (materials C_*: node groups nested two deep, reroutes, muted
nodes, implicit conversions, packed images), DIR/cycles/<material>.pfm (Cycles Emit bake,
64x64 float, of each C_* material on the default UV plane), DIR/warnings.blend (materials
W_* that each exercise one warning path, E_* that cannot be exported) and
DIR/expected.json (what run_combined.py checks). Every C_* material ends in
Emission(Strength 1), so Cycles' Emit bake and memograph's `emission` output compare.
"""

import argparse
import array
import json
import os
import sys
from math import cos, pi, sin

import bpy

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..',
                                'tools', 'blender'))
from cycles_reference import configure_bake, write_pfm  # noqa: E402 (needs the path above)

SIZE = 64


def args():
    argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
    p = argparse.ArgumentParser()
    p.add_argument('--out', required=True)
    return p.parse_args(argv)


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    configure_bake(scene)
    return scene


def new_material(name):
    mat = bpy.data.materials.new(name)
    mat.use_fake_user = True  # saved although no object uses it
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.remove(nt.nodes['Principled BSDF'])
    return mat, nt, nt.nodes['Material Output']


def emit(nt, out, socket, into='Color'):
    em = nt.nodes.new('ShaderNodeEmission')
    em.inputs['Strength'].default_value = 1.0
    nt.links.new(socket, em.inputs[into])
    nt.links.new(em.outputs[0], out.inputs['Surface'])
    return em


def uv(nt):
    return nt.nodes.new('ShaderNodeTexCoord').outputs['UV']


def math(nt, op, a=None, b=None):
    m = nt.nodes.new('ShaderNodeMath')
    m.operation = op
    for sock, v in ((m.inputs[0], a), (m.inputs[1], b)):
        if isinstance(v, (int, float)):
            sock.default_value = v
        elif v is not None:
            nt.links.new(v, sock)
    return m


def separate_x(nt, vec):
    sep = nt.nodes.new('ShaderNodeSeparateXYZ')
    nt.links.new(vec, sep.inputs[0])
    return sep


# -- combined graphs ---------------------------------------------------------------------


def pack_as_png(img, path):
    """Saves a generated image as the PNG at `path` and packs that file into the .blend, so
    the image the exporter unpacks is the 8-bit file Cycles samples, not the float pixels."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    img.filepath_raw = path
    img.file_format = 'PNG'
    img.save()
    img.source = 'FILE'
    img.reload()
    img.pack()


def inner_group():
    g = bpy.data.node_groups.new('MG_Inner', 'ShaderNodeTree')
    gi = g.nodes.new('NodeGroupInput')
    go = g.nodes.new('NodeGroupOutput')
    g.inputs.new('NodeSocketFloat', 'X')
    g.inputs.new('NodeSocketFloat', 'Scale')
    g.inputs['Scale'].default_value = 3.0
    g.outputs.new('NodeSocketFloat', 'Y')
    m = g.nodes.new('ShaderNodeMath')
    m.operation = 'MULTIPLY'
    g.links.new(gi.outputs['X'], m.inputs[0])
    g.links.new(gi.outputs['Scale'], m.inputs[1])
    r = g.nodes.new('NodeReroute')  # a reroute inside a group
    g.links.new(m.outputs[0], r.inputs[0])
    g.links.new(r.outputs[0], go.inputs['Y'])
    return g


def outer_group(inner):
    g = bpy.data.node_groups.new('MG_Outer', 'ShaderNodeTree')
    gi = g.nodes.new('NodeGroupInput')
    go = g.nodes.new('NodeGroupOutput')
    g.inputs.new('NodeSocketVector', 'UV')
    g.outputs.new('NodeSocketColor', 'Color')
    sep = g.nodes.new('ShaderNodeSeparateXYZ')
    g.links.new(gi.outputs['UV'], sep.inputs[0])
    n1 = g.nodes.new('ShaderNodeGroup')
    n1.node_tree = inner
    n1.inputs['Scale'].default_value = 0.5  # per-instance group socket value
    n2 = g.nodes.new('ShaderNodeGroup')
    n2.node_tree = inner  # second instance keeps the interface default 3.0? set 0.25
    n2.inputs['Scale'].default_value = 0.25
    g.links.new(sep.outputs['X'], n1.inputs['X'])
    g.links.new(sep.outputs['Y'], n2.inputs['X'])
    comb = g.nodes.new('ShaderNodeCombineXYZ')
    g.links.new(n1.outputs['Y'], comb.inputs['X'])
    g.links.new(n2.outputs['Y'], comb.inputs['Y'])
    comb.inputs['Z'].default_value = 0.125
    g.links.new(comb.outputs[0], go.inputs['Color'])  # vector -> colour at the boundary
    frame = g.nodes.new('NodeFrame')  # frames are ignored
    sep.parent = frame
    return g


def build_combined(out_dir):
    expected = {}
    inner = inner_group()
    outer = outer_group(inner)

    mat, nt, out = new_material('C_groups_nested')
    grp = nt.nodes.new('ShaderNodeGroup')
    grp.node_tree = outer
    nt.links.new(uv(nt), grp.inputs['UV'])
    emit(nt, out, grp.outputs['Color'])

    mat, nt, out = new_material('C_reroutes')
    r1 = nt.nodes.new('NodeReroute')
    r2 = nt.nodes.new('NodeReroute')
    nt.links.new(uv(nt), r1.inputs[0])
    nt.links.new(r1.outputs[0], r2.inputs[0])
    emit(nt, out, r2.outputs[0])

    mat, nt, out = new_material('C_muted_math')
    sx = separate_x(nt, uv(nt))
    m = math(nt, 'ADD', sx.outputs['X'], 0.5)
    m.mute = True  # passes X through (its first input)
    m2 = math(nt, 'MULTIPLY', m.outputs[0], 0.5)
    emit(nt, out, m2.outputs[0])

    mat, nt, out = new_material('C_muted_texture')
    noise = nt.nodes.new('ShaderNodeTexNoise')
    nt.links.new(uv(nt), noise.inputs['Vector'])
    noise.mute = True  # Blender's internal link: Vector -> Color (Fac has none)
    emit(nt, out, noise.outputs['Color'])

    mat, nt, out = new_material('C_muted_texture_fac')
    noise = nt.nodes.new('ShaderNodeTexNoise')
    nt.links.new(uv(nt), noise.inputs['Vector'])
    noise.mute = True
    m = math(nt, 'ADD', noise.outputs['Fac'], 0.25)
    emit(nt, out, m.outputs[0])

    mat, nt, out = new_material('C_color_to_float')
    comb = nt.nodes.new('ShaderNodeCombineColor')
    sep = nt.nodes.new('ShaderNodeSeparateXYZ')
    nt.links.new(uv(nt), sep.inputs[0])
    nt.links.new(sep.outputs['X'], comb.inputs['Red'])
    nt.links.new(sep.outputs['Y'], comb.inputs['Green'])
    comb.inputs['Blue'].default_value = 0.7
    m = math(nt, 'MULTIPLY', comb.outputs[0], 1.0)  # colour -> float: luminance
    emit(nt, out, m.outputs[0])  # float -> colour: grey

    mat, nt, out = new_material('C_vector_to_float')
    m = math(nt, 'ADD', uv(nt), 0.0)  # vector -> float: average
    emit(nt, out, m.outputs[0])

    mat, nt, out = new_material('C_float_to_color_strength')
    sx = separate_x(nt, uv(nt))
    em = emit(nt, out, sx.outputs['X'])  # float -> colour
    nt.links.new(uv(nt), em.inputs['Strength'])  # vector -> float (average)

    for name, cs in (('C_image_srgb', 'sRGB'), ('C_image_noncolor', 'Non-Color')):
        img = bpy.data.images.new('mg_' + name, SIZE, SIZE, alpha=True)
        px = []
        for j in range(SIZE):
            for i in range(SIZE):
                # Smooth and periodic: the Cycles bake samples a fraction of a texel off the
                # centres, so a jump (and the REPEAT wrap at the edges) would show that.
                t = 2.0 * pi / SIZE
                px += [0.5 + 0.45 * sin(t * i), 0.5 + 0.45 * cos(t * j),
                       0.5 + 0.45 * sin(t * (i + j)), 1.0]
        img.pixels = px
        pack_as_png(img, os.path.join(out_dir, 'images', name + '.png'))
        img.colorspace_settings.name = cs
        mat, nt, out = new_material(name)
        tex = nt.nodes.new('ShaderNodeTexImage')
        tex.image = img  # Vector unlinked: UV
        emit(nt, out, tex.outputs['Color'])
    # Closest interpolation on pixel art: 8 x 4 texels of unrelated colours, the UV doubled
    # and shifted by whole texels (negative u and v: the floor and the repeat wrap). Every
    # bake pixel centre stays an eighth of a texel or more from a texel edge, far beyond the
    # bake's offset from the centre (docs/guide/blender.md), so the texels must match
    # exactly; linear filtering blends neighbours and misses by up to ~0.5. Opaque: with
    # Alpha unlinked Cycles gives an image's colour premultiplied, which is another matter.
    art_w, art_h = 8, 4
    img = bpy.data.images.new('mg_C_image_closest', art_w, art_h, alpha=True)
    px = []
    for j in range(art_h):
        for i in range(art_w):
            k = i + art_w * j
            px += [((k * 37) % 11) / 10.0, ((k * 53) % 7) / 6.0, ((k * 29) % 5) / 4.0, 1.0]
    img.pixels = px
    pack_as_png(img, os.path.join(out_dir, 'images', 'C_image_closest.png'))
    mat, nt, out = new_material('C_image_closest')
    scaled = nt.nodes.new('ShaderNodeVectorMath')
    scaled.operation = 'MULTIPLY_ADD'
    nt.links.new(uv(nt), scaled.inputs[0])
    scaled.inputs[1].default_value = (2.0, 2.0, 2.0)
    scaled.inputs[2].default_value = (-0.5, -0.5, 0.0)
    tex = nt.nodes.new('ShaderNodeTexImage')
    tex.image = img
    tex.interpolation = 'Closest'
    nt.links.new(scaled.outputs[0], tex.inputs['Vector'])
    emit(nt, out, tex.outputs['Color'])
    # Tables: ColorRamp and the three curve nodes, sampled from Blender's own evaluation.
    for name, interp in (('C_ramp_ease', 'EASE'), ('C_ramp_constant', 'CONSTANT'),
                         ('C_ramp_bspline', 'B_SPLINE')):
        mat, nt, out = new_material(name)
        sx = separate_x(nt, uv(nt))
        ramp = nt.nodes.new('ShaderNodeValToRGB')
        ramp.color_ramp.interpolation = interp
        el = ramp.color_ramp.elements
        el[0].position, el[0].color = 0.2, (0.9, 0.1, 0.2, 1.0)
        el[1].position, el[1].color = 0.8, (0.1, 0.5, 0.95, 0.3)
        e = el.new(0.45)
        e.color = (0.2, 0.9, 0.3, 0.6)
        nt.links.new(sx.outputs['X'], ramp.inputs['Fac'])
        emit(nt, out, ramp.outputs['Color'])
    mat, nt, out = new_material('C_ramp_alpha')
    sx = separate_x(nt, uv(nt))
    ramp = nt.nodes.new('ShaderNodeValToRGB')
    ramp.color_ramp.elements[0].color = (1, 1, 1, 0.1)
    nt.links.new(sx.outputs['X'], ramp.inputs['Fac'])
    emit(nt, out, ramp.outputs['Alpha'])

    def stretched_uv(nt, scale, offset):
        vm = nt.nodes.new('ShaderNodeVectorMath')
        vm.operation = 'MULTIPLY_ADD'
        nt.links.new(uv(nt), vm.inputs[0])
        vm.inputs[1].default_value = (scale, scale, scale)
        vm.inputs[2].default_value = (offset, offset, offset)
        return vm.outputs[0]

    for name, extend in (('C_rgb_curves', 'EXTRAPOLATED'), ('C_rgb_curves_horizontal',
                                                            'HORIZONTAL')):
        mat, nt, out = new_material(name)
        cn = nt.nodes.new('ShaderNodeRGBCurve')
        m = cn.mapping
        m.extend = extend
        m.curves[3].points.new(0.4, 0.6)  # C
        m.curves[0].points.new(0.5, 0.2)  # R
        m.curves[1].points[0].location = (0.1, 0.3)  # G starts later
        m.curves[2].points.new(0.7, 0.9)  # B
        m.update()
        cn.inputs['Fac'].default_value = 0.8
        nt.links.new(stretched_uv(nt, 1.4, -0.2), cn.inputs['Color'])  # beyond [0, 1]
        emit(nt, out, cn.outputs['Color'])
    mat, nt, out = new_material('C_vector_curves')
    cn = nt.nodes.new('ShaderNodeVectorCurve')
    m = cn.mapping
    m.curves[0].points.new(0.2, 0.7)
    m.curves[1].points.new(-0.3, -0.6)
    m.update()
    nt.links.new(stretched_uv(nt, 3.0, -1.5), cn.inputs['Vector'])  # [-1.5, 1.5]
    emit(nt, out, cn.outputs['Vector'])
    mat, nt, out = new_material('C_float_curve')
    cn = nt.nodes.new('ShaderNodeFloatCurve')
    m = cn.mapping
    # Gentle slopes: the Cycles bake samples ~1e-3 pixel off the centres, which a steep
    # extrapolated end segment would turn into a visible difference.
    m.curves[0].points[0].location = (0.0, 0.2)
    m.curves[0].points[1].location = (1.0, 0.9)
    m.curves[0].points.new(0.5, 0.65)
    m.update()
    sx = separate_x(nt, stretched_uv(nt, 1.6, -0.3))
    nt.links.new(sx.outputs['X'], cn.inputs['Value'])
    emit(nt, out, cn.outputs['Value'])

    # Shader mixing that is exact for emission: Mix and Add of two Emission shaders.
    for name, idname in (('C_mix_shader_emission', 'ShaderNodeMixShader'),
                         ('C_add_shader_emission', 'ShaderNodeAddShader')):
        mat, nt, out = new_material(name)
        s = nt.nodes.new(idname)
        e1 = nt.nodes.new('ShaderNodeEmission')
        e1.inputs['Color'].default_value = (0.9, 0.2, 0.1, 1)
        e1.inputs['Strength'].default_value = 0.5
        e2 = nt.nodes.new('ShaderNodeEmission')
        nt.links.new(uv(nt), e2.inputs['Color'])
        e2.inputs['Strength'].default_value = 0.75
        if idname == 'ShaderNodeMixShader':
            sy = separate_x(nt, uv(nt))
            nt.links.new(sy.outputs['Y'], s.inputs['Fac'])
        nt.links.new(e1.outputs[0], s.inputs[-2])
        nt.links.new(e2.outputs[0], s.inputs[-1])
        nt.links.new(s.outputs[0], out.inputs['Surface'])

    # A colour linked straight into the Material Output's Surface (Cycles: emission).
    mat, nt, out = new_material('C_color_into_surface')
    nt.links.new(uv(nt), out.inputs['Surface'])

    # Mix node data types.
    mat, nt, out = new_material('C_mix_vector_nonuniform')
    mix = nt.nodes.new('ShaderNodeMix')
    mix.data_type = 'VECTOR'
    mix.factor_mode = 'NON_UNIFORM'
    nt.links.new(uv(nt), mix.inputs['Factor_Vector'] if 'Factor_Vector' in mix.inputs
                 else mix.inputs[1])
    mix.inputs[4].default_value = (0.1, 0.2, 0.3)   # A_Vector
    mix.inputs[5].default_value = (0.9, 0.7, -0.5)  # B_Vector
    emit(nt, out, mix.outputs[1])
    mat, nt, out = new_material('C_mixrgb_legacy')
    mix = nt.nodes.new('ShaderNodeMixRGB')
    mix.blend_type = 'OVERLAY'
    mix.use_clamp = True
    nt.links.new(uv(nt), mix.inputs['Color1'])
    mix.inputs['Color2'].default_value = (0.8, 0.3, 0.6, 1)
    sx = separate_x(nt, uv(nt))
    nt.links.new(sx.outputs['Y'], mix.inputs['Fac'])
    emit(nt, out, mix.outputs[0])

    mat, nt, out = new_material('C_image_alpha')
    tex = nt.nodes.new('ShaderNodeTexImage')
    tex.image = bpy.data.images['mg_C_image_noncolor']
    emit(nt, out, tex.outputs['Alpha'])
    return expected


# -- warning paths -------------------------------------------------------------------------


def build_warnings():
    """{material: [(node label or '', message substring)]} for the warnings scene."""
    exp = {}

    mat, nt, out = new_material('W_unsupported_node')
    ies = nt.nodes.new('ShaderNodeTexIES')
    ies.name = 'IES'
    emit(nt, out, ies.outputs['Fac'])
    exp[mat.name] = [('IES', 'ShaderNodeTexIES (IES Texture) is not supported:'
                      ' its output \'Fac\' is replaced by the default value 0')]

    mat, nt, out = new_material('W_principled_uncarried')
    p = nt.nodes.new('ShaderNodeBsdfPrincipled')
    p.name = 'P'
    p.inputs['Anisotropic'].default_value = 0.5
    nt.links.new(uv(nt), p.inputs['Subsurface Radius'])  # not a warned feature
    nt.links.new(p.outputs[0], out.inputs['Surface'])
    exp[mat.name] = [('P', 'Anisotropic = 0.5 is not carried')]

    # Sheen, Clearcoat and Transmission (a linked one too) and Clearcoat Normal are carried as
    # PrincipledLayers: no warning of them, and the graph compiles for both targets (below).
    mat, nt, out = new_material('W_principled_layers')
    p = nt.nodes.new('ShaderNodeBsdfPrincipled')
    p.name = 'P'
    p.inputs['Clearcoat'].default_value = 0.5
    nt.links.new(uv(nt), p.inputs['Clearcoat Normal'])
    p.inputs['Sheen'].default_value = 0.5
    sx = separate_x(nt, uv(nt))
    nt.links.new(sx.outputs['X'], p.inputs['Transmission'])
    nt.links.new(p.outputs[0], out.inputs['Surface'])
    exp[mat.name] = []

    # Diffuse, Glossy and the transmission BSDFs alone are written exactly as lobes
    # (memograph_export/lobes.py): no warning; a Multiscatter GGX Glossy is written as GGX,
    # warned.
    for name, idname in (('W_diffuse', 'ShaderNodeBsdfDiffuse'),
                         ('W_glossy', 'ShaderNodeBsdfGlossy'),
                         ('W_glass', 'ShaderNodeBsdfGlass'),
                         ('W_refraction', 'ShaderNodeBsdfRefraction'),
                         ('W_transparent', 'ShaderNodeBsdfTransparent'),
                         ('W_translucent', 'ShaderNodeBsdfTranslucent')):
        mat, nt, out = new_material(name)
        s = nt.nodes.new(idname)
        s.name = 'S'
        nt.links.new(s.outputs[0], out.inputs['Surface'])
        exp[name] = []
    mat, nt, out = new_material('W_glossy_multiscatter')
    s = nt.nodes.new('ShaderNodeBsdfGlossy')
    s.name = 'S'
    s.distribution = 'MULTI_GGX'
    nt.links.new(s.outputs[0], out.inputs['Surface'])
    exp['W_glossy_multiscatter'] = [('S', 'Multiscatter GGX is written as single-scatter GGX')]

    shaders = [('W_other_shader', 'ShaderNodeBsdfToon', 'ShaderNodeBsdfToon is not supported')]
    for name, idname, msg in shaders:
        mat, nt, out = new_material(name)
        s = nt.nodes.new(idname)
        s.name = 'S'
        nt.links.new(s.outputs[0], out.inputs['Surface'])
        exp[name] = [('S', msg)]

    for name, idname, msg in (('W_mix_shader', 'ShaderNodeMixShader', 'Mix Shader approximated'),
                              ('W_add_shader', 'ShaderNodeAddShader', 'Add Shader approximated')):
        # With a Diffuse and an Emission the tree is exact (lobes); with a Toon BSDF, which is
        # not a lobe, the whole surface falls back to the Principled approximation.
        mat, nt, out = new_material(name)
        s = nt.nodes.new(idname)
        s.name = 'S'
        d = nt.nodes.new('ShaderNodeBsdfToon')
        d.name = 'D'
        e = nt.nodes.new('ShaderNodeEmission')
        nt.links.new(d.outputs[0], s.inputs[-2])
        nt.links.new(e.outputs[0], s.inputs[-1])
        nt.links.new(s.outputs[0], out.inputs['Surface'])
        exp[name] = [('S', msg), ('D', 'ShaderNodeBsdfToon is not supported')]
    # A Transparent BSDF beside a shader that is not a lobe keeps the Principled fallback
    # (opacity 0), warned.
    mat, nt, out = new_material('W_transparent_with_toon')
    s = nt.nodes.new('ShaderNodeAddShader')
    s.name = 'S'
    t = nt.nodes.new('ShaderNodeBsdfTransparent')
    t.name = 'T'
    d = nt.nodes.new('ShaderNodeBsdfToon')
    d.name = 'D'
    nt.links.new(t.outputs[0], s.inputs[0])
    nt.links.new(d.outputs[0], s.inputs[1])
    nt.links.new(s.outputs[0], out.inputs['Surface'])
    exp[mat.name] = [('S', 'Add Shader approximated'), ('T', 'Transparent BSDF approximated'),
                     ('D', 'ShaderNodeBsdfToon is not supported')]

    mat, nt, out = new_material('W_image_modes')
    tex = nt.nodes.new('ShaderNodeTexImage')
    tex.name = 'T'
    tex.image = bpy.data.images.new('mg_modes', 4, 4)
    tex.image.pack()
    tex.interpolation = 'Linear'
    tex.extension = 'EXTEND'
    tex.projection = 'SPHERE'  # carried (ImageProjection): no warning
    tex.image.colorspace_settings.name = 'Filmic Log'
    emit(nt, out, tex.outputs['Color'])
    exp[mat.name] = [('T', 'colour space Filmic Log is not carried')]

    mat, nt, out = new_material('W_image_missing')
    tex = nt.nodes.new('ShaderNodeTexImage')
    tex.name = 'T'
    emit(nt, out, tex.outputs['Color'])
    exp[mat.name] = [('T', 'Image Texture without an image')]

    mat, nt, out = new_material('W_image_file_missing')
    tex = nt.nodes.new('ShaderNodeTexImage')
    tex.name = 'T'
    img = bpy.data.images.new('mg_gone', 4, 4)
    img.source = 'FILE'
    img.filepath = '/nonexistent/memograph_gone.png'
    tex.image = img
    emit(nt, out, tex.outputs['Color'])
    exp[mat.name] = [('T', 'is missing: the texture is not carried')]

    mat, nt, out = new_material('W_volume_displacement')
    e = nt.nodes.new('ShaderNodeEmission')
    nt.links.new(e.outputs[0], out.inputs['Surface'])
    v = nt.nodes.new('ShaderNodeVolumePrincipled')
    nt.links.new(v.outputs[0], out.inputs['Volume'])
    d = nt.nodes.new('ShaderNodeDisplacement')
    nt.links.new(d.outputs[0], out.inputs['Displacement'])
    exp[mat.name] = [('Material Output', 'Volume is linked but not carried'),
                     ('Material Output', 'Displacement is linked but not carried')]

    mat, nt, out = new_material('W_surface_unlinked')
    exp[mat.name] = [('Material Output', 'Surface is not linked')]

    mat = bpy.data.materials.new('W_no_nodes')
    mat.use_fake_user = True
    mat.use_nodes = False
    exp[mat.name] = [('', 'material does not use nodes')]

    mat, nt, out = new_material('W_mixrgb_alpha')
    mix = nt.nodes.new('ShaderNodeMixRGB')
    mix.name = 'M'
    mix.use_alpha = True
    emit(nt, out, mix.outputs[0])
    exp[mat.name] = [('M', 'Use Alpha" is not carried')]

    mat, nt, out = new_material('W_value_into_shader')
    sx = separate_x(nt, uv(nt))
    nt.links.new(sx.outputs['X'], out.inputs['Surface'])
    exp[mat.name] = [('', 'value is linked into a shader socket')]

    # Cannot be exported: no Material Output at all.
    mat, nt, out = new_material('E_no_output')
    nt.nodes.remove(out)
    return exp


def bake_all(out_dir):
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_plane_add(size=2, location=(0, 0, 0))
    plane = bpy.context.active_object
    plane.select_set(True)
    bpy.context.view_layer.objects.active = plane
    img = bpy.data.images.new('memograph_bake', SIZE, SIZE, alpha=False, float_buffer=True)
    img.colorspace_settings.name = 'Linear'
    os.makedirs(os.path.join(out_dir, 'cycles'), exist_ok=True)
    for mat in sorted((m for m in bpy.data.materials if m.name.startswith('C_')),
                      key=lambda m: m.name):
        plane.data.materials.clear()
        plane.data.materials.append(mat)
        nt = mat.node_tree
        tex = nt.nodes.new('ShaderNodeTexImage')
        tex.image = img
        nt.nodes.active = tex
        tex.select = True
        bpy.ops.object.bake(type='EMIT', margin=0)
        buf = array.array('f', [0.0]) * (SIZE * SIZE * 4)
        img.pixels.foreach_get(buf)
        write_pfm(os.path.join(out_dir, 'cycles', mat.name + '.pfm'), SIZE, SIZE, buf)
        nt.nodes.remove(tex)  # not part of the material that gets exported
    bpy.data.objects.remove(plane, do_unlink=True)
    bpy.data.images.remove(img)


def main():
    a = args()
    out_dir = os.path.abspath(a.out)
    os.makedirs(out_dir, exist_ok=True)
    reset()
    build_combined(out_dir)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out_dir, 'combined.blend'), compress=False)
    bake_all(out_dir)
    reset()
    exp = build_warnings()
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out_dir, 'warnings.blend'), compress=True)
    with open(os.path.join(out_dir, 'expected.json'), 'w') as f:
        json.dump({'warnings': exp, 'version': bpy.app.version_string}, f, indent=1,
                  sort_keys=True)
    print('build_scenes: done')


if __name__ == '__main__':
    try:
        main()
    except Exception:
        import traceback
        traceback.print_exc()
        sys.stdout.flush()
        os._exit(1)
    sys.stdout.flush()
    os._exit(0)

"""Scene export: the whole scene through Blender's own glTF exporter (io_scene_gltf2), plus a
sidecar with what glTF drops. See docs/guide/blender.md ("Scene export") for the sidecar format.

    export_scene(out_dir, names, context) -> (gltf_path, sidecar_path, warnings)

`names` maps Blender material names to the exported .mgraph material names (the exporter's
`result.names`); the glTF's materials are renamed to them, so that
`memograph render DIR/scene.gltf --materials DIR` finds DIR/<name>.mgraph for each.
"""

import json
import os

import bpy

SIDECAR_VERSION = 1
WATTS_TO_LUMENS = 683.0  # io_scene_gltf2's PBR_WATTS_TO_LUMENS (lighting mode SPEC)


def _fmt(x):
    return '%.9g' % float(x)


def _line(*parts):
    return ' '.join(_fmt(p) if isinstance(p, (int, float)) else str(p) for p in parts)


def _texspace(mesh):
    loc = getattr(mesh, 'texspace_location', None)
    size = getattr(mesh, 'texspace_size', None)
    if loc is None:  # Blender 4.x names
        loc = getattr(mesh, 'texture_space_location', None)
        size = getattr(mesh, 'texture_space_size', None)
    return loc, size


def _world_lines(scene, out_dir, warnings):
    world = scene.world
    if world is None:
        return [_line('world', 'color', 0, 0, 0, 'strength', 1)]
    if not world.use_nodes or world.node_tree is None:
        c = world.color
        return [_line('world', 'color', c[0], c[1], c[2], 'strength', 1)]
    out = None
    for node in world.node_tree.nodes:
        if node.bl_idname == 'ShaderNodeOutputWorld' and node.is_active_output:
            out = node
    if out is None or not out.inputs['Surface'].is_linked:
        return [_line('world', 'color', 0, 0, 0, 'strength', 1)]
    bg = out.inputs['Surface'].links[0].from_node
    if bg.bl_idname != 'ShaderNodeBackground':
        warnings.append('world: the surface is a %s, not a Background: black world' % bg.bl_idname)
        return [_line('world', 'color', 0, 0, 0, 'strength', 1)]
    strength = bg.inputs['Strength'].default_value
    if bg.inputs['Strength'].is_linked:
        warnings.append('world: Strength is linked; its unlinked value %.4g is used' % strength)
    col = bg.inputs['Color']
    if col.is_linked:
        src = col.links[0].from_node
        if src.bl_idname == 'ShaderNodeTexEnvironment' and src.image is not None:
            from . import exporter
            assets = exporter.Assets(out_dir)
            msgs = []
            rel = assets.image_path(src.image, lambda m: msgs.append(m))
            warnings.extend('world: %s' % m for m in msgs)
            if src.inputs['Vector'].is_linked:
                warnings.append('world: the environment texture\'s Vector is linked; ignored')
            return [_line('world', 'image', 'strength', strength, rel)]
        warnings.append('world: Color is linked to a %s; its unlinked value is used'
                        % src.bl_idname)
    c = col.default_value
    return [_line('world', 'color', c[0], c[1], c[2], 'strength', strength)]


def _value(sock, fallback):
    """An input's unlinked value, or `fallback` where it is linked (a texture)."""
    if sock is None:
        return fallback
    if sock.is_linked:
        return fallback
    v = sock.default_value
    return tuple(v)[:3] if hasattr(v, '__len__') else float(v)


def emission_estimate(material):
    """The emitted radiance of a material and whether it is exact: (rgb, exact), or None for
    no emission. Exact when the Emission colour and strength are both unlinked (the graph
    then emits colour x strength everywhere, which memograph's light sampling takes as it
    is: `emitter_constant`); otherwise a rough value for choosing among lights by power
    (`emitter`: memograph evaluates the graph's real emission at each light sample)."""
    if material is None or not material.use_nodes or material.node_tree is None:
        return None
    out = None
    for node in material.node_tree.nodes:
        if node.bl_idname == 'ShaderNodeOutputMaterial' and node.is_active_output:
            out = node
    if out is None or not out.inputs['Surface'].is_linked:
        return None
    shader = out.inputs['Surface'].links[0].from_node
    if shader.bl_idname == 'ShaderNodeEmission':
        color, strength = shader.inputs.get('Color'), shader.inputs.get('Strength')
    elif shader.bl_idname == 'ShaderNodeBsdfPrincipled':
        color, strength = shader.inputs.get('Emission'), shader.inputs.get('Emission Strength')
    else:
        return None  # mixes and groups: found by BSDF rays only
    c = _value(color, (1.0, 1.0, 1.0))
    s = _value(strength, 1.0)
    raw = [float(x) * s for x in c]
    est = [max(0.0, x) for x in raw]
    exact = (color is not None and not color.is_linked and strength is not None
             and not strength.is_linked and est == raw)
    return (est, exact) if max(est) > 0.0 else None


def sidecar_lines(scene, objects, out_dir, warnings, names=None):
    lines = ['memograph-blender-scene %d' % SIDECAR_VERSION,
             '# written by tools/blender/memograph_export/scene.py; format: docs/guide/blender.md',
             'up z',
             _line('lighting', 'SPEC', WATTS_TO_LUMENS)]
    if scene.camera is not None:
        lines.append(_line('camera', scene.camera.name))
    # Cycles' Filter Glossy (Render Properties > Light Paths > Caustics; 1 in a new file): the
    # renderer blurs glossy lobes after low-pdf bounces as Cycles does (docs/design/closures.md).
    cycles = getattr(scene, 'cycles', None)
    if cycles is not None:
        lines.append(_line('render', 'filter_glossy', float(cycles.blur_glossy)))
    lines += _world_lines(scene, out_dir, warnings)
    for mat in bpy.data.materials:
        if names and mat.name in names:
            found = emission_estimate(mat)
            if found is not None:
                est, exact = found
                lines.append(_line('emitter_constant' if exact else 'emitter', est[0], est[1],
                                   est[2], names[mat.name]))
    seen_meshes = set()
    for obj in objects:
        if obj.type == 'MESH' and obj.data is not None and obj.data.name not in seen_meshes:
            seen_meshes.add(obj.data.name)
            loc, size = _texspace(obj.data)
            if loc is not None:
                lines.append(_line('texspace', loc[0], loc[1], loc[2], size[0], size[1], size[2],
                                   obj.data.name))
        if obj.type == 'LIGHT' and obj.data.type == 'AREA':
            light = obj.data
            sx = light.size
            sy = light.size_y if light.shape in ('RECTANGLE', 'ELLIPSE') else light.size
            if light.shape in ('DISK', 'ELLIPSE'):
                warnings.append('light %s: a %s area light becomes a quad of the same area'
                                % (obj.name, light.shape.lower()))
            if light.use_nodes:
                warnings.append('light %s: its node tree is ignored (colour x power)' % obj.name)
            m = obj.matrix_world
            flat = [m[r][c] for c in range(4) for r in range(4)]  # column-major
            lines.append(_line('area', light.shape, sx, sy, light.energy, light.color[0],
                               light.color[1], light.color[2], *flat, obj.name))
        elif obj.type == 'LIGHT' and obj.data.type in ('POINT', 'SPOT'):
            if obj.data.shadow_soft_size > 0:
                warnings.append('light %s: radius %.3g is rendered as a point'
                                % (obj.name, obj.data.shadow_soft_size))
        elif obj.type == 'LIGHT' and obj.data.type == 'SUN' and obj.data.angle > 0.0:
            warnings.append('light %s: angle %.3g is rendered as a hard sun'
                            % (obj.name, obj.data.angle))
    return lines


def export_scene(out_dir, names, context=None, use_selection=False, gltf_name='scene.gltf'):
    context = context or bpy.context
    scene = context.scene
    warnings = []
    os.makedirs(out_dir, exist_ok=True)
    gltf_path = os.path.join(out_dir, gltf_name)
    # Z-up (export_yup off): every object space stays Blender's, so Object and Generated
    # coordinates match Cycles; memograph rotates the root to its y-up on import.
    bpy.ops.export_scene.gltf(filepath=gltf_path, export_format='GLTF_SEPARATE',
                              export_yup=False, export_apply=True, export_cameras=True,
                              export_lights=True, export_materials='EXPORT',
                              export_texcoords=True, export_normals=True,
                              use_selection=use_selection, convert_lighting_mode='SPEC')
    with open(gltf_path) as f:
        doc = json.load(f)
    # glTF's materials keep Blender's names: rename them to the .mgraph names.
    for mat in doc.get('materials', []):
        if mat.get('name') in names:
            mat['name'] = names[mat['name']]
    from . import exporter
    exporter.write_atomic(gltf_path, json.dumps(doc, indent=1) + '\n')
    objects = context.selected_objects if use_selection else scene.objects
    objects = [o for o in objects if o.visible_get()]
    lines = sidecar_lines(scene, objects, out_dir, warnings, names)
    sidecar = os.path.splitext(gltf_path)[0] + '.memograph'
    exporter.write_atomic(sidecar, '\n'.join(lines) + '\n')
    return gltf_path, sidecar, warnings

"""Builds and bakes the per-node comparison cases INSIDE Blender (3.4), one process for all.

    blender -b --factory-startup --python tests/blender/build_and_bake.py -- \
        --out DIR [--cases noise,math] [--match REGEX] [--no-export]

For each case (cases/<family>.py): one material on the default UV plane (size 2 at the
origin: object = world coordinates (2u-1, 2v-1, 0)) holding
    drivers -> node under test -> chosen output -> Emission (Strength 1) -> Material Output.
Cycles bakes it (EMIT, 64x64 float, 1 sample, no denoising) to DIR/cycles/<case>.pfm, then the
exporter add-on writes it to DIR/export/<case>/ (its own folder, so the files it wrote are
known). DIR/cases.json records what happened per case; compare_nodes.py reads it.

Drivers are the simplest supported nodes because they are exported too: Texture Coordinate,
Separate XYZ, Math MULTIPLY_ADD and Vector Math MULTIPLY_ADD.
"""
import argparse
import array
import inspect
import json
import os
import shutil
import struct
import sys
import time
import traceback

import bpy

sys.dont_write_bytecode = True  # no __pycache__ in the source tree

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(REPO, 'tools', 'blender'))

import cases as case_registry  # noqa: E402
from cycles_reference import configure_bake, write_pfm  # noqa: E402

SIZE = 64
COORD_OUTPUT = {'uv3': 'UV', 'uv': 'UV', 'generated': 'Generated', 'object': 'Object',
                'normal': 'Normal'}


def parse_args():
    argv = sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []
    p = argparse.ArgumentParser(prog='build_and_bake.py')
    p.add_argument('--out', required=True)
    p.add_argument('--cases', default='', help='comma-separated families (default: all)')
    p.add_argument('--match', default=None, help='regex on case names')
    p.add_argument('--no-export', action='store_true', help='bake with Cycles only')
    p.add_argument('--keep-bake-offset', action='store_true', help='do not cancel the bake '
                   'rasterizer\'s sub-texel offset (see BAKE_OFFSET_TEXELS)')
    p.add_argument('--exr', action='store_true', help='also save each Cycles bake as '
                   'DIR/cycles/<case>.exr (float EXR, for viewing; the comparison reads PFM)')
    return p.parse_args(argv)


def save_exr(scene, img, path):
    """A copy of the baked image as 32-bit float EXR, leaving the bake image untouched."""
    settings = scene.render.image_settings
    settings.file_format = 'OPEN_EXR'
    settings.color_depth = '32'
    settings.color_mode = 'RGB'
    img.save_render(path, scene=scene)


# Blender's bake rasterizer (3.4) samples texel (i, j) at ((i + 0.5 + 0.001) / W,
# (j + 0.5 + 0.002) / H), not at its centre (measured with Separate XYZ of UV: u is 1.56e-5
# and v 3.1e-5 high on every texel at 64x64). memograph bake samples the exact centres. The
# offset is harmless for smooth outputs but flips texels that lie on a discontinuity (u == v
# in a comparison, a modulo edge, a pole), so it is cancelled at the source: the plane's
# vertices move back by the offset (positions, Object coordinates) with its texture space
# pinned to the unmoved plane (Generated), and the shaders read a second, render-active UV
# map moved back by the offset, while the bake still rasterizes with the active UV map.
BAKE_OFFSET_TEXELS = (0.001, 0.002)


def cancel_bake_offset(me):
    du, dv = BAKE_OFFSET_TEXELS[0] / SIZE, BAKE_OFFSET_TEXELS[1] / SIZE
    loc, size = tuple(me.texspace_location), tuple(me.texspace_size)
    me.use_auto_texspace = False
    for v in me.vertices:  # object = world coordinates (2u-1, 2v-1, 0): d/du = 2
        v.co.x -= 2.0 * du
        v.co.y -= 2.0 * dv
    me.texspace_location = loc
    me.texspace_size = size
    bake_uv = me.uv_layers.active
    shader_uv = me.uv_layers.new(name='ShaderUV')
    for src, dst in zip(bake_uv.data, shader_uv.data):
        dst.uv = (src.uv[0] - du, src.uv[1] - dv)
    shader_uv.active_render = True
    me.uv_layers.active = bake_uv
    me.update()


def set_plane_normal(me, flat_coords, normal):
    """Tilts the plane's mesh about the origin so that its (flat) face normal is `normal`, or
    puts it back flat (`flat_coords`, its vertices as set up) for None. The face normal is
    what Cycles shades with, exact to float rounding; custom normals would be stored as
    16-bit angles (about 1e-4 rad off). The UV maps stay: the bake still covers the image."""
    from mathutils import Vector
    rotation = None
    if normal is not None:
        rotation = Vector((0.0, 0.0, 1.0)).rotation_difference(
            Vector(normal).normalized()).to_matrix()
    for v, co in zip(me.vertices, flat_coords):
        v.co = co if rotation is None else rotation @ co
    me.update()


def setup_scene(texel_fix=True):
    scene = bpy.context.scene
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    configure_bake(scene)
    bpy.ops.mesh.primitive_plane_add(size=2, location=(0, 0, 0))
    plane = bpy.context.active_object
    plane.name = 'BakePlane'
    if texel_fix:
        cancel_bake_offset(plane.data)
    plane.select_set(True)
    bpy.context.view_layer.objects.active = plane
    img = bpy.data.images.new('memograph_bake', SIZE, SIZE, alpha=False, float_buffer=True)
    img.colorspace_settings.name = 'Linear'
    return scene, plane, img


def find_socket(sockets, key, what):
    """By identifier among enabled sockets, then by name among enabled ones, then by
    identifier among all (props may not have been meant to enable it: report that)."""
    for s in sockets:
        if s.enabled and s.identifier == key:
            return s
    for s in sockets:
        if s.enabled and s.name == key:
            return s
    avail = ['%s (%s)' % (s.identifier, s.name) for s in sockets if s.enabled]
    raise KeyError('no enabled %s socket %r; enabled: %s' % (what, key, ', '.join(avail)))


def set_prop(node, path, value):
    obj = node
    parts = path.split('.')
    for part in parts[:-1]:
        obj = getattr(obj, part)
    setattr(obj, parts[-1], value)


def set_input(sock, value):
    if sock.type == 'RGBA':
        if isinstance(value, (int, float)):
            value = (value, value, value, 1.0)
        elif len(value) == 3:
            value = tuple(value) + (1.0,)
    elif sock.type == 'VECTOR' and isinstance(value, (int, float)):
        value = (value,) * len(sock.default_value)
    sock.default_value = value


def vec3(x):
    return (float(x),) * 3 if isinstance(x, (int, float)) else tuple(float(c) for c in x)


def make_driver(nt, spec, cache, x):
    """The output socket that drives an input per pixel (see cases/case.py)."""
    links = nt.links
    if 'texcoord' not in cache:
        tc = nt.nodes.new('ShaderNodeTexCoord')
        tc.location = (x - 600, 0)
        cache['texcoord'] = tc
    tc = cache['texcoord']
    src, a, b = (spec, None, None) if isinstance(spec, str) else spec
    if src in COORD_OUTPUT:
        out = tc.outputs[COORD_OUTPUT[src]]
        if a is None:
            return out
        vm = nt.nodes.new('ShaderNodeVectorMath')
        vm.operation = 'MULTIPLY_ADD'
        vm.location = (x - 400, -200 * len(cache))
        links.new(out, vm.inputs[0])
        vm.inputs[1].default_value = vec3(a)   # scale
        vm.inputs[2].default_value = vec3(b)   # offset
        cache['vm%d' % len(cache)] = vm
        return vm.outputs['Vector']
    # scalar u / v: Separate XYZ of UV (+ Math MULTIPLY_ADD: u * scale + offset)
    if 'sep' not in cache:
        sep = nt.nodes.new('ShaderNodeSeparateXYZ')
        sep.location = (x - 400, 200)
        links.new(tc.outputs['UV'], sep.inputs['Vector'])
        cache['sep'] = sep
    out = cache['sep'].outputs['X' if src == 'u' else 'Y']
    if a is None:
        return out
    m = nt.nodes.new('ShaderNodeMath')
    m.operation = 'MULTIPLY_ADD'
    m.use_clamp = False
    m.location = (x - 200, -200 * len(cache))
    links.new(out, m.inputs[0])
    m.inputs[1].default_value = float(b)   # scale
    m.inputs[2].default_value = float(a)   # offset
    cache['m%d' % len(cache)] = m
    return m.outputs['Value']


def build_material(case, img):
    mat = bpy.data.materials.new(case.name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new('ShaderNodeOutputMaterial')
    out.location = (600, 0)
    emit = nt.nodes.new('ShaderNodeEmission')
    emit.location = (400, 0)
    emit.inputs['Strength'].default_value = 1.0
    nt.links.new(emit.outputs['Emission'], out.inputs['Surface'])
    node = nt.nodes.new(case.node)
    node.location = (0, 0)
    for k, v in case.props.items():
        set_prop(node, k, v)
    if case.extra is not None:
        nparams = len(inspect.signature(case.extra).parameters)
        case.extra(*((node, nt) if nparams >= 2 else (node,)))
    for k, v in case.inputs.items():
        set_input(find_socket(node.inputs, k, 'input'), v)
    cache = {}
    for k, spec in case.drive.items():
        nt.links.new(make_driver(nt, spec, cache, 0), find_socket(node.inputs, k, 'input'))
    if case.output is None:
        osock = next(s for s in node.outputs if s.enabled)
    else:
        osock = find_socket(node.outputs, case.output, 'output')
    nt.links.new(osock, emit.inputs['Color'])
    bake_node = nt.nodes.new('ShaderNodeTexImage')
    bake_node.image = img
    bake_node.location = (400, 300)
    for n in nt.nodes:
        n.select = False
    bake_node.select = True
    nt.nodes.active = bake_node
    return mat, bake_node, osock


def load_exporter():
    try:
        from memograph_export import exporter  # tools/blender/memograph_export
        if not hasattr(exporter, 'export_materials'):
            return None, 'memograph_export.exporter has no export_materials yet'
        return exporter, None
    except Exception as e:
        return None, 'exporter add-on not importable (%s: %s)' % (type(e).__name__, e)


def main():
    args = parse_args()
    out_dir = os.path.abspath(args.out)
    for sub in ('cycles', 'export'):
        os.makedirs(os.path.join(out_dir, sub), exist_ok=True)
    families = [f for f in args.cases.split(',') if f] or None
    family_errors = []
    selected = case_registry.all_cases(families, args.match, errors=family_errors)
    for fam, msg in family_errors:
        print('build_and_bake: case family %s failed to load: %s' % (fam, msg))
    exporter, export_skip = (None, 'export disabled (--no-export)') if args.no_export \
        else load_exporter()
    if export_skip:
        print('build_and_bake: NOT exporting: %s; put hand-written graphs in a folder and pass '
              'compare_nodes.py --handwritten DIR' % export_skip)
    export_table = None
    if exporter is not None:
        try:  # the node table once, not per material
            from memograph_export import writers
            export_table = writers.build_table()
        except Exception as e:
            print('build_and_bake: writers.build_table() failed (%s: %s); the exporter builds '
                  'its own per material' % (type(e).__name__, e))
    scene, plane, img = setup_scene(not args.keep_bake_offset)
    flat_coords = [v.co.copy() for v in plane.data.vertices]
    records = []
    t_start = time.time()
    buf = array.array('f', [0.0]) * (SIZE * SIZE * 4)
    for i, case in enumerate(selected):
        rec = {'name': case.name, 'family': case.family, 'node': case.node,
               'mode': case.mode(), 'output': case.output or '', 'kind': case.kind,
               'tolerance': case.max_error, 'note': case.note}
        t0 = time.time()
        try:
            mat, bake_node, osock = build_material(case, img)
            rec['output'], rec['output_type'] = osock.identifier, osock.type
            plane.data.materials.clear()
            plane.data.materials.append(mat)
            set_plane_normal(plane.data, flat_coords, case.normal)
            if case.normal is not None:
                rec['normal'] = list(plane.data.polygons[0].normal)
            bpy.ops.object.bake(type='EMIT', margin=0, use_clear=True)
            img.pixels.foreach_get(buf)
            path = os.path.join(out_dir, 'cycles', case.name + '.pfm')
            write_pfm(path, SIZE, SIZE, buf)
            rec['cycles'] = path
            if args.exr:
                save_exr(scene, img, os.path.join(out_dir, 'cycles', case.name + '.exr'))
            # The bake target is not part of the material: take it out before exporting.
            mat.node_tree.nodes.remove(bake_node)
        except Exception as e:
            rec['error'] = 'Blender build/bake failed: %s: %s' % (type(e).__name__, e)
            print('build_and_bake: %s: %s' % (case.name, rec['error']))
            records.append(rec)
            continue
        if exporter is None:
            rec['export'] = 'skipped: ' + export_skip
        else:
            edir = os.path.join(out_dir, 'export', case.name)
            shutil.rmtree(edir, ignore_errors=True)  # no stale graph from an earlier run
            os.makedirs(edir)
            try:
                res = exporter.export_materials([mat], edir, table=export_table)
                errors = [e for e in getattr(res, 'errors', [])]
                files = [f for f in getattr(res, 'files', []) if f.endswith('.mgraph')]
                if not files:  # older API without .files: what it wrote
                    files = [os.path.join(edir, f) for f in sorted(os.listdir(edir))
                             if f.endswith('.mgraph')]
                rec['export_warnings'] = [
                    ': '.join(str(x) for x in w[1:]) if isinstance(w, tuple) else str(w)
                    for w in getattr(res, 'warnings', [])]  # (material, node, message)
                if errors:
                    rec['export'] = 'error: ' + '; '.join(
                        '%s: %s' % e if isinstance(e, tuple) else str(e) for e in errors)
                elif len(files) != 1:
                    rec['export'] = 'error: exporter wrote %d .mgraph files' % len(files)
                else:
                    rec['export'] = 'ok'
                    rec['mgraph'] = files[0]
            except Exception as e:
                rec['export'] = 'error: %s: %s' % (type(e).__name__, e)
                print('build_and_bake: %s: export raised:' % case.name)
                traceback.print_exc(file=sys.stdout)
        rec['seconds'] = round(time.time() - t0, 4)
        records.append(rec)
        if exporter is not None and rec.get('export') != 'ok':
            print('build_and_bake: %s: export %s' % (case.name, rec.get('export')))
    meta = {'blender': bpy.app.version_string, 'size': SIZE,
            'seconds': round(time.time() - t_start, 3), 'export_skipped': export_skip,
            'family_errors': family_errors, 'cases': records}
    with open(os.path.join(out_dir, 'cases.json'), 'w') as f:
        json.dump(meta, f, indent=1)
    print('build_and_bake: %d cases in %.1fs -> %s' % (len(records), meta['seconds'], out_dir))


try:
    main()
except SystemExit as e:
    sys.stdout.flush()
    os._exit(e.code if isinstance(e.code, int) else 1)
except Exception:
    traceback.print_exc()
    sys.stdout.flush()
    os._exit(1)
sys.stdout.flush()
os._exit(0)

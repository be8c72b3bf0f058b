"""Headless memograph export:

    blender -b scene.blend --python tools/blender/export_memograph.py -- --out DIR
            [--materials NAME...]

Writes one .mgraph per material into DIR (see docs/guide/blender.md). Warnings go to stderr as
`warning: <material>: <node>: <message>`. Exit status: 0 written (warnings allowed), 1 a
material could not be exported or a named material does not exist, 2 bad arguments.
The add-on package is imported from beside this script (tools/blender/memograph_export,
or the installed copy next to the memograph binary).
"""

import argparse
import os
import sys


def main(argv):
    parser = argparse.ArgumentParser(prog='export_memograph.py',
                                     description='Export Blender materials to .mgraph')
    parser.add_argument('--out', required=True, help='output folder')
    parser.add_argument('--materials', nargs='+', metavar='NAME',
                        help='only these materials (default: all)')
    parser.add_argument('--quiet', action='store_true', help='no summary on stdout')
    parser.add_argument('--scene', action='store_true',
                        help='also write DIR/scene.gltf (Blender\'s glTF exporter) and its '
                             'sidecar DIR/scene.memograph (docs/guide/blender.md, Scene export)')
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:
        return 2 if exc.code else 0
    here = os.path.dirname(os.path.abspath(__file__))
    sys.dont_write_bytecode = True  # no __pycache__ beside the (source tree's) add-on
    if here not in sys.path:
        sys.path.insert(0, here)
    import bpy
    from memograph_export import exporter
    from memograph_export.spec import SpecError

    if not bpy.data.filepath:
        print('error: no .blend file was opened (pass it before --python)', file=sys.stderr)
        return 1
    blend_name = os.path.basename(bpy.data.filepath)
    printed = []  # every warning line, so that the summary counts what was printed

    def warn(line):
        printed.append(line)
        print('warning: ' + line, file=sys.stderr)

    newer = exporter.newer_file_warning(tuple(bpy.data.version), tuple(bpy.app.version_file),
                                        bpy.app.version_string)
    if newer:
        warn('%s: %s' % (blend_name, newer))
    mats = list(bpy.data.materials)
    if args.materials:
        by_name = {m.name: m for m in mats}
        missing = [n for n in args.materials if n not in by_name]
        if missing:
            print('error: no material named %s in %s (it has: %s)'
                  % (', '.join(repr(n) for n in missing), bpy.data.filepath,
                     ', '.join(sorted(by_name)) or 'none'), file=sys.stderr)
            return 1
        mats = [by_name[n] for n in args.materials]
    elif not mats:
        # Not an error: the file is valid and the (empty) export is complete; a batch over
        # many files should not fail on one without materials. But never silently.
        warn('%s: the file has no materials: only an empty index.json is written'
             % blend_name)
    try:
        result = exporter.export_materials(mats, os.path.abspath(args.out))
    except SpecError as exc:
        print('error: the exporter\'s node specs are broken: %s' % exc, file=sys.stderr)
        return 1
    except OSError as exc:
        print('error: %s' % exc, file=sys.stderr)
        return 1
    for material, node, message in result.warnings:
        warn('%s: %s: %s' % (material, node or '(material)', message))
    for material, message in result.errors:
        print('error: %s: %s' % (material, message), file=sys.stderr)
    if args.scene and not result.errors:
        from memograph_export import scene as scene_export
        try:
            gltf, sidecar, scene_warnings = scene_export.export_scene(
                os.path.abspath(args.out), result.names)
        except Exception as exc:
            print('error: the scene export failed: %s' % exc, file=sys.stderr)
            return 1
        for message in scene_warnings:
            warn('scene: %s' % message)
        if not args.quiet:
            print('memograph: wrote %s and %s' % (gltf, sidecar))
    if not args.quiet:
        if result.errors:
            # No "wrote ... to DIR": run by import-blender, a failed export leaves DIR as it
            # was (the files went to a staging folder that is removed).
            print('memograph: the export failed: %d error(s), %d warning(s); %d other '
                  'material(s) exported' % (len(result.errors), len(printed),
                                            len(result.files)))
        else:
            print('memograph: wrote %d material(s) to %s, %d warning(s), 0 error(s)'
                  % (len(result.files), args.out, len(printed)))
    return 1 if result.errors else 0


def _argv():
    return sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else []


if __name__ == '__main__':
    code = main(_argv())
    sys.stdout.flush()
    sys.stderr.flush()
    # Blender ignores a script's SystemExit status in some versions; os._exit is reliable.
    os._exit(code)

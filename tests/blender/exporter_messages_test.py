#!/usr/bin/env python3
"""The headless exporter's messages say what happened (ctest blender_exporter_messages).

Each check builds a small .blend with Blender 3.4, runs tools/blender/export_memograph.py on
it and checks the exit status, the warnings and the summary line:

  - a file saved by a newer Blender (its header's version raised) is reported as such;
  - a material linked from a library that is missing names that library, not "does not use
    nodes";
  - a file without materials says so (exit 0: an empty export is complete and correct);
  - a material that fails makes the summary say the export failed, not "wrote N material(s)
    to DIR" (import-blender then leaves DIR unchanged);
  - the summary's warning count is the number of warning lines printed, scene warnings
    included;
  - a Principled BSDF's Sheen, Clearcoat and Transmission (with their tint, roughness and IOR
    sockets, a linked one too) export as PrincipledLayers without a warning (a linked
    Clearcoat Normal, carried too, is in combined/build_scenes.py).

Fails (never skips) without Blender 3.4. Plain python3, standard library only.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SCRIPT = os.path.join(REPO, 'tools', 'blender', 'export_memograph.py')
BLENDER = shutil.which('blender')

# Builds the fixtures inside Blender: argv after '--' is KIND OUT.blend [LIB.blend].
BUILD = r'''
import bpy, sys
kind, out = sys.argv[sys.argv.index('--') + 1:][:2]
for m in list(bpy.data.materials):
    bpy.data.materials.remove(m)
def emission(name):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    m.use_fake_user = True  # saved even where no object uses it
    return m
if kind == 'plain':
    emission('Plain')
elif kind == 'empty':
    pass
elif kind == 'library':
    lib = sys.argv[sys.argv.index('--') + 3]
    emission('Shared')
    bpy.data.libraries.write(lib, {bpy.data.materials['Shared']})
    bpy.data.materials.remove(bpy.data.materials['Shared'])
    with bpy.data.libraries.load(lib, link=True) as (src, dst):
        dst.materials = ['Shared']
    bpy.data.objects['Cube'].data.materials.append(bpy.data.materials['Shared'])
elif kind == 'broken':
    emission('Good')
    bad = emission('Bad')
    bad.node_tree.nodes.remove(bad.node_tree.nodes['Material Output'])
elif kind == 'scene_warnings':
    m = emission('Lit')
    m.node_tree.nodes.new('ShaderNodeTexSky')  # unused: no warning
    tex = m.node_tree.nodes.new('ShaderNodeTexImage')  # no image: one material warning
    m.node_tree.links.new(tex.outputs['Color'],
                          m.node_tree.nodes['Principled BSDF'].inputs['Base Color'])
    bpy.data.objects['Cube'].data.materials.append(m)
    bpy.data.lights['Light'].shadow_soft_size = 0.5  # a light radius: a scene warning
    sun = bpy.data.lights.new('Sun', 'SUN')
    sun.angle = 0.2  # a sun angle: another scene warning
    bpy.context.scene.collection.objects.link(bpy.data.objects.new('Sun', sun))
elif kind == 'layers':
    m = emission('Layered')
    p = m.node_tree.nodes['Principled BSDF']
    for name, value in (('Sheen', 0.5), ('Sheen Tint', 0.25), ('Clearcoat', 0.75),
                        ('Transmission', 0.6), ('Transmission Roughness', 0.2), ('IOR', 1.33)):
        p.inputs[name].default_value = value
    v = m.node_tree.nodes.new('ShaderNodeValue')
    v.outputs[0].default_value = 0.125
    m.node_tree.links.new(v.outputs[0], p.inputs['Clearcoat Roughness'])
bpy.ops.wm.save_as_mainfile(filepath=out, compress=False)
'''


def blender_env():
    # Debian's Blender takes its Python home from the first python3 on PATH: a pyenv
    # interpreter there hides Debian's numpy, which the glTF exporter (--scene) imports.
    env = dict(os.environ)
    own_bin = os.path.dirname(os.path.realpath(sys.executable))
    env['PATH'] = os.pathsep.join(
        d for d in env.get('PATH', '').split(os.pathsep)
        if d and os.path.realpath(d) != own_bin and '.pyenv' not in d)
    return env


def blender(args):
    return subprocess.run([BLENDER, '-b', '--factory-startup'] + args, capture_output=True,
                          text=True, timeout=120, env=blender_env())


class ExporterMessages(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if BLENDER is None:
            raise RuntimeError('Blender 3.4 not found on PATH: run tools/setup.sh')
        cls.tmp = tempfile.mkdtemp(prefix='mg_exporter_messages_')
        cls.build_py = os.path.join(cls.tmp, 'build.py')
        with open(cls.build_py, 'w') as f:
            f.write(BUILD)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def build(self, kind, *extra):
        path = os.path.join(self.tmp, kind + '.blend')
        r = blender(['--python', self.build_py, '--', kind, path] + list(extra))
        self.assertTrue(os.path.exists(path), r.stdout + r.stderr)
        return path

    def export(self, blend, *args):
        out = os.path.join(self.tmp, 'out_' + os.path.basename(blend))
        r = blender([blend, '--python-exit-code', '1', '--python', SCRIPT, '--', '--out', out]
                    + list(args))
        return r.returncode, r.stdout, r.stderr

    def summary(self, stdout):
        lines = [l for l in stdout.splitlines() if l.startswith('memograph: ')]
        self.assertTrue(lines, stdout)
        return lines[-1]

    def test_newer_blender_file_is_reported(self):
        blend = self.build('plain')
        with open(blend, 'r+b') as f:
            head = f.read(12)
            self.assertTrue(head.startswith(b'BLENDER') and head[9:12].isdigit(), head)
            f.seek(9)
            f.write(b'309')  # as if saved by Blender 3.9
        code, out, err = self.export(blend)
        self.assertEqual(code, 0, err)
        self.assertRegex(err, r'warning: .*saved by Blender 3\.9.*newer than the running '
                              r'Blender 3\.4.*results may differ')
        self.assertIn('1 warning(s)', self.summary(out))

    def test_missing_library_is_named(self):
        lib = os.path.join(self.tmp, 'shared_lib.blend')
        blend = self.build('library', lib)
        os.remove(lib)
        code, out, err = self.export(blend)
        self.assertNotIn('does not use nodes', err)
        self.assertRegex(err, r"warning: Shared: .*library .*shared_lib\.blend.* is missing")
        self.assertEqual(code, 0, err)

    def test_no_materials_is_said(self):
        blend = self.build('empty')
        code, out, err = self.export(blend)
        self.assertEqual(code, 0, err)
        self.assertRegex(err, r'warning: .*has no materials')
        self.assertIn('0 material(s)', self.summary(out))

    def test_failed_export_summary_does_not_claim_written(self):
        blend = self.build('broken')
        code, out, err = self.export(blend)
        self.assertEqual(code, 1, err)
        self.assertIn('error: Bad: no Material Output', err)
        line = self.summary(out)
        self.assertNotRegex(line, r'wrote \d+ material')
        self.assertRegex(line, r'export failed.*1 error')

    def test_summary_counts_printed_warnings(self):
        blend = self.build('scene_warnings')
        code, out, err = self.export(blend, '--scene')
        self.assertEqual(code, 0, err)
        printed = len(re.findall(r'^warning: ', err, re.M))
        self.assertGreaterEqual(printed, 2, err)
        m = re.search(r'(\d+) warning\(s\)', self.summary(out))
        self.assertIsNotNone(m, out)
        self.assertEqual(int(m.group(1)), printed, out + err)

    def test_principled_layers_export_without_a_warning(self):
        blend = self.build('layers')
        code, out, err = self.export(blend)
        self.assertEqual(code, 0, err)
        self.assertNotIn('warning:', err)
        with open(os.path.join(self.tmp, 'out_layers.blend', 'Layered.mgraph')) as f:
            text = f.read()
        self.assertRegex(text, r'PrincipledLayers BaseColor=\([^)]*\) Metallic=0 '
                               r'Roughness=0\.5 Sheen=0\.5 SheenTint=0\.25 Clearcoat=0\.75 '
                               r'ClearcoatRoughness<\d+ Transmission=0\.6\d* '
                               r'TransmissionRoughness=0\.2\d* IOR=1\.33')


if __name__ == '__main__':
    unittest.main(verbosity=2)

#!/usr/bin/env python3
"""Checks the comparison harness itself, without Blender: every case family imports, case
names are unique valid material names, drives are well formed, and the PFM reader and the
comparison agree with build_and_bake.py's PFM layout."""
import os
import struct
import sys
import tempfile
import unittest

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import cases  # noqa: E402
import compare_nodes  # noqa: E402
from cases.case import Case, drive_ok  # noqa: E402


class CasesTest(unittest.TestCase):
    def test_every_family_loads_with_unique_names(self):
        errors = []
        found = cases.all_cases(errors=errors)
        self.assertEqual(errors, [])
        self.assertIn('smoke', cases.family_names())
        self.assertGreater(len(found), 0)
        names = [c.name for c in found]
        self.assertEqual(len(names), len(set(names)))

    def test_filters(self):
        smoke = cases.all_cases(['smoke'], match='separate')
        self.assertTrue(smoke)
        self.assertTrue(all(c.family == 'smoke' and 'separate' in c.name for c in smoke))

    def test_validation(self):
        with self.assertRaises(ValueError):
            Case(name='bad__name', node='ShaderNodeMath').validate()
        with self.assertRaises(ValueError):
            Case(name='x', node='ShaderNodeMath', drive={'Value': ('w', 0, 1)}).validate()
        self.assertTrue(drive_ok(('uv3', (1, 2, 3), 0.5)))
        self.assertTrue(drive_ok(('u', -1.0, 2.0)))
        self.assertFalse(drive_ok(('u', (1, 2, 3), 2.0)))
        self.assertEqual(Case(name='n', node='X', kind='noise').max_error, 1e-2)
        self.assertEqual(Case(name='a', node='X').max_error, 1e-3)
        self.assertEqual(Case(name='t', node='X', tolerance=5e-3).max_error, 5e-3)


class PfmTest(unittest.TestCase):
    def write(self, path, w, h, f, big=False):
        vals = [c for j in range(h) for i in range(w) for c in f(i, j)]
        with open(path, 'wb') as out:
            out.write(b'PF\n%d %d\n%s\n' % (w, h, b'1.0' if big else b'-1.0'))
            out.write(struct.pack(('>' if big else '<') + '%df' % len(vals), *vals))

    def test_read_and_compare(self):
        with tempfile.TemporaryDirectory() as d:
            a, b = os.path.join(d, 'a.pfm'), os.path.join(d, 'b.pfm')
            self.write(a, 4, 3, lambda i, j: (i, j, 0.5))
            self.write(b, 4, 3, lambda i, j: (i, j + (0.25 if (i, j) == (2, 1) else 0), 0.5),
                       big=True)
            w, h, ra = compare_nodes.read_pfm(a)
            _, _, rb = compare_nodes.read_pfm(b)
            self.assertEqual((w, h), (4, 3))
            self.assertEqual(ra[1][2], (2.0, 1.0, 0.5))  # row 1 from the bottom, column 2
            maxe, meane, worst, nan = compare_nodes.compare(ra, rb)
            self.assertEqual(maxe, [0.0, 0.25, 0.0])
            self.assertEqual(worst[1], (2, 1))
            self.assertAlmostEqual(meane[1], 0.25 / 12)
            self.assertFalse(nan)

    def test_material_name(self):
        with tempfile.TemporaryDirectory() as d:
            g = os.path.join(d, 'stem.mgraph')
            with open(g, 'w') as f:
                f.write('# c\nFloat1Constant 1 Out>0;\n')
            self.assertEqual(compare_nodes.material_name(g), 'stem')
            with open(g, 'w') as f:
                f.write('material Named;\nFloat1Constant 1 Out>0;\n')
            self.assertEqual(compare_nodes.material_name(g), 'Named')


if __name__ == '__main__':
    unittest.main()

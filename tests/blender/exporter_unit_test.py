#!/usr/bin/env python3
"""Unit tests of the Blender exporter's pure-Python parts with fake node objects (no Blender):
the spec loader, literals and names, graph walking (groups, reroutes, muted nodes, invalid
and disabled links, implicit conversions) and the Blender 4.x branches that cannot run on
the Blender 3.4 installed here (Principled v2 sockets, 4.1 Noise types, 4.x-only inputs).

    python3 tests/blender/exporter_unit_test.py
"""

import os
import re
import sys
import tempfile
import textwrap
import unittest

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, '..', '..', 'tools', 'blender'))

from memograph_export import compat, exporter, graph, mgraph, shaders, writers  # noqa: E402
from memograph_export.spec import NodeSpec, SpecError, load_specs  # noqa: E402

# -- fakes ------------------------------------------------------------------------------


class Sock:
    def __init__(self, identifier, type_, default=None, name=None, enabled=True,
                 is_output=False):
        self.identifier = identifier
        self.name = name or identifier
        self.type = type_
        if default is not None:
            self.default_value = default
        self.enabled = enabled
        self.is_output = is_output
        self.node = None

    def as_pointer(self):
        return id(self)


class Prop:
    def __init__(self, type_, items=()):
        self.type = type_
        self.enum_items = [type('I', (), {'identifier': i})() for i in items]


class RNA:
    def __init__(self, props):
        self.properties = props


class Node:
    def __init__(self, bl_idname, name, inputs=(), outputs=(), mute=False, props=None,
                 rna=None, **attrs):
        self.bl_idname = bl_idname
        self.bl_label = bl_idname
        self.name = name
        self.inputs = list(inputs)
        self.outputs = list(outputs)
        for s in self.outputs:
            s.is_output = True
        for s in self.inputs + self.outputs:
            s.node = self
        self.mute = mute
        self.internal_links = []
        self.bl_rna = RNA(rna or {})
        for k, v in (props or {}).items():
            setattr(self, k, v)
        for k, v in attrs.items():
            setattr(self, k, v)


class ILink:
    def __init__(self, from_socket, to_socket):
        self.from_socket = from_socket
        self.to_socket = to_socket


class NLink:
    def __init__(self, a, b, valid=True, muted=False):
        self.from_node, self.from_socket = a.node, a
        self.to_node, self.to_socket = b.node, b
        self.is_valid = valid
        self.is_muted = muted


class Tree:
    def __init__(self):
        self.nodes = []
        self.links = []

    def add(self, node):
        self.nodes.append(node)
        return node

    def link(self, a, b, **kw):
        self.links.append(NLink(a, b, **kw))


class Material:
    def __init__(self, name, tree):
        self.name = name
        self.node_tree = tree
        self.use_nodes = True


def output_node(tree):
    return tree.add(Node('ShaderNodeOutputMaterial', 'Material Output',
                         [Sock('Surface', 'SHADER'), Sock('Volume', 'SHADER'),
                          Sock('Displacement', 'VECTOR', (0, 0, 0))],
                         target='ALL', is_active_output=True))


def emission(tree, name='Emission'):
    return tree.add(Node('ShaderNodeEmission', name,
                         [Sock('Color', 'RGBA', (1, 1, 1, 1)), Sock('Strength', 'VALUE', 1.0)],
                         [Sock('Emission', 'SHADER')]))


def math_node(name, a=0.5, mute=False):
    n = Node('ShaderNodeMath', name,
             [Sock('Value', 'VALUE', a), Sock('Value_001', 'VALUE', 0.5),
              Sock('Value_002', 'VALUE', 0.5, enabled=False)],
             [Sock('Value', 'VALUE', 0.0)], mute=mute,
             rna={'operation': Prop('ENUM', ['ADD', 'SUBTRACT', 'MULTIPLY'])},
             operation='MULTIPLY', use_clamp=False)
    n.internal_links = [ILink(n.inputs[0], n.outputs[0])]
    return n


MATH_SPEC = {'ShaderNodeMath': NodeSpec('Math', {'Value': 'A', 'Value_001': 'B',
                                                 'Value_002': 'C'},
                                        {'Value': 'Value'}, props={'operation': 'Operation'})}


def export(mats, table=None):
    out = tempfile.mkdtemp(prefix='mgexp')
    if table is None:
        table = writers.build_table(dict(MATH_SPEC))
    result = exporter.export_materials(mats, out, table=table)
    texts = []
    for f in result.files:
        with open(f, encoding='utf-8') as fh:
            texts.append(fh.read())
    return result, texts


def body(text):
    return [l for l in text.splitlines() if l and not l.startswith('#')]


# -- tests ------------------------------------------------------------------------------


class NodeSupportTableTest(unittest.TestCase):
    """docs/guide/nodes.md's table of Blender nodes (tools/blender/node_support_table.py)
    names every node type the exporter writes, with the status its map gives."""

    def test_table_lists_every_known_node_type(self):
        import re
        doc = os.path.join(HERE, '..', '..', 'docs', 'guide', 'nodes.md')
        with open(doc) as f:
            text = f.read()
        begin = text.index('<!-- blender-node-table: begin')
        end = text.index('<!-- blender-node-table: end -->')
        rows = {}
        for line in text[begin:end].splitlines():
            m = re.match(r'\| [^|]+ \| [^|]+ \| `(\w+)` \| ([a-z ]+) \|', line)
            if m:
                rows[m.group(1)] = m.group(2)
        known = set(writers.build_table()) | set(shaders.SHADER_WRITERS)
        missing = sorted(known - set(rows))
        self.assertEqual(missing, [], 'node types the exporter writes that the table lacks; '
                         'regenerate it (tools/blender/node_support_table.py)')
        wrong = sorted(t for t in known if rows[t] == 'not supported')
        self.assertEqual(wrong, [], 'written by the exporter but listed as not supported')
        unknown = sorted(t for t, status in rows.items()
                         if status != 'not supported' and t not in known
                         and t != 'ShaderNodeOutputMaterial'
                         and not t.startswith('ShaderNodeBsdf')
                         and t not in ('ShaderNodeSubsurfaceScattering',
                                       'ShaderNodeBackground'))
        self.assertEqual(unknown, [], 'listed as handled, but the exporter has no writer')


class SpecLoaderTest(unittest.TestCase):
    def make_pkg(self, files):
        root = tempfile.mkdtemp(prefix='mgspec')
        pkg = os.path.join(root, 'fakespecs_%d' % id(files))
        os.makedirs(pkg)
        open(os.path.join(pkg, '__init__.py'), 'w').close()
        for name, text in files.items():
            with open(os.path.join(pkg, name), 'w') as f:
                f.write(textwrap.dedent(text))
        sys.path.insert(0, root)
        return os.path.basename(pkg)

    def test_merges_modules(self):
        pkg = self.make_pkg({
            'a.py': "from memograph_export.spec import NodeSpec\n"
                    "NODES = {'ShaderNodeA': NodeSpec('A', {}, {})}\n",
            'b.py': "from memograph_export.spec import NodeSpec\n"
                    "NODES = {'ShaderNodeB': NodeSpec(lambda n: 'B', {'X': 'X'}, {})}\n"})
        specs = load_specs(pkg)
        self.assertEqual(sorted(specs), ['ShaderNodeA', 'ShaderNodeB'])

    def test_duplicate_is_an_error(self):
        pkg = self.make_pkg({
            'a.py': "from memograph_export.spec import NodeSpec\n"
                    "NODES = {'ShaderNodeA': NodeSpec('A', {}, {})}\n",
            'b.py': "from memograph_export.spec import NodeSpec\n"
                    "NODES = {'ShaderNodeA': NodeSpec('A2', {}, {})}\n"})
        with self.assertRaisesRegex(SpecError, 'defined twice'):
            load_specs(pkg)

    def test_bad_spec(self):
        with self.assertRaises(SpecError):
            NodeSpec('A', {}, {}, implicit_vector='nonsense')
        with self.assertRaises(SpecError):
            NodeSpec(3, {}, {})

    def test_custom_writer_conflict(self):
        with self.assertRaisesRegex(SpecError, 'custom writer'):
            writers.build_table({'ShaderNodeValToRGB': NodeSpec('ColorRamp', {}, {})})

    def test_real_specs_load(self):
        specs = load_specs()  # every family file in the tree must import and not collide
        writers.build_table(specs)


class LiteralTest(unittest.TestCase):
    def test_numbers(self):
        self.assertEqual(mgraph.format_number(0.1), '0.100000001')
        self.assertEqual(mgraph.format_number(-0.0), '0')
        self.assertEqual(mgraph.format_number(float('inf')), '3.40282347e+38')
        self.assertEqual(mgraph.format_number(2.0), '2')

    def test_names(self):
        self.assertEqual(mgraph.sanitize_identifier('My Mat.001'), 'My_Mat_001')
        self.assertEqual(mgraph.sanitize_identifier('a__b'), 'a_b')
        self.assertEqual(mgraph.sanitize_identifier('1x'), 'M1x')
        self.assertEqual(mgraph.sanitize_identifier('***'), 'Material')
        names = exporter.unique_names([Material('a b', None), Material('a.b', None)])
        self.assertEqual(names, {'a b': 'a_b', 'a.b': 'a_b_2'})

    def test_table(self):
        text = mgraph.format_literal(mgraph.Literal([0.5] * 1024, 'table'))
        self.assertTrue(text.startswith('[') and text.endswith(']'))
        self.assertEqual(len(text.replace('[', ' ').replace(']', ' ').split()), 1024)


class GraphTest(unittest.TestCase):
    def test_reroute_mute_group_conversions(self):
        # Material: Value(0.25) -> reroute -> muted Math -> Group[ inner Math x ] ->
        # Emission.Strength; a colour -> Emission.Color through an RGB node.
        inner = Tree()
        gin = inner.add(Node('NodeGroupInput', 'Group Input', [],
                             [Sock('Input_1', 'VALUE', 0.0), Sock('Input_2', 'RGBA')]))
        gout = inner.add(Node('NodeGroupOutput', 'Group Output',
                              [Sock('Output_1', 'VALUE', 0.0), Sock('Output_2', 'VALUE', 0.0)],
                              is_active_output=True))
        m_in = inner.add(math_node('Inner Math'))
        inner.link(gin.outputs[0], m_in.inputs[0])
        inner.link(m_in.outputs[0], gout.inputs[0])
        inner.link(gin.outputs[1], gout.inputs[1])  # colour into a float group output

        tree = Tree()
        out = output_node(tree)
        em = emission(tree)
        val = tree.add(Node('ShaderNodeValue', 'Value', [], [Sock('Value', 'VALUE', 0.25)]))
        rr = tree.add(Node('NodeReroute', 'Reroute', [Sock('Input', 'VALUE')],
                           [Sock('Output', 'VALUE')]))
        muted = tree.add(math_node('Muted Math', mute=True))
        group = tree.add(Node('ShaderNodeGroup', 'Group',
                              [Sock('Input_1', 'VALUE', 0.0),
                               Sock('Input_2', 'RGBA', (0.2, 0.4, 0.6, 1.0))],
                              [Sock('Output_1', 'VALUE'), Sock('Output_2', 'VALUE')],
                              node_tree=inner))
        vec = tree.add(Node('ShaderNodeCombineXYZ', 'Combine', [], [Sock('Vector', 'VECTOR')]))
        m2 = tree.add(math_node('Averaged'))
        tree.link(val.outputs[0], rr.inputs[0])
        tree.link(rr.outputs[0], muted.inputs[0])
        tree.link(muted.outputs[0], group.inputs[0])
        tree.link(group.outputs[0], m2.inputs[1])
        tree.link(vec.outputs[0], m2.inputs[0])          # vector -> float: average
        tree.link(m2.outputs[0], em.inputs[1])
        tree.link(group.outputs[1], em.inputs[0])         # colour -> float -> colour
        tree.link(em.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        lines = body(text)
        self.assertEqual(lines[0], 'material Mat;')
        joined = '\n'.join(lines)
        # The muted Math and the reroute vanish; the Value node has no writer here, so its
        # output becomes its default 0.25 and the inner Math reads it directly.
        self.assertIn('Math A=0.25 B=0.5 Operation=2 Value>2;', joined)
        self.assertEqual(joined.count('Math '), 2)
        self.assertIn('VectorAverage Vector=(0, 0, 0) Value>', joined)  # CombineXYZ unknown
        self.assertIn('RGBToBW Color=(0.200000003, 0.400000006, 0.600000024) Val>', joined)
        self.assertIn('EmissionOutput Color<', joined)
        self.assertIn('BaseColorOutput In=(0, 0, 0);', joined)
        msgs = [w[2] for w in result.warnings]
        self.assertTrue(any('ShaderNodeValue' in m and '0.25' in m for m in msgs), msgs)
        self.assertTrue(any('ShaderNodeCombineXYZ' in m for m in msgs), msgs)
        labels = {w[1] for w in result.warnings}
        self.assertIn('Value', labels)

    def test_invalid_disabled_and_muted_links(self):
        tree = Tree()
        out = output_node(tree)
        em = emission(tree)
        m = tree.add(math_node('M', a=0.75))
        m2 = tree.add(math_node('M2', a=0.125))
        tree.link(m.outputs[0], em.inputs[1], valid=False)      # ignored
        tree.link(m2.outputs[0], m.inputs[2])                   # to a disabled socket
        tree.link(m2.outputs[0], em.inputs[0], muted=True)      # muted link
        tree.link(em.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertNotIn('Math', text)
        self.assertIn('EmissionOutput Color=(1, 1, 1) Strength=1;', text)

    def test_muted_output_without_internal_link(self):
        tree = Tree()
        out = output_node(tree)
        em = emission(tree)
        m = tree.add(math_node('M', mute=True))
        m.internal_links = []
        tree.link(m.outputs[0], em.inputs[1])
        tree.link(em.outputs[0], out.inputs[0])
        _, (text,) = export([Material('Mat', tree)])
        self.assertIn('Strength=1;', text)  # the consumer's own value

    def test_deterministic(self):
        tree = Tree()
        out = output_node(tree)
        em = emission(tree)
        m = tree.add(math_node('M'))
        tree.link(m.outputs[0], em.inputs[1])
        tree.link(m.outputs[0], em.inputs[0])
        tree.link(em.outputs[0], out.inputs[0])
        _, (a,) = export([Material('Mat', tree)])
        _, (b,) = export([Material('Mat', tree)])
        self.assertEqual(a, b)
        self.assertEqual(a.count('Math '), 1)

    def test_no_output_node_is_an_error(self):
        tree = Tree()
        emission(tree)
        result, texts = export([Material('Mat', tree)])
        self.assertEqual(texts, [])
        self.assertIn('no Material Output', result.errors[0][1])


def principled_v2(tree):
    """A Blender 4.x Principled BSDF (v2 socket names)."""
    names = [('Base Color', 'RGBA', (0.8, 0.8, 0.8, 1)), ('Metallic', 'VALUE', 0.0),
             ('Roughness', 'VALUE', 0.5), ('IOR', 'VALUE', 1.5), ('Alpha', 'VALUE', 1.0),
             ('Normal', 'VECTOR', (0, 0, 0)), ('Subsurface Weight', 'VALUE', 0.0),
             ('Specular IOR Level', 'VALUE', 0.5), ('Specular Tint', 'RGBA', (1, 1, 1, 1)),
             ('Coat Weight', 'VALUE', 0.3), ('Sheen Weight', 'VALUE', 0.0),
             ('Emission Color', 'RGBA', (1, 0.5, 0, 1)), ('Emission Strength', 'VALUE', 2.0),
             ('Transmission Weight', 'VALUE', 0.0)]
    return tree.add(Node('ShaderNodeBsdfPrincipled', 'Principled BSDF',
                         [Sock(n, t, d) for n, t, d in names], [Sock('BSDF', 'SHADER')]))


def principled_v1(tree, tint=0.0, distribution='GGX'):
    """A Blender 3.x Principled BSDF (v1 socket names; the subset the exporter reads)."""
    names = [('Base Color', 'RGBA', (0.8, 0.3, 0.1, 1)), ('Subsurface', 'VALUE', 0.0),
             ('Metallic', 'VALUE', 0.25), ('Specular', 'VALUE', 0.7),
             ('Specular Tint', 'VALUE', tint), ('Roughness', 'VALUE', 0.4),
             ('Anisotropic', 'VALUE', 0.0), ('Sheen', 'VALUE', 0.0),
             ('Clearcoat', 'VALUE', 0.0), ('Transmission', 'VALUE', 0.0),
             ('Sheen Tint', 'VALUE', 0.5), ('Clearcoat Roughness', 'VALUE', 0.03),
             ('Emission', 'RGBA', (0, 0, 0, 1)), ('Emission Strength', 'VALUE', 1.0),
             ('Alpha', 'VALUE', 1.0), ('Normal', 'VECTOR', (0, 0, 0)),
             ('Clearcoat Normal', 'VECTOR', (0, 0, 0)), ('Tangent', 'VECTOR', (0, 0, 0)),
             ('IOR', 'VALUE', 1.45), ('Transmission Roughness', 'VALUE', 0.0)]
    return tree.add(Node('ShaderNodeBsdfPrincipled', 'Principled BSDF',
                         [Sock(n, t, d) for n, t, d in names], [Sock('BSDF', 'SHADER')],
                         distribution=distribution))


class PrincipledTest(unittest.TestCase):
    def test_v1_carries_specular_tint_and_cycles_weighting(self):
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree, tint=0.6)
        tree.link(p.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('PrincipledOutput BaseColor=(0.800000012, 0.300000012, 0.100000001) '
                      'Metallic=0.25 Roughness=0.400000006 Specular=0.699999988 '
                      'Emission=(0, 0, 0) EmissionStrength=1 Alpha=1 '
                      'SpecularTint=0.600000024 CyclesPrincipled=1;', text)
        self.assertEqual(result.warnings, [])  # Specular Tint is carried: no warning

    def test_v1_linked_tint_and_uncarried_features(self):
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree, distribution='MULTI_GGX')
        m = tree.add(math_node('M'))
        tree.link(m.outputs[0], p.inputs[4])  # Specular Tint
        p.inputs[6].default_value = 0.5  # Anisotropic
        tree.link(p.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('Math A=0.5 B=0.5 Operation=2 Value>0;', text)
        self.assertIn('SpecularTint<0 CyclesPrincipled=1;', text)
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertNotIn('Specular Tint', msgs)
        self.assertIn('Anisotropic = 0.5 is not carried', msgs)
        self.assertIn('Multiscatter GGX is written as single-scatter GGX', msgs)
        self.assertNotIn('PrincipledLayers', text)  # no sheen, clearcoat, transmission: no lobes

    def test_v1_sheen_and_clearcoat_are_carried_as_layers(self):
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree)
        p.inputs[7].default_value = 0.5  # Sheen
        p.inputs[8].default_value = 0.75  # Clearcoat
        p.inputs[10].default_value = 0.25  # Sheen Tint
        m = tree.add(math_node('M'))
        tree.link(m.outputs[0], p.inputs[11])  # Clearcoat Roughness
        tree.link(p.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('PrincipledLayers BaseColor=(0.800000012, 0.300000012, 0.100000001) '
                      'Metallic=0.25 Roughness=0.400000006 Sheen=0.5 SheenTint=0.25 '
                      'Clearcoat=0.75 ClearcoatRoughness<0 Transmission=0 '
                      'TransmissionRoughness=0 IOR=1.45000005;', text)
        self.assertEqual(result.warnings, [])  # Sheen, Clearcoat and their sockets: carried

    def test_v1_clearcoat_normal_is_carried(self):
        # Clearcoat Normal linked: PrincipledLayers' ClearcoatNormal, no warning. Unlinked
        # under a linked Normal: the interpolated normal (Cycles' sd->N), not the bumped one.
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree)
        p.inputs[8].default_value = 1.0  # Clearcoat
        bump = tree.add(Node('ShaderNodeMath', 'N', [], [Sock('Vector', 'VECTOR', (0, 0, 1))]))
        coat = tree.add(Node('ShaderNodeMath', 'C', [], [Sock('Vector', 'VECTOR', (0, 1, 0))]))
        tree.link(coat.outputs[0], p.inputs[16])  # Clearcoat Normal
        tree.link(p.outputs[0], out.inputs[0])
        table = writers.build_table({'ShaderNodeMath': NodeSpec(
            'NormalInput', {}, {'Vector': 'Out'})})
        result, (text,) = export([Material('Coat', tree)], table)
        self.assertIn('Clearcoat=1 ClearcoatRoughness=0.0299999993 Transmission=0 '
                      'TransmissionRoughness=0 IOR=1.45000005 ClearcoatNormal<0;', text)
        self.assertNotIn('NormalOutput', text)
        self.assertEqual(result.warnings, [])
        tree.links = [l for l in tree.links if l.to_socket is not p.inputs[16]]
        tree.link(bump.outputs[0], p.inputs[15])  # Normal
        result, (text,) = export([Material('Bumped', tree)], table)
        self.assertIn('NormalInput Out>1;  # implicit normal', text)
        self.assertIn('ClearcoatNormal<1;', text)
        self.assertIn('NormalOutput In<0;', text)
        self.assertEqual(result.warnings, [])

    def test_v1_transmission_is_carried_as_a_layer(self):
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree)
        p.inputs[9].default_value = 0.9  # Transmission
        p.inputs[18].default_value = 1.33  # IOR
        p.inputs[19].default_value = 0.2  # Transmission Roughness
        tree.link(p.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('PrincipledLayers BaseColor=(0.800000012, 0.300000012, 0.100000001) '
                      'Metallic=0.25 Roughness=0.400000006 Sheen=0 SheenTint=0.5 '
                      'Clearcoat=0 ClearcoatRoughness=0.0299999993 Transmission=0.899999976 '
                      'TransmissionRoughness=0.200000003 IOR=1.33000004;', text)
        self.assertEqual(result.warnings, [])
        # Multiscatter GGX: Cycles' glass takes the one roughness; warned as a whole.
        p.distribution = 'MULTI_GGX'
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('TransmissionRoughness=0 IOR=1.33000004;', text)
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertIn('Multiscatter GGX is written as single-scatter GGX', msgs)

    def test_v1_under_a_mix_shader_is_a_principled_bsdf_sink(self):
        # A Principled BSDF mixed with an Emission: exact as lobes (lobes.py), its clearcoat a
        # lobe of PrincipledBsdf (Layers bit 2), the emission weighted by the Mix; it fits one
        # hit, so nothing is chosen per hit and nothing is warned.
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree)
        p.inputs[8].default_value = 1.0  # Clearcoat
        em = emission(tree)
        mix = tree.add(Node('ShaderNodeMixShader', 'Mix',
                            [Sock('Fac', 'VALUE', 0.5), Sock('Shader', 'SHADER'),
                             Sock('Shader_001', 'SHADER')], [Sock('Shader', 'SHADER')]))
        tree.link(p.outputs[0], mix.inputs[1])
        tree.link(em.outputs[0], mix.inputs[2])
        tree.link(mix.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('MixShader Fac=0.5 Weight=1 WeightA>0 WeightB>1;', text)
        self.assertIn('PrincipledBsdf BaseColor=(0.800000012, 0.300000012, 0.100000001) '
                      'Metallic=0.25 Roughness=0.400000006 Specular=0.699999988 SpecularTint=0 '
                      'Sheen=0 SheenTint=0.5 Clearcoat=1 ClearcoatRoughness=0.0299999993 '
                      'Transmission=0 TransmissionRoughness=0 IOR=1.45000005 Layers=2 '
                      'Weight<0;', text)
        self.assertIn('Mul A=(1, 1, 1) B<1 Out>2;', text)
        self.assertIn('EmissionOutput Color<2 Strength=1;', text)
        self.assertNotIn('ChooseShader', text)
        self.assertNotIn('PrincipledOutput', text)
        self.assertEqual(result.warnings, [])
        # Added to an emission, the sum is exact: the layers stay, and nothing is warned
        # of them.
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree)
        p.inputs[8].default_value = 1.0  # Clearcoat
        em = emission(tree)
        add = tree.add(Node('ShaderNodeAddShader', 'Add',
                            [Sock('Shader', 'SHADER'), Sock('Shader_001', 'SHADER')],
                            [Sock('Shader', 'SHADER')]))
        tree.link(em.outputs[0], add.inputs[0])
        tree.link(p.outputs[0], add.inputs[1])
        tree.link(add.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('PrincipledLayers BaseColor=(0.800000012, 0.300000012, 0.100000001) '
                      'Metallic=0.25 Roughness=0.400000006 Sheen=0 SheenTint=0.5 Clearcoat=1 '
                      'ClearcoatRoughness=0.0299999993 Transmission=0', text)
        self.assertNotIn('PrincipledBsdf', text)
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertNotIn('Sheen, Clearcoat', msgs)

    def test_mix_with_a_diffuse_fits_one_hit_and_is_exact(self):
        # A Principled BSDF without layers (one lobe) and a Diffuse (one lobe): both at every
        # hit, no choice, nothing approximated.
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree, tint=1.0)
        diff = tree.add(Node('ShaderNodeBsdfDiffuse', 'Diffuse',
                             [Sock('Color', 'RGBA', (0.5, 0.1, 0.1, 1)),
                              Sock('Roughness', 'VALUE', 0.0),
                              Sock('Normal', 'VECTOR', (0, 0, 0))], [Sock('BSDF', 'SHADER')]))
        mix = tree.add(Node('ShaderNodeMixShader', 'Mix',
                            [Sock('Fac', 'VALUE', 0.25), Sock('Shader', 'SHADER'),
                             Sock('Shader_001', 'SHADER')], [Sock('Shader', 'SHADER')]))
        tree.link(diff.outputs[0], mix.inputs[1])
        tree.link(p.outputs[0], mix.inputs[2])
        tree.link(mix.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('DiffuseBsdf Color=(0.5, 0.100000001, 0.100000001) Roughness=0 Weight<0;',
                      text)
        self.assertIn('PrincipledBsdf BaseColor=(0.800000012, 0.300000012, 0.100000001) '
                      'Metallic=0.25 Roughness=0.400000006 Specular=0.699999988 SpecularTint=1 '
                      'Layers=0 Weight<1;', text)
        self.assertNotIn('ChooseShader', text)
        self.assertEqual(result.warnings, [])


def mix_shader(tree, name, fac):
    return tree.add(Node('ShaderNodeMixShader', name,
                         [Sock('Fac', 'VALUE', fac), Sock('Shader', 'SHADER'),
                          Sock('Shader_001', 'SHADER')], [Sock('Shader', 'SHADER')]))


def add_shader(tree, name):
    return tree.add(Node('ShaderNodeAddShader', name,
                         [Sock('Shader', 'SHADER'), Sock('Shader_001', 'SHADER')],
                         [Sock('Shader', 'SHADER')]))


class ClosureChoiceTest(unittest.TestCase):
    def test_two_principled_bsdfs_are_chosen_per_hit(self):
        # Two sets of Principled outputs cannot share a hit: the Mix chooses (ChooseShader
        # after its MixShader), each side a PrincipledBsdf at its chosen weight.
        tree = Tree()
        out = output_node(tree)
        red = principled_v1(tree)
        red.inputs[8].default_value = 1.0  # Clearcoat
        red.inputs[7].default_value = 0.5  # Sheen
        gold = principled_v1(tree)
        gold.name = 'Gold'
        gold.inputs[2].default_value = 1.0  # Metallic
        mix = mix_shader(tree, 'Mix', 0.3)
        tree.link(red.outputs[0], mix.inputs[1])
        tree.link(gold.outputs[0], mix.inputs[2])
        tree.link(mix.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('MixShader Fac=0.300000012 Weight=1 WeightA>0 WeightB>1;', text)
        self.assertIn('ChooseShader WeightA<0 WeightB<1 Stream=0 ChosenA>2 ChosenB>3;', text)
        self.assertIn('Layers=3 Weight<2;', text)
        self.assertIn('Metallic=1 Roughness=0.400000006 Specular=0.699999988 SpecularTint=0 '
                      'Layers=0 Weight<3;', text)
        self.assertNotIn('PrincipledOutput', text)
        self.assertEqual(result.warnings, [])

    def test_nested_mixes_choose_where_their_sides_do_not_fit(self):
        # Mix(Mix(layered Principled, Principled), Glass): the inner Mix holds two Principled
        # BSDFs and chooses; its larger side needs 4 lobes, which with the Glass's 1 exceed
        # MAX_LOBES, so the outer Mix chooses too, with its own stream.
        tree = Tree()
        out = output_node(tree)
        a = principled_v1(tree)
        a.inputs[7].default_value = 0.5  # Sheen
        a.inputs[8].default_value = 1.0  # Clearcoat
        a.inputs[9].default_value = 0.5  # Transmission
        b = principled_v1(tree)
        b.name = 'Plain'
        glass = tree.add(Node('ShaderNodeBsdfGlass', 'Glass',
                              [Sock('Color', 'RGBA', (1.0, 1.0, 1.0, 1)),
                               Sock('Roughness', 'VALUE', 0.0), Sock('IOR', 'VALUE', 1.5),
                               Sock('Normal', 'VECTOR', (0, 0, 0))], [Sock('BSDF', 'SHADER')],
                              distribution='GGX'))
        inner = mix_shader(tree, 'Inner', 0.5)
        outer = mix_shader(tree, 'Outer', 0.25)
        tree.link(a.outputs[0], inner.inputs[1])
        tree.link(b.outputs[0], inner.inputs[2])
        tree.link(inner.outputs[0], outer.inputs[1])
        tree.link(glass.outputs[0], outer.inputs[2])
        tree.link(outer.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('ChooseShader WeightA<0 WeightB<1 Stream=0 ChosenA>2 ChosenB>3;', text)
        self.assertIn('MixShader Fac=0.5 Weight<2 WeightA>4 WeightB>5;', text)
        self.assertIn('ChooseShader WeightA<4 WeightB<5 Stream=1 ChosenA>6 ChosenB>7;', text)
        self.assertIn('Layers=7 Weight<6;', text)
        self.assertIn('Layers=0 Weight<7;', text)
        self.assertIn('GlassBsdf', text)
        self.assertIn('Weight<3;', text)
        self.assertEqual(result.warnings, [])

    def test_add_shader_that_fits_stays_exact_and_one_that_does_not_chooses(self):
        # Principled (no layer) + Glossy: two lobes, both at every hit.
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree)
        gl = tree.add(Node('ShaderNodeBsdfGlossy', 'Glossy',
                           [Sock('Color', 'RGBA', (0.9, 0.9, 0.9, 1)),
                            Sock('Roughness', 'VALUE', 0.2), Sock('Normal', 'VECTOR', (0, 0, 0))],
                           [Sock('BSDF', 'SHADER')], distribution='GGX'))
        add = add_shader(tree, 'Add')
        tree.link(p.outputs[0], add.inputs[0])
        tree.link(gl.outputs[0], add.inputs[1])
        tree.link(add.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('Layers=0 Weight=1;', text)
        self.assertIn('GlossyBsdf Color=(0.899999976, 0.899999976, 0.899999976) '
                      'Roughness=0.200000003 Distribution=0 Weight=1;', text)
        self.assertNotIn('ChooseShader', text)
        # With its clearcoat, sheen and transmission (4 lobes) + Glossy: 5, the Add chooses,
        # each side with probability 1/2 at twice the weight.
        p.inputs[7].default_value = 0.5
        p.inputs[8].default_value = 1.0
        p.inputs[9].default_value = 0.5
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('ChooseShader WeightA=1 WeightB=1 Stream=0 ChosenA>0 ChosenB>1;', text)
        self.assertIn('Layers=7 Weight<0;', text)
        self.assertIn('Distribution=0 Weight<1;', text)
        self.assertEqual(result.warnings, [])

    def test_five_bsdfs_choose_instead_of_being_approximated(self):
        # Five Diffuse BSDFs added: more than MAX_LOBES. The top Add chooses between a side of
        # four (which fits) and one; nothing falls back to the Principled approximation.
        tree = Tree()
        out = output_node(tree)
        diffuse = [tree.add(Node('ShaderNodeBsdfDiffuse', 'D%d' % i,
                                 [Sock('Color', 'RGBA', (0.1 * i, 0.1, 0.1, 1)),
                                  Sock('Roughness', 'VALUE', 0.0),
                                  Sock('Normal', 'VECTOR', (0, 0, 0))], [Sock('BSDF', 'SHADER')]))
                   for i in range(5)]
        adds = [add_shader(tree, 'A%d' % i) for i in range(4)]
        tree.link(diffuse[0].outputs[0], adds[0].inputs[0])
        tree.link(diffuse[1].outputs[0], adds[0].inputs[1])
        for i in range(1, 4):
            tree.link(adds[i - 1].outputs[0], adds[i].inputs[0])
            tree.link(diffuse[i + 1].outputs[0], adds[i].inputs[1])
        tree.link(adds[3].outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertEqual(text.count('ChooseShader'), 1)
        self.assertEqual(text.count('DiffuseBsdf'), 5)
        self.assertNotIn('PrincipledOutput', text)
        self.assertEqual(result.warnings, [])


    def test_a_mixed_principled_bsdfs_alpha_is_a_transparent_lobe(self):
        # Mix(Principled of Alpha 0.4 with emission, Glossy): written as Cycles expands the
        # Principled BSDF (PrincipledBsdfNode::expand): a MixShader of Fac Alpha splits its
        # weight into a white TransparentBsdf (1 - Alpha) and the PrincipledBsdf (Alpha), and
        # its emission takes Alpha too. Three lobes fit one hit: no choice, and no warning.
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree)
        p.inputs[12].default_value = (1.0, 0.5, 0.0, 1)  # Emission
        p.inputs[14].default_value = 0.4  # Alpha
        gl = tree.add(Node('ShaderNodeBsdfGlossy', 'Glossy',
                           [Sock('Color', 'RGBA', (0.9, 0.9, 0.9, 1)),
                            Sock('Roughness', 'VALUE', 0.2), Sock('Normal', 'VECTOR', (0, 0, 0))],
                           [Sock('BSDF', 'SHADER')], distribution='GGX'))
        mix = mix_shader(tree, 'Mix', 0.25)
        tree.link(p.outputs[0], mix.inputs[1])
        tree.link(gl.outputs[0], mix.inputs[2])
        tree.link(mix.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('MixShader Fac=0.25 Weight=1 WeightA>0 WeightB>1;', text)
        self.assertIn('MixShader Fac=0.400000006 Weight<0 WeightA>2 WeightB>3;', text)
        self.assertIn('TransparentBsdf Color=(1, 1, 1) Weight<2;', text)
        self.assertIn('Saturate In=0.400000006 Out>4;', text)
        self.assertIn('Mul A<4 B<0 Out>5;', text)
        self.assertIn('Layers=0 Weight<3;', text)
        self.assertIn('EmissionOutput', text)
        self.assertNotIn('ChooseShader', text)
        self.assertEqual(result.warnings, [])
        # Alpha 1 (the default) writes no Transparent lobe at all.
        p.inputs[14].default_value = 1.0
        result, (text,) = export([Material('Mat', tree)])
        self.assertNotIn('TransparentBsdf', text)
        self.assertIn('Layers=0 Weight<0;', text)
        # With its sheen and clearcoat (3 lobes) and Alpha the Principled side needs 4, the
        # Glossy one more: the Mix chooses, and each side keeps its own lobes.
        p.inputs[14].default_value = 0.4
        p.inputs[7].default_value = 0.5
        p.inputs[8].default_value = 1.0
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('ChooseShader WeightA<0 WeightB<1 Stream=0 ChosenA>2 ChosenB>3;', text)
        self.assertIn('MixShader Fac=0.400000006 Weight<2 WeightA>4 WeightB>5;', text)
        self.assertIn('TransparentBsdf Color=(1, 1, 1) Weight<4;', text)
        self.assertIn('Layers=3 Weight<5;', text)
        self.assertEqual(result.warnings, [])
        # With its transmission too, its four lobes leave no room for the Transparent one: the
        # Alpha is warned and dropped, never written as a fifth lobe the compiler would refuse.
        p.inputs[9].default_value = 0.5
        result, (text,) = export([Material('Mat', tree)])
        self.assertNotIn('TransparentBsdf', text)
        self.assertIn('Layers=7 Weight<', text)
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertIn('Alpha of a Principled BSDF under a Mix or Add Shader is not carried', msgs)


class SpecWriterTest(unittest.TestCase):
    def test_uncarried_input_and_output_are_reported(self):
        tree = Tree()
        out = output_node(tree)
        em = emission(tree)
        src = tree.add(math_node('Src'))
        node = tree.add(Node('ShaderNodeX', 'X', [Sock('In', 'VALUE', 1.0),
                                                  Sock('Extra', 'VALUE', 2.0)],
                             [Sock('Out', 'VALUE', 0.5), Sock('Other', 'VALUE', 0.25)]))
        tree.link(src.outputs[0], node.inputs[1])  # linked but not in the spec
        tree.link(node.outputs[1], em.inputs[1])   # an output the spec does not map
        tree.link(node.outputs[0], em.inputs[0])
        tree.link(em.outputs[0], out.inputs[0])
        table = dict(MATH_SPEC)
        table['ShaderNodeX'] = NodeSpec('Xn', {'In': 'In'}, {'Out': 'Out'})
        result, (text,) = export([Material('Mat', tree)], writers.build_table(table))
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertIn("input 'Extra' is linked but the exporter does not carry it", msgs)
        self.assertIn("output 'Other' is not carried: its default 0.25 is used instead", msgs)
        self.assertIn('Xn In=1 Out>0;', text)
        self.assertIn('Strength=0.25', text)
        self.assertNotIn('Math', text)  # only the ignored input read it


LIGHT_PATH_OUTPUTS = ('Is Camera Ray', 'Is Shadow Ray', 'Is Diffuse Ray', 'Is Glossy Ray',
                      'Is Singular Ray', 'Is Reflection Ray', 'Is Transmission Ray',
                      'Ray Length', 'Ray Depth', 'Diffuse Depth', 'Glossy Depth',
                      'Transparent Depth', 'Transmission Depth')


def light_path_material(output):
    """Emission whose Strength is Light Path's `output`."""
    tree = Tree()
    out = output_node(tree)
    em = emission(tree)
    lp = tree.add(Node('ShaderNodeLightPath', 'Light Path', [],
                       [Sock(o, 'VALUE', 0.0) for o in LIGHT_PATH_OUTPUTS]))
    tree.link(lp.outputs[LIGHT_PATH_OUTPUTS.index(output)], em.inputs[1])
    tree.link(em.outputs[0], out.inputs[0])
    return Material('Mat', tree)


class LightPathTest(unittest.TestCase):
    """Light Path's outputs are the path tracer's per-ray inputs (LightPath node), carried
    without a warning; Transparent Depth, which memograph has no use for (no transparent
    bounces), is warned and written as its default, 0."""

    def test_carried_outputs_need_no_warning(self):
        table = writers.build_table(load_specs())
        for output in LIGHT_PATH_OUTPUTS:
            if output == 'Transparent Depth':
                continue
            result, (text,) = export([light_path_material(output)], table)
            self.assertEqual(result.warnings, [], output)
            socket = output.replace(' ', '')
            self.assertRegex(text, r'LightPath %s>\d+;' % socket)

    def test_transparent_depth_is_warned(self):
        result, (text,) = export([light_path_material('Transparent Depth')],
                                 writers.build_table(load_specs()))
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertIn("output 'Transparent Depth' is not carried: its default 0", msgs)
        self.assertIn('Strength=0', text)


def ao_material(link_normal=False, distance=0.5):
    """Emission whose Color is Blender's Ambient Occlusion Color (Only Local on)."""
    tree = Tree()
    out = output_node(tree)
    em = emission(tree)
    ao = tree.add(Node('ShaderNodeAmbientOcclusion', 'Ambient Occlusion',
                       [Sock('Color', 'RGBA', (0.5, 0.5, 0.5, 1)),
                        Sock('Distance', 'VALUE', distance), Sock('Normal', 'VECTOR', (0, 0, 0))],
                       [Sock('Color', 'RGBA', (1, 1, 1, 1)), Sock('AO', 'VALUE', 1.0)],
                       samples=8, inside=False, only_local=True))
    if link_normal:
        src = tree.add(math_node('Src'))
        tree.link(src.outputs[0], ao.inputs[2])
    tree.link(ao.outputs[0], em.inputs[0])
    tree.link(em.outputs[0], out.inputs[0])
    return Material('Mat', tree)


class AmbientOcclusionTest(unittest.TestCase):
    """The Ambient Occlusion node is a traced input (docs/design/traced-inputs.md): its
    settings are written as constants; a linked Normal, which the tracer cannot know, is
    warned."""

    def test_settings_are_constants(self):
        result, (text,) = export([ao_material()], writers.build_table(load_specs()))
        self.assertEqual(result.warnings, [])
        self.assertRegex(text, r'AmbientOcclusion Color=\(0\.5, 0\.5, 0\.5\) Samples=8 '
                               r'Inside=0 OnlyLocal=1 Distance=0\.5 Out>\d+;')

    def test_linked_normal_is_warned(self):
        result, (text,) = export([ao_material(link_normal=True)],
                                 writers.build_table(load_specs()))
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertIn("input 'Normal' is linked but the exporter does not carry it", msgs)
        self.assertNotIn('Math', text)


class BevelTest(unittest.TestCase):
    """Bevel, traced like Ambient Occlusion: Radius and Samples written as constants."""

    def test_settings_are_constants(self):
        tree = Tree()
        out = output_node(tree)
        em = emission(tree)
        bevel = tree.add(Node('ShaderNodeBevel', 'Bevel',
                              [Sock('Radius', 'VALUE', 0.125), Sock('Normal', 'VECTOR', (0, 0, 0))],
                              [Sock('Normal', 'VECTOR', (0, 0, 1))], samples=6))
        tree.link(bevel.outputs[0], em.inputs[0])
        tree.link(em.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)], writers.build_table(load_specs()))
        self.assertEqual(result.warnings, [])
        self.assertRegex(text, r'Bevel Samples=6 Radius=0\.125 Normal>\d+;')


class Blender4Test(unittest.TestCase):
    def test_principled_v2(self):
        tree = Tree()
        out = output_node(tree)
        p = principled_v2(tree)
        tree.link(p.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat', tree)])
        # v2 keeps memograph's own weighting (CyclesPrincipled 0) and no tint.
        self.assertIn('PrincipledOutput BaseColor=(0.800000012, 0.800000012, 0.800000012) '
                      'Metallic=0 Roughness=0.5 Specular=0.5 Emission=(1, 0.5, 0) '
                      'EmissionStrength=2 Alpha=1 SpecularTint=0 CyclesPrincipled=0;', text)
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertIn('Specular IOR Level', msgs)
        self.assertIn('Coat = 0.3 is not carried', msgs)
        self.assertNotIn('PrincipledLayers', text)  # v2's coat is another model
        p.inputs[13].default_value = 0.5  # Transmission Weight
        result, (text,) = export([Material('Mat', tree)])
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertIn('Transmission = 0.5 is not carried', msgs)
        self.assertNotIn('Specular Tint', msgs)  # white tint = off in 4.x
        # A coloured 4.x tint is not carried, and says so.
        p.inputs[8].default_value = (1, 0.5, 0.5, 1)
        result, (text,) = export([Material('Mat', tree)])
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertIn('Specular Tint (4.x colour) = (1, 0.5, 0.5) is not carried', msgs)
        self.assertIn('SpecularTint=0 CyclesPrincipled=0;', text)

    def test_noise_types_and_new_inputs(self):
        tree = Tree()
        out = output_node(tree)
        em = emission(tree)
        noise = tree.add(Node('ShaderNodeTexNoise', 'Noise',
                              [Sock('Vector', 'VECTOR', (0, 0, 0)), Sock('Scale', 'VALUE', 5.0),
                               Sock('Lacunarity', 'VALUE', 3.0)],
                              [Sock('Fac', 'VALUE')], noise_type='RIDGED_MULTIFRACTAL',
                              normalize=True))
        tree.link(noise.outputs[0], em.inputs[1])
        tree.link(em.outputs[0], out.inputs[0])
        spec = {'ShaderNodeTexNoise': NodeSpec('NoiseTexture', {'Vector': 'Vector',
                                                                 'Scale': 'Scale'},
                                               {'Fac': 'Fac'}, implicit_vector='generated')}
        result, (text,) = export([Material('Mat', tree)], writers.build_table(spec))
        msgs = ' | '.join(w[2] for w in result.warnings)
        self.assertIn('RIDGED_MULTIFRACTAL', msgs)
        self.assertIn('Lacunarity = 3 (Blender 4.x input) is not carried', msgs)
        self.assertIn('TextureCoordinate Generated>0;', text)
        self.assertIn('NoiseTexture Vector<0 Scale=5 Fac>1;', text)
        self.assertIn('NoiseTexture computes Blender 3.4\'s fBm normalisation', msgs)
        # A spec that carries Lacunarity: no warning for it.
        spec['ShaderNodeTexNoise'].inputs['Lacunarity'] = 'Lacunarity'
        result, (text,) = export([Material('Mat', tree)], writers.build_table(spec))
        self.assertNotIn('Lacunarity = 3', ' | '.join(w[2] for w in result.warnings))
        self.assertIn('Lacunarity=3', text)

    def test_find_input_fallbacks(self):
        n = Node('X', 'x', [Sock('Emission Color', 'RGBA', (1, 1, 1, 1)),
                           Sock('Specular', 'VALUE', 0.5, enabled=False)])
        self.assertEqual(compat.find_input(n, 'Emission', 'Emission Color'), 'Emission Color')
        self.assertIsNone(compat.find_input(n, 'Specular'))


class ShaderTest(unittest.TestCase):
    def test_mix_add_and_approximations(self):
        tree = Tree()
        out = output_node(tree)
        diff = tree.add(Node('ShaderNodeBsdfDiffuse', 'Diffuse',
                             [Sock('Color', 'RGBA', (0.5, 0.1, 0.1, 1)),
                              Sock('Roughness', 'VALUE', 0.0),
                              Sock('Normal', 'VECTOR', (0, 0, 0))], [Sock('BSDF', 'SHADER')]))
        gl = tree.add(Node('ShaderNodeBsdfGlossy', 'Glossy',
                           [Sock('Color', 'RGBA', (0.9, 0.9, 0.9, 1)),
                            Sock('Roughness', 'VALUE', 0.2),
                            Sock('Normal', 'VECTOR', (0, 0, 0))], [Sock('BSDF', 'SHADER')],
                           distribution='GGX'))
        mix = tree.add(Node('ShaderNodeMixShader', 'Mix',
                            [Sock('Fac', 'VALUE', 0.25), Sock('Shader', 'SHADER'),
                             Sock('Shader_001', 'SHADER')], [Sock('Shader', 'SHADER')]))
        em = emission(tree)
        add = tree.add(Node('ShaderNodeAddShader', 'Add',
                            [Sock('Shader', 'SHADER'), Sock('Shader_001', 'SHADER')],
                            [Sock('Shader', 'SHADER')]))
        holdout = tree.add(Node('ShaderNodeHoldout', 'Holdout', [], [Sock('Holdout', 'SHADER')]))
        tree.link(diff.outputs[0], mix.inputs[1])
        tree.link(gl.outputs[0], mix.inputs[2])
        tree.link(mix.outputs[0], add.inputs[0])
        tree.link(em.outputs[0], add.inputs[1])
        tree.link(add.outputs[0], out.inputs[0])
        # Diffuse, Glossy, Emission, Mix and Add only: written exactly as lobes (lobes.py).
        result, (text,) = export([Material('Mat', tree)])
        self.assertIn('MixShader Fac=0.25 Weight=1 WeightA>0 WeightB>1;', text)
        self.assertIn('DiffuseBsdf Color=(0.5, 0.100000001, 0.100000001) Roughness=0 '
                      'Weight<0;', text)
        self.assertIn('GlossyBsdf Color=(0.899999976, 0.899999976, 0.899999976) '
                      'Roughness=0.200000003 Distribution=0 Weight<1;', text)
        self.assertIn('EmissionOutput Color=(1, 1, 1) Strength=1;', text)
        self.assertNotIn('PrincipledOutput', text)
        self.assertEqual(result.warnings, [])
        # A shader that is not a lobe in the tree (here a Holdout in the Mix): the whole
        # surface falls back to the Principled approximation, with its warnings.
        tree.links[1] = NLink(holdout.outputs[0], mix.inputs[2])
        result, (text,) = export([Material('Mat1', tree)])
        self.assertIn('Saturate In=0.25 Out>0;', text)
        self.assertIn('Mix A=(0.5, 0.100000001, 0.100000001) B=(0.800000012, 0.800000012, '
                      '0.800000012) Factor<0 Out>1;', text)
        self.assertIn('PrincipledOutput', text)
        msgs = ' | '.join(w[2] for w in result.warnings)
        for what in ('Diffuse BSDF approximated', 'ShaderNodeHoldout is not supported',
                     'Mix Shader approximated', 'Add Shader approximated'):
            self.assertIn(what, msgs)
        # An unsupported shader: a warning and the defaults.
        tree.links[-1] = NLink(holdout.outputs[0], out.inputs[0])
        result, (text,) = export([Material('Mat2', tree)])
        self.assertIn('ShaderNodeHoldout is not supported', result.warnings[0][2])
        self.assertIn('PrincipledOutput BaseColor=(0.800000012, 0.800000012, 0.800000012)',
                      text)

    def test_each_bsdf_keeps_its_own_normal(self):
        # A bumped Diffuse mixed with a smooth Glossy: the Diffuse's sink takes its Normal,
        # the Glossy none (the material's normal), and no NormalOutput. Both linked to the
        # same normal: that normal is the material's (NormalOutput), the sinks take none.
        tree = Tree()
        out = output_node(tree)
        diff = tree.add(Node('ShaderNodeBsdfDiffuse', 'Diffuse',
                             [Sock('Color', 'RGBA', (0.5, 0.1, 0.1, 1)),
                              Sock('Roughness', 'VALUE', 0.0),
                              Sock('Normal', 'VECTOR', (0, 0, 0))], [Sock('BSDF', 'SHADER')]))
        gl = tree.add(Node('ShaderNodeBsdfGlossy', 'Glossy',
                           [Sock('Color', 'RGBA', (0.9, 0.9, 0.9, 1)),
                            Sock('Roughness', 'VALUE', 0.2),
                            Sock('Normal', 'VECTOR', (0, 0, 0))], [Sock('BSDF', 'SHADER')],
                           distribution='GGX'))
        mix = tree.add(Node('ShaderNodeMixShader', 'Mix',
                            [Sock('Fac', 'VALUE', 0.25), Sock('Shader', 'SHADER'),
                             Sock('Shader_001', 'SHADER')], [Sock('Shader', 'SHADER')]))
        bump = tree.add(Node('ShaderNodeMath', 'B', [], [Sock('Vector', 'VECTOR', (0, 0, 1))]))
        tree.link(bump.outputs[0], diff.inputs[2])
        tree.link(diff.outputs[0], mix.inputs[1])
        tree.link(gl.outputs[0], mix.inputs[2])
        tree.link(mix.outputs[0], out.inputs[0])
        table = writers.build_table({'ShaderNodeMath': NodeSpec(
            'NormalInput', {}, {'Vector': 'Out'})})
        result, (text,) = export([Material('OwnNormals', tree)], table)
        self.assertIn('NormalInput Out>2;', text)
        self.assertIn('DiffuseBsdf Color=(0.5, 0.100000001, 0.100000001) Roughness=0 '
                      'Weight<0 Normal<2;', text)
        self.assertIn('GlossyBsdf Color=(0.899999976, 0.899999976, 0.899999976) '
                      'Roughness=0.200000003 Distribution=0 Weight<1;', text)
        self.assertNotIn('NormalOutput', text)
        self.assertEqual(result.warnings, [])
        tree.link(bump.outputs[0], gl.inputs[2])
        result, (text,) = export([Material('SharedNormal', tree)], table)
        self.assertIn('Roughness=0 Weight<0;', text)
        self.assertIn('Distribution=0 Weight<1;', text)
        self.assertIn('NormalOutput In<2;', text)
        self.assertEqual(result.warnings, [])

    def test_a_mixed_principled_bsdf_carries_its_normals(self):
        # Mixed with a Diffuse of another normal, the Principled BSDF's Normal and Clearcoat
        # Normal go to PrincipledBsdf's Normal and ClearcoatNormal, without warnings. When both
        # BSDFs link the same Normal it is the material's, and an unlinked Clearcoat Normal is
        # the interpolated normal (Cycles' sd->N), not the bumped one.
        tree = Tree()
        out = output_node(tree)
        p = principled_v1(tree)
        p.inputs[8].default_value = 1.0  # Clearcoat
        diff = tree.add(Node('ShaderNodeBsdfDiffuse', 'Diffuse',
                             [Sock('Color', 'RGBA', (0.5, 0.1, 0.1, 1)),
                              Sock('Roughness', 'VALUE', 0.0),
                              Sock('Normal', 'VECTOR', (0, 0, 0))], [Sock('BSDF', 'SHADER')]))
        mix = tree.add(Node('ShaderNodeMixShader', 'Mix',
                            [Sock('Fac', 'VALUE', 0.5), Sock('Shader', 'SHADER'),
                             Sock('Shader_001', 'SHADER')], [Sock('Shader', 'SHADER')]))
        bump = tree.add(Node('ShaderNodeMath', 'B', [], [Sock('Vector', 'VECTOR', (0, 0, 1))]))
        coat = tree.add(Node('ShaderNodeMath', 'C', [], [Sock('Vector', 'VECTOR', (0, 1, 0))]))
        tree.link(bump.outputs[0], p.inputs[15])  # Normal
        tree.link(coat.outputs[0], p.inputs[16])  # Clearcoat Normal
        tree.link(p.outputs[0], mix.inputs[1])
        tree.link(diff.outputs[0], mix.inputs[2])
        tree.link(mix.outputs[0], out.inputs[0])
        table = writers.build_table({'ShaderNodeMath': NodeSpec(
            'NormalInput', {}, {'Vector': 'Out'})})
        result, (text,) = export([Material('OwnNormals', tree)], table)
        self.assertRegex(text, r'PrincipledBsdf [^;]* Normal<(\d+) ClearcoatNormal<(?!\1)\d+;')
        self.assertNotIn('NormalOutput', text)
        self.assertEqual(result.warnings, [])
        tree.links = [l for l in tree.links if l.to_socket is not p.inputs[16]]
        tree.link(bump.outputs[0], diff.inputs[2])
        result, (text,) = export([Material('SharedNormal', tree)], table)
        normal = re.search(r'NormalOutput In<(\d+);', text).group(1)
        implicit = re.search(r'NormalInput Out>(\d+);  # implicit normal', text).group(1)
        self.assertNotEqual(normal, implicit)
        self.assertRegex(text, r'PrincipledBsdf [^;]* Weight<\d+ ClearcoatNormal<%s;' % implicit)
        self.assertEqual(result.warnings, [])

    def test_transmission_shaders_are_lobes_without_warnings(self):
        # Glass, Refraction, Transparent and Translucent are lobes now (lobes.py): written as
        # their sinks with IOR and distribution, no Principled approximation and no warning.
        tree = Tree()
        out = output_node(tree)
        glass = tree.add(Node('ShaderNodeBsdfGlass', 'Glass',
                              [Sock('Color', 'RGBA', (0.9, 0.9, 1.0, 1)),
                               Sock('Roughness', 'VALUE', 0.1), Sock('IOR', 'VALUE', 1.5),
                               Sock('Normal', 'VECTOR', (0, 0, 0))], [Sock('BSDF', 'SHADER')],
                              distribution='BECKMANN'))
        refraction = tree.add(Node('ShaderNodeBsdfRefraction', 'Refraction',
                                   [Sock('Color', 'RGBA', (1.0, 1.0, 1.0, 1)),
                                    Sock('Roughness', 'VALUE', 0.3), Sock('IOR', 'VALUE', 1.33),
                                    Sock('Normal', 'VECTOR', (0, 0, 0))],
                                   [Sock('BSDF', 'SHADER')], distribution='SHARP'))
        transparent = tree.add(Node('ShaderNodeBsdfTransparent', 'Transparent',
                                    [Sock('Color', 'RGBA', (0.5, 0.25, 1.0, 1))],
                                    [Sock('BSDF', 'SHADER')]))
        translucent = tree.add(Node('ShaderNodeBsdfTranslucent', 'Translucent',
                                    [Sock('Color', 'RGBA', (0.25, 0.5, 0.25, 1)),
                                     Sock('Normal', 'VECTOR', (0, 0, 0))],
                                    [Sock('BSDF', 'SHADER')]))
        adds = []
        for i in range(3):
            adds.append(tree.add(Node('ShaderNodeAddShader', 'Add%d' % i,
                                      [Sock('Shader', 'SHADER'), Sock('Shader_001', 'SHADER')],
                                      [Sock('Shader', 'SHADER')])))
        tree.link(glass.outputs[0], adds[0].inputs[0])
        tree.link(refraction.outputs[0], adds[0].inputs[1])
        tree.link(transparent.outputs[0], adds[1].inputs[0])
        tree.link(translucent.outputs[0], adds[1].inputs[1])
        tree.link(adds[0].outputs[0], adds[2].inputs[0])
        tree.link(adds[1].outputs[0], adds[2].inputs[1])
        tree.link(adds[2].outputs[0], out.inputs[0])
        result, (text,) = export([Material('Glassy', tree)])
        self.assertIn('GlassBsdf Color=(0.899999976, 0.899999976, 1) Roughness=0.100000001 '
                      'IOR=1.5 Distribution=1 Weight=1;', text)
        # Sharp: Distribution 2, Roughness 0 (the lobe is then singular, as Cycles' sharp
        # refraction, and Filter Glossy leaves it alone, as Cycles' bsdf_blur does).
        self.assertIn('RefractionBsdf Color=(1, 1, 1) Roughness=0 IOR=1.33000004 '
                      'Distribution=2 Weight=1;', text)
        self.assertIn('TransparentBsdf Color=(0.5, 0.25, 1) Weight=1;', text)
        self.assertIn('TranslucentBsdf Color=(0.25, 0.5, 0.25) Weight=1;', text)
        self.assertNotIn('PrincipledOutput', text)
        self.assertNotIn('OpacityOutput', text)
        self.assertEqual(result.warnings, [])
        # Multiscatter GGX glass is written as GGX, warned.
        glass.distribution = 'MULTI_GGX'
        result, (text,) = export([Material('Glassy1', tree)])
        self.assertIn('GlassBsdf Color=(0.899999976, 0.899999976, 1) Roughness=0.100000001 '
                      'IOR=1.5 Distribution=0 Weight=1;', text)
        self.assertEqual(len(result.warnings), 1)
        self.assertIn('Multiscatter GGX is written as single-scatter GGX glass',
                      result.warnings[0][2])


if __name__ == '__main__':
    unittest.main()

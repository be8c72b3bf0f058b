"""Shader trees of BSDF lobes -> memograph's BSDF sinks (nodes/bsdf.inc).

A surface whose shader tree holds only Diffuse, Glossy, Velvet, Refraction, Glass,
Transparent and Translucent BSDFs, Emission, and Mix and Add Shaders between them is written
exactly: each BSDF becomes a sink that adds one lobe (DiffuseBsdf, GlossyBsdf, VelvetBsdf,
RefractionBsdf, GlassBsdf, TransparentBsdf, TranslucentBsdf) with a weight, Mix Shader becomes a MixShader node
that splits its weight by Fac, Add Shader gives both its shaders its weight, and the
emissions, weighted likewise, are summed into one EmissionOutput. This is Cycles' own
closure weighting (svm_node_mix_closure, svm_node_closure_bsdf), so the runtime samples
the same BSDF (docs/design/closures.md). Any other shader in the tree (Principled,
Subsurface, ...) keeps the Principled approximation of shaders.py.

Each BSDF is shaded about its own Normal, as Cycles shades each closure: where every BSDF
that has a normal links the same one, it is the material's normal (NormalOutput); otherwise
each linked Normal goes to its sink's Normal input, and an unlinked one means the material's
normal, the interpolated one (Cycles' sd->N).
"""

from .graph import Const, Out
from .mgraph import Literal

MAX_LOBES = 4  # MG_MAX_LOBES of nodes/prelude/common.inc

LOBE_NODES = ('ShaderNodeBsdfDiffuse', 'ShaderNodeBsdfGlossy', 'ShaderNodeBsdfVelvet',
              'ShaderNodeBsdfRefraction', 'ShaderNodeBsdfGlass', 'ShaderNodeBsdfTransparent',
              'ShaderNodeBsdfTranslucent')
TREE_NODES = LOBE_NODES + ('ShaderNodeEmission', 'ShaderNodeMixShader',
                           'ShaderNodeAddShader')


def _shader_node(source):
    """The FlatNode a shader Source comes from, or None (unlinked, a value)."""
    return source.node if isinstance(source, Out) else None


def count_lobes(source):
    """The number of BSDF lobes of the tree at source, or None when some shader of it is not
    one that lobes express (then shaders.py approximates the whole surface)."""
    if source is None or isinstance(source, Const):
        return 0  # an unlinked shader socket: no closure
    flat = _shader_node(source)
    if flat is None or flat.bl_idname not in TREE_NODES:
        return None
    if flat.bl_idname in LOBE_NODES:
        return 1
    if flat.bl_idname == 'ShaderNodeEmission':
        return 0
    counts = [count_lobes(flat.input(name)) for name in ('Shader', 'Shader_001')]
    return None if None in counts else sum(counts)


def _source_key(source):
    """What a Normal socket reads, comparable across sockets (None: unlinked)."""
    if isinstance(source, Out):
        return ('out', source.node.key, source.identifier)
    if isinstance(source, Const):
        return None if source.unlinked else ('const', repr(source.value))
    if source is None:
        return None
    return ('convert', getattr(source, 'op', None), _source_key(getattr(source, 'source', None)))


def _normal_keys(source, keys):
    """Appends the Normal of every BSDF of the tree at source that has one (all but
    Transparent) to keys, as _source_key gives it."""
    flat = _shader_node(source)
    if flat is None:
        return
    if flat.bl_idname in ('ShaderNodeMixShader', 'ShaderNodeAddShader'):
        _normal_keys(flat.input('Shader'), keys)
        _normal_keys(flat.input('Shader_001'), keys)
    elif flat.bl_idname in LOBE_NODES and flat.bl_idname != 'ShaderNodeBsdfTransparent':
        keys.append(_source_key(flat.input('Normal')) if flat.is_linked('Normal') else None)


def writes_lobes(mw, surface):
    """Whether the surface is written as lobes (it holds one at least, all expressible); a
    tree of more than MAX_LOBES is refused with a warning and approximated instead."""
    n = count_lobes(surface)
    if not n:
        return False
    if n > MAX_LOBES:
        mw.warn('', 'the surface mixes %d BSDFs, more than memograph\'s %d lobes: '
                'approximated as one Principled BSDF' % (n, MAX_LOBES))
        return False
    return True


class _Writer:
    def __init__(self, mw, per_lobe_normals):
        self.mw = mw
        self.emissions = []  # weighted emission operands
        self.normal = None   # the shared Normal of the BSDFs (not per_lobe_normals)
        # The BSDFs' Normals differ (or some are unlinked): each sink takes its own.
        self.per_lobe_normals = per_lobe_normals

    def _weighted(self, operand, weight, comment):
        if isinstance(weight, Literal) and float(weight.value) == 1.0:
            return operand
        link = self.mw.builder.new_link()
        self.mw.builder.add('Mul', [('A', operand), ('B', weight)], [('Out', link)],
                            comment=comment)
        return link

    def _operand(self, flat, name, default):
        value = self.mw.input_operand(flat, name)
        return default if value is None else value

    def _take_normal(self, flat):
        """The sink's Normal input for flat's linked Normal ([] where it has none, or where
        every BSDF shares it: then it is the material's normal)."""
        if not flat.is_linked('Normal'):
            return []
        normal = self.mw.input_operand(flat, 'Normal')
        if self.per_lobe_normals:
            return [('Normal', normal)]
        if self.normal is None:
            self.normal = normal
        return []

    def write(self, source, weight):
        flat = _shader_node(source)
        if flat is None:
            return
        kind = flat.bl_idname
        b = self.mw.builder
        if kind == 'ShaderNodeMixShader':
            fac = self._operand(flat, 'Fac', Literal(0.5))
            wa, wb = b.new_link(), b.new_link()
            b.add('MixShader', [('Fac', fac), ('Weight', weight)],
                  [('WeightA', wa), ('WeightB', wb)], comment=flat.label)
            self.write(flat.input('Shader'), wa)
            self.write(flat.input('Shader_001'), wb)
        elif kind == 'ShaderNodeAddShader':
            self.write(flat.input('Shader'), weight)
            self.write(flat.input('Shader_001'), weight)
        elif kind == 'ShaderNodeEmission':
            color = self._operand(flat, 'Color', Literal((1.0, 1.0, 1.0)))
            strength = self._operand(flat, 'Strength', Literal(1.0))
            emitted = self._weighted(color, strength, flat.label + ' emission x strength')
            self.emissions.append(self._weighted(emitted, weight, flat.label + ' weight'))
        elif kind == 'ShaderNodeBsdfDiffuse':
            normal = self._take_normal(flat)
            b.add('DiffuseBsdf', [('Color', self._operand(flat, 'Color', Literal((0.8,) * 3))),
                                  ('Roughness', self._operand(flat, 'Roughness', Literal(0.0))),
                                  ('Weight', weight)] + normal, [], comment=flat.label)
        elif kind == 'ShaderNodeBsdfGlossy':
            normal = self._take_normal(flat)
            distribution = getattr(flat.node, 'distribution', 'GGX')
            roughness = self._operand(flat, 'Roughness', Literal(0.5))
            if distribution == 'SHARP':
                roughness = Literal(0.0)
            elif distribution == 'MULTI_GGX':
                self.mw.warn(flat, 'Multiscatter GGX is written as single-scatter GGX: the '
                             'energy that multiple scattering adds back at high Roughness '
                             'is missing')
            elif distribution not in ('GGX', 'BECKMANN'):
                self.mw.warn(flat, 'distribution %s is written as GGX' % distribution)
            b.add('GlossyBsdf', [('Color', self._operand(flat, 'Color', Literal((0.8,) * 3))),
                                 ('Roughness', roughness),
                                 ('Distribution', Literal(1 if distribution == 'BECKMANN' else 0,
                                                          form='int')),
                                 ('Weight', weight)] + normal, [], comment=flat.label)
        elif kind in ('ShaderNodeBsdfRefraction', 'ShaderNodeBsdfGlass'):
            normal = self._take_normal(flat)
            distribution = getattr(flat.node, 'distribution', 'GGX')
            roughness = self._operand(flat, 'Roughness', Literal(0.0))
            if distribution == 'SHARP':
                roughness = Literal(0.0)
            elif distribution == 'MULTI_GGX':
                self.mw.warn(flat, 'Multiscatter GGX is written as single-scatter GGX glass '
                             '(reflection and refraction split by the Fresnel of the shading '
                             'normal): the energy that multiple scattering adds back at high '
                             'Roughness is missing')
            elif distribution not in ('GGX', 'BECKMANN'):
                self.mw.warn(flat, 'distribution %s is written as GGX' % distribution)
            node = 'GlassBsdf' if kind == 'ShaderNodeBsdfGlass' else 'RefractionBsdf'
            b.add(node, [('Color', self._operand(flat, 'Color', Literal((1.0,) * 3))),
                         ('Roughness', roughness),
                         ('IOR', self._operand(flat, 'IOR', Literal(1.45))),
                         ('Distribution', Literal(1 if distribution == 'BECKMANN' else 0,
                                                  form='int')),
                         ('Weight', weight)] + normal, [], comment=flat.label)
        elif kind == 'ShaderNodeBsdfTransparent':
            b.add('TransparentBsdf', [('Color', self._operand(flat, 'Color',
                                                              Literal((1.0,) * 3))),
                                      ('Weight', weight)], [], comment=flat.label)
        elif kind == 'ShaderNodeBsdfTranslucent':
            normal = self._take_normal(flat)
            b.add('TranslucentBsdf', [('Color', self._operand(flat, 'Color',
                                                              Literal((0.8,) * 3))),
                                      ('Weight', weight)] + normal, [], comment=flat.label)
        elif kind == 'ShaderNodeBsdfVelvet':
            normal = self._take_normal(flat)
            b.add('VelvetBsdf', [('Color', self._operand(flat, 'Color', Literal((0.8,) * 3))),
                                 ('Sigma', self._operand(flat, 'Sigma', Literal(1.0))),
                                 ('Weight', weight)] + normal, [], comment=flat.label)


def write(mw, surface):
    """Writes the surface's lobes, emission and normal (writes_lobes(surface) holds)."""
    keys = []
    _normal_keys(surface, keys)
    # One Normal linked by every BSDF is the material's (as before per-lobe normals, so such
    # a material's graph and image are unchanged); any other case gives each lobe its own.
    shared = bool(keys) and keys[0] is not None and all(k == keys[0] for k in keys)
    w = _Writer(mw, per_lobe_normals=not shared and any(k is not None for k in keys))
    w.write(surface, Literal(1.0))
    b = mw.builder
    if w.emissions:
        total = w.emissions[0]
        for e in w.emissions[1:]:
            link = b.new_link()
            b.add('Add', [('A', total), ('B', e)], [('Out', link)], comment='emission sum')
            total = link
        b.add('EmissionOutput', [('Color', total), ('Strength', Literal(1.0))], [])
    if w.normal is not None:
        b.add('NormalOutput', [('In', w.normal)], [])

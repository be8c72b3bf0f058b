"""Shader trees of BSDF lobes -> memograph's BSDF sinks (nodes/bsdf.inc).

A surface whose shader tree holds only Diffuse, Glossy, Velvet, Refraction, Glass,
Transparent and Translucent BSDFs, Blender 3.x Principled BSDFs (v1), Emission, and Mix and
Add Shaders between them is written exactly: each BSDF becomes a sink that adds its lobes
(DiffuseBsdf, GlossyBsdf, VelvetBsdf, RefractionBsdf, GlassBsdf, TransparentBsdf,
TranslucentBsdf; PrincipledBsdf, one lobe and one per layer in use) with a weight, Mix Shader
becomes a MixShader node that splits its weight by Fac, Add Shader gives both its shaders its
weight, and the emissions, weighted likewise, are summed into one EmissionOutput. This is
Cycles' own closure weighting (svm_node_mix_closure, svm_node_closure_bsdf), so the runtime
samples the same BSDF (docs/design/closures.md).

One hit holds at most MAX_LOBES lobes and one Principled BSDF's parameters. A Mix or Add
Shader whose two sides together need more is written with a ChooseShader after its weights:
each hit takes one side, by weight, at the weight of both (Cycles' mixed BSDF in
expectation). Which ones is decided bottom-up (_Plan): a node stays exact (both sides at
every hit) where its sides fit together, so a tree that fits is written as without choices.
The emissions keep the exact weights. A Principled BSDF that is the surface shader itself, or
added to an emission, stays with shaders.py (PrincipledOutput, and PrincipledLayers where its
layers are in use); any other shader in the tree (Subsurface, a 4.x Principled BSDF, ...)
keeps the Principled approximation of shaders.py.

Each BSDF is shaded about its own Normal, as Cycles shades each closure: where every BSDF
that has a normal links the same one, it is the material's normal (NormalOutput); otherwise
each linked Normal goes to its sink's Normal input, and an unlinked one means the material's
normal, the interpolated one (Cycles' sd->N). A Principled BSDF among them (PrincipledBsdf)
takes its Normal the same way and its Clearcoat Normal as ClearcoatNormal (unlinked under a
linked Normal: the interpolated normal, as Cycles' clearcoat takes sd->N).

A Principled BSDF among them whose Alpha is linked or not 1 is written as Cycles expands it
(PrincipledBsdfNode::expand): its lobes and emission at weight x Alpha, and a white
TransparentBsdf at weight x (1 - Alpha), one lobe more for the hit (where its layers already
take all MAX_LOBES, the Alpha is warned and dropped).
"""

from . import compat
from . import shaders
from .graph import Const, Out
from .mgraph import Literal

MAX_LOBES = 4  # MG_MAX_LOBES of nodes/prelude/common.inc
# The Distribution input of GlossyBsdf, RefractionBsdf and GlassBsdf (nodes/bsdf.inc); any
# other Blender distribution is written as GGX (0), warned where it differs.
DISTRIBUTIONS = {'GGX': 0, 'BECKMANN': 1, 'SHARP': 2}
PRINCIPLED = 'ShaderNodeBsdfPrincipled'
# PrincipledBsdf's Layers bits: the layers whose input is in use get a lobe each.
_LAYER_BITS = (('Sheen', 1), ('Clearcoat', 2), ('Transmission', 4))

LOBE_NODES = ('ShaderNodeBsdfDiffuse', 'ShaderNodeBsdfGlossy', 'ShaderNodeBsdfVelvet',
              'ShaderNodeBsdfRefraction', 'ShaderNodeBsdfGlass', 'ShaderNodeBsdfTransparent',
              'ShaderNodeBsdfTranslucent')
TREE_NODES = LOBE_NODES + ('ShaderNodeEmission', 'ShaderNodeMixShader',
                           'ShaderNodeAddShader')


def _shader_node(source):
    """The FlatNode a shader Source comes from, or None (unlinked, a value)."""
    return source.node if isinstance(source, Out) else None


def _is_v1_principled(flat):
    """A Blender 3.x Principled BSDF (v1, with a Specular factor): one PrincipledBsdf sink."""
    return (flat.bl_idname == PRINCIPLED and
            compat.find_input(flat.node, 'Specular', 'Specular IOR Level') == 'Specular')


def _layer_bits(flat):
    """PrincipledBsdf's Layers: the sheen, clearcoat and transmission whose input is in use."""
    return sum(bit for name, bit in _LAYER_BITS if shaders._in_use(flat, name))


def _principled_lobes(flat):
    return 1 + bin(_layer_bits(flat)).count('1')


class _Need:
    """What a shader tree needs at one hit: lobes and sets of Principled outputs."""

    def __init__(self, lobes=0, principled=0):
        self.lobes = lobes
        self.principled = principled

    def fits(self):
        return self.lobes <= MAX_LOBES and self.principled <= 1


class _Plan:
    """Which Mix and Add Shaders of a tree choose one side per hit (ChooseShader), decided
    bottom-up: a node whose sides fit one hit together stays exact; else it chooses, and needs
    the larger side's lobes. Counts the tree's BSDFs and Principled BSDFs on the way."""

    def __init__(self):
        self.choosing = set()  # keys of the Mix/Add FlatNodes that choose
        self.bsdfs = 0         # BSDF nodes other than Principled BSDFs
        self.principled = 0
        self.mixes = 0

    def need(self, source):
        """The tree's _Need at source, or None when some shader of it is not one that lobes
        express (then shaders.py writes the whole surface)."""
        if source is None or isinstance(source, Const):
            return _Need()  # an unlinked shader socket: no closure
        flat = _shader_node(source)
        if flat is None:
            return None
        kind = flat.bl_idname
        if kind in LOBE_NODES:
            self.bsdfs += 1
            return _Need(1, 0)
        if kind == 'ShaderNodeEmission':
            return _Need()
        if _is_v1_principled(flat):
            self.principled += 1
            return _Need(_principled_lobes(flat) + (1 if _alpha_lobe(flat) else 0), 1)
        if kind not in ('ShaderNodeMixShader', 'ShaderNodeAddShader'):
            return None
        if kind == 'ShaderNodeMixShader':
            self.mixes += 1
        a = self.need(flat.input('Shader'))
        b = self.need(flat.input('Shader_001'))
        if a is None or b is None:
            return None
        both = _Need(a.lobes + b.lobes, a.principled + b.principled)
        if both.fits():
            return both
        self.choosing.add(flat.key)
        return _Need(max(a.lobes, b.lobes), max(a.principled, b.principled))


def plan_lobes(surface):
    """The _Plan of a surface written as lobes, or None where shaders.py writes it: a tree with
    a shader that lobes do not express, without any BSDF, or whose only BSDF is one Principled
    BSDF outside any Mix Shader (the surface shader itself, or added to emissions: exact
    there, with the layers, as before)."""
    plan = _Plan()
    need = plan.need(surface)
    if need is None or need.lobes == 0:
        return None
    if plan.bsdfs == 0 and plan.principled == 1 and plan.mixes == 0:
        return None
    return plan


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
    Transparent; a Principled BSDF's too) to keys, as _source_key gives it."""
    flat = _shader_node(source)
    if flat is None:
        return
    if flat.bl_idname in ('ShaderNodeMixShader', 'ShaderNodeAddShader'):
        _normal_keys(flat.input('Shader'), keys)
        _normal_keys(flat.input('Shader_001'), keys)
    elif ((flat.bl_idname in LOBE_NODES and flat.bl_idname != 'ShaderNodeBsdfTransparent')
          or flat.bl_idname == PRINCIPLED):
        keys.append(_source_key(flat.input('Normal')) if flat.is_linked('Normal') else None)


def writes_lobes(mw, surface):
    """Whether the surface is written as lobes (plan_lobes)."""
    return plan_lobes(surface) is not None


class _Writer:
    def __init__(self, mw, plan, per_lobe_normals):
        self.mw = mw
        self.plan = plan
        self.streams = 0     # ChooseShaders written: each draws its own number (Stream)
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

    def _choose(self, flat, weight_a, weight_b):
        """ChooseShader over two weights: each hit keeps one side, at both weights."""
        b = self.mw.builder
        ca, cb = b.new_link(), b.new_link()
        b.add('ChooseShader', [('WeightA', weight_a), ('WeightB', weight_b),
                               ('Stream', Literal(self.streams, form='int'))],
              [('ChosenA', ca), ('ChosenB', cb)],
              comment=flat.label + ' chosen per hit (its sides do not fit one hit together)')
        self.streams += 1
        return ca, cb

    def write(self, source, weight, emission_weight=None):
        """Writes the tree at source: its BSDFs' lobes at weight (ChooseShader's below a
        choice), its emissions at emission_weight (the exact weight; weight where None)."""
        flat = _shader_node(source)
        if flat is None:
            return
        if emission_weight is None:
            emission_weight = weight
        kind = flat.bl_idname
        b = self.mw.builder
        choosing = flat.key in self.plan.choosing
        if kind == 'ShaderNodeMixShader':
            fac = self._operand(flat, 'Fac', Literal(0.5))
            wa, wb = b.new_link(), b.new_link()
            b.add('MixShader', [('Fac', fac), ('Weight', weight)],
                  [('WeightA', wa), ('WeightB', wb)], comment=flat.label)
            ea, eb = wa, wb
            if emission_weight is not weight and _emits(flat):
                ea, eb = b.new_link(), b.new_link()
                b.add('MixShader', [('Fac', fac), ('Weight', emission_weight)],
                      [('WeightA', ea), ('WeightB', eb)], comment=flat.label + ' emission')
            if choosing:
                wa, wb = self._choose(flat, wa, wb)
            self.write(flat.input('Shader'), wa, ea)
            self.write(flat.input('Shader_001'), wb, eb)
        elif kind == 'ShaderNodeAddShader':
            wa, wb = (self._choose(flat, weight, weight) if choosing else (weight, weight))
            self.write(flat.input('Shader'), wa, emission_weight)
            self.write(flat.input('Shader_001'), wb, emission_weight)
        elif kind == PRINCIPLED:
            self._principled(flat, weight, emission_weight)
        elif kind == 'ShaderNodeEmission':
            color = self._operand(flat, 'Color', Literal((1.0, 1.0, 1.0)))
            strength = self._operand(flat, 'Strength', Literal(1.0))
            emitted = self._weighted(color, strength, flat.label + ' emission x strength')
            self.emissions.append(self._weighted(emitted, emission_weight,
                                                 flat.label + ' weight'))
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
                # Distribution 2: a mirror, Cycles' separate reflection closure (which Filter
                # Glossy does not widen, unlike GGX of Roughness 0).
                roughness = Literal(0.0)
            elif distribution == 'MULTI_GGX':
                self.mw.warn(flat, 'Multiscatter GGX is written as single-scatter GGX: the '
                             'energy that multiple scattering adds back at high Roughness '
                             'is missing')
            elif distribution not in ('GGX', 'BECKMANN'):
                self.mw.warn(flat, 'distribution %s is written as GGX' % distribution)
            b.add('GlossyBsdf', [('Color', self._operand(flat, 'Color', Literal((0.8,) * 3))),
                                 ('Roughness', roughness),
                                 ('Distribution', Literal(DISTRIBUTIONS.get(distribution, 0),
                                                          form='int')),
                                 ('Weight', weight)] + normal, [], comment=flat.label)
        elif kind in ('ShaderNodeBsdfRefraction', 'ShaderNodeBsdfGlass'):
            normal = self._take_normal(flat)
            distribution = getattr(flat.node, 'distribution', 'GGX')
            roughness = self._operand(flat, 'Roughness', Literal(0.0))
            if distribution == 'SHARP':  # Distribution 2: Cycles' sharp closures (as Glossy's)
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
                         ('Distribution', Literal(DISTRIBUTIONS.get(distribution, 0),
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


    def _principled(self, flat, weight, emission_weight):
        """A v1 Principled BSDF among other shaders: PrincipledBsdf, which writes the
        Principled outputs where its weight is above 0 and adds its lobes."""
        mw = self.mw
        normals = self._take_normal(flat)
        if _layer_bits(flat) & 2:
            # Cycles 3.4 shades the clearcoat about Clearcoat Normal, and about the interpolated
            # normal sd->N where it is unlinked, not about the (maybe bumped) Normal.
            clearcoat_normal = shaders._normal(mw, flat, 'Clearcoat Normal')
            if clearcoat_normal is None and flat.is_linked('Normal'):
                clearcoat_normal = mw.implicit('normal')
            if clearcoat_normal is not None:
                normals.append(('ClearcoatNormal', clearcoat_normal))
        shaders._warn_unused(mw, flat, compat.PRINCIPLED_UNCARRIED)
        distribution = getattr(flat.node, 'distribution', 'GGX')
        if distribution == 'MULTI_GGX':
            mw.warn(flat, 'Multiscatter GGX is written as single-scatter GGX (Cycles uses '
                    'multiscatter above Roughness 0.075, and for Transmission above 0.05: rough '
                    'speculars are brighter there)')
        if _has_alpha(flat) and not _alpha_lobe(flat):
            mw.warn(flat, 'Alpha of a Principled BSDF under a Mix or Add Shader is not carried '
                    'when its sheen, clearcoat and transmission are all in use (with them its '
                    'Transparent share would be a fifth lobe): ignored (opaque)')
        if _alpha_lobe(flat):
            # Cycles' expansion (scene/shader_nodes.cpp PrincipledBsdfNode::expand): Mix(Fac =
            # Alpha, Transparent BSDF (white), Principled BSDF + its emission), so the
            # Principled lobes and the emission take weight x Alpha and a white Transparent
            # lobe weight x (1 - Alpha); the Transparent lobe is one more of the hit's lobes
            # (_Plan counts it).
            b = mw.builder
            alpha = shaders._in(mw, flat, 'Alpha')
            transparent, principled = b.new_link(), b.new_link()
            b.add('MixShader', [('Fac', alpha), ('Weight', weight)],
                  [('WeightA', transparent), ('WeightB', principled)],
                  comment=flat.label + ' Alpha')
            b.add('TransparentBsdf', [('Color', Literal((1.0, 1.0, 1.0))),
                                      ('Weight', transparent)], [],
                  comment=flat.label + ' Alpha: the transparent share')
            weight = principled
            if _emits(flat):
                clamped = b.new_link()  # MixShader's Fac is clamped so (svm_node_mix_closure)
                b.add('Saturate', [('In', alpha)], [('Out', clamped)],
                      comment=flat.label + ' Alpha')
                emission_weight = self._weighted(clamped, emission_weight,
                                                 flat.label + ' Alpha: emission weight')
        operands = [('BaseColor', shaders._in(mw, flat, 'Base Color')),
                    ('Metallic', shaders._in(mw, flat, 'Metallic')),
                    ('Roughness', shaders._in(mw, flat, 'Roughness')),
                    ('Specular', shaders._in(mw, flat, 'Specular')),
                    ('SpecularTint', shaders._in(mw, flat, 'Specular Tint') or Literal(0.0))]
        layers = shaders._principled_layers(mw, flat, distribution == 'MULTI_GGX')
        if layers is not None:
            operands += [(socket, layers[socket]) for socket, _, _ in shaders._LAYER_SOCKETS]
        operands += [('Layers', Literal(_layer_bits(flat), form='int')), ('Weight', weight)]
        operands += normals
        mw.builder.add('PrincipledBsdf', [(k, v) for k, v in operands if v is not None], [],
                       comment=flat.label)
        if _emits(flat):
            color = shaders._in(mw, flat, 'Emission', 'Emission Color')
            strength = shaders._in(mw, flat, 'Emission Strength') or Literal(1.0)
            emitted = self._weighted(color, strength, flat.label + ' emission x strength')
            self.emissions.append(self._weighted(emitted, emission_weight,
                                                 flat.label + ' weight'))


def _has_alpha(flat):
    """Whether a Principled BSDF's Alpha is linked or not 1: Cycles then expands it into a
    Mix with a Transparent BSDF (PrincipledBsdfNode::expand)."""
    ident = compat.find_input(flat.node, 'Alpha')
    return ident is not None and not _is_const(flat, ident, 1.0)


def _alpha_lobe(flat):
    """Whether a mixed Principled BSDF's Alpha is written as a Transparent lobe: it has one
    (_has_alpha) and its lobes with that one fit a hit."""
    return _has_alpha(flat) and _principled_lobes(flat) + 1 <= MAX_LOBES


def _is_const(flat, name, value):
    src = flat.input(name)
    return isinstance(src, Const) and src.value == value


def _emits(flat):
    """Whether the tree at flat may emit: an Emission shader, or a Principled BSDF whose
    Emission is linked or not black (and its Strength not 0)."""
    kind = flat.bl_idname
    if kind == 'ShaderNodeEmission':
        return True
    if kind == PRINCIPLED:
        ident = compat.find_input(flat.node, 'Emission', 'Emission Color')
        strength = compat.find_input(flat.node, 'Emission Strength')
        if ident is None:
            return False
        color = flat.input(ident)
        if isinstance(color, Const) and tuple(color.value)[:3] == (0.0, 0.0, 0.0):
            return False
        return not (strength is not None and _is_const(flat, strength, 0.0))
    if kind in ('ShaderNodeMixShader', 'ShaderNodeAddShader'):
        return any(_emits(child) for child in
                   (_shader_node(flat.input(n)) for n in ('Shader', 'Shader_001'))
                   if child is not None)
    return False


def write(mw, surface):
    """Writes the surface's lobes, emission and normal (writes_lobes(surface) holds)."""
    keys = []
    _normal_keys(surface, keys)
    # One Normal linked by every BSDF is the material's (as before per-lobe normals, so such
    # a material's graph and image are unchanged); any other case gives each lobe its own.
    shared = bool(keys) and keys[0] is not None and all(k == keys[0] for k in keys)
    w = _Writer(mw, plan_lobes(surface),
                per_lobe_normals=not shared and any(k is not None for k in keys))
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

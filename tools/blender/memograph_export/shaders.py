"""Shader nodes -> memograph outputs.

memograph materials have one BRDF (Principled subset: base colour, metallic, roughness,
specular, specular tint, emission, opacity, normal; nodes/outputs.inc). A shader node is
evaluated into a Params record of those fields (operands), shader mixing blends the fields,
and the material writes them once at the end. Everything but Principled BSDF is an
approximation and says so in a warning naming the material, the node and what was used.

A Blender 3.x Principled BSDF (v1) also sets cycles_principled = 1: memograph's BRDF then
weights and shapes its diffuse and specular as Cycles 3.4 does (runtime/shaders/common/brdf.glsl,
docs/guide/blender.md "Principled BSDF"); every other shader, and 4.x's v2, keeps memograph's
own energy-conserving weighting (0). A v1 Principled BSDF whose Sheen, Clearcoat or
Transmission is in use also writes PrincipledLayers (nodes/bsdf.inc): the BRDF, its sheen, its
clearcoat and its transmission as lobes, when it is the surface shader itself. Under a Mix
Shader, or an Add Shader with another BSDF, lobes.py writes it (PrincipledBsdf); only a tree
with a shader that lobes do not express comes here mixed, and drops the layers, warned. The
clearcoat is shaded about its Clearcoat Normal (PrincipledLayers' ClearcoatNormal).
"""

from . import compat
from .graph import Const, Convert, Out, SHADER
from .mgraph import Link, Literal

FIELDS = ('base_color', 'metallic', 'roughness', 'specular', 'specular_tint',
          'cycles_principled', 'emission', 'alpha')
_COLOR_FIELDS = ('base_color', 'emission')


class Params:
    """Principled-subset parameters as operands. emission is colour x strength."""

    def __init__(self, **kw):
        self.base_color = kw.get('base_color', Literal((0.8, 0.8, 0.8)))
        self.metallic = kw.get('metallic', Literal(0.0))
        self.roughness = kw.get('roughness', Literal(0.5))
        self.specular = kw.get('specular', Literal(0.5))
        self.specular_tint = kw.get('specular_tint', Literal(0.0))
        self.cycles_principled = kw.get('cycles_principled', Literal(0.0))
        self.emission = kw.get('emission', Literal((0.0, 0.0, 0.0)))
        self.emission_strength = kw.get('emission_strength', Literal(1.0))
        self.alpha = kw.get('alpha', Literal(1.0))
        self.normal = kw.get('normal')  # operand or None (geometric normal)
        self.pure_emission = kw.get('pure_emission', False)
        # A v1 Principled BSDF's sheen, clearcoat and transmission: a dict of PrincipledLayers'
        # operands by socket, or None (none in use).
        self.layers = kw.get('layers')

    def emission_product(self, mw):
        """emission x emission_strength as one operand (folds constant strength 1)."""
        s = self.emission_strength
        if isinstance(s, Literal) and float(s.value) == 1.0:
            return self.emission
        link = mw.builder.new_link()
        mw.builder.add('Mul', [('A', self.emission), ('B', s)], [('Out', link)],
                       comment='emission x strength')
        self.emission = link
        self.emission_strength = Literal(1.0)
        return link


def black():
    """What an unlinked/empty surface gives in Cycles: no closure, a black surface."""
    return Params(base_color=Literal((0.0, 0.0, 0.0)), specular=Literal(0.0))


def _in(mw, flat, *names):
    """The operand of the first available input among names (4.x renames), or None."""
    ident = compat.find_input(flat.node, *names)
    return None if ident is None else mw.input_operand(flat, ident)


def _normal(mw, flat, name='Normal'):
    ident = compat.find_input(flat.node, name)
    if ident is None or not flat.is_linked(ident):
        return None
    return mw.input_operand(flat, ident)


def _warn_unused(mw, flat, checks):
    """Warns for each Principled feature memograph does not carry that is in use."""
    for names, default, what in checks:  # default: the values that mean "off"
        ident = compat.find_input(flat.node, *names)
        if ident is None:
            continue
        src = flat.input(ident)
        if src is None:
            continue
        if not isinstance(src, Const):
            mw.warn(flat, '%s is linked but not carried: ignored' % what)
        elif src.kind != SHADER and src.value not in default:
            mw.warn(flat, '%s = %s is not carried: ignored' % (what, _fmt(src.value)))


def _in_use(flat, name):
    """Whether input name is linked or set off 0 (its operand would change the result)."""
    ident = compat.find_input(flat.node, name)
    if ident is None:
        return False
    src = flat.input(ident)
    return src is not None and (not isinstance(src, Const) or src.value != 0.0)


# PrincipledLayers' sockets: (socket, Blender 3.4's input, its default).
_LAYER_SOCKETS = (('Sheen', 'Sheen', 0.0), ('SheenTint', 'Sheen Tint', 0.5),
                  ('Clearcoat', 'Clearcoat', 0.0),
                  ('ClearcoatRoughness', 'Clearcoat Roughness', 0.03),
                  ('Transmission', 'Transmission', 0.0),
                  ('TransmissionRoughness', 'Transmission Roughness', 0.0), ('IOR', 'IOR', 1.45))


def _principled_layers(mw, flat, multiscatter):
    """The PrincipledLayers operands of a v1 Principled BSDF whose Sheen, Clearcoat or
    Transmission is in use, or None. multiscatter: Multiscatter GGX, whose glass Cycles
    takes of the one roughness (Transmission Roughness unused)."""
    if not any(_in_use(flat, name) for name in ('Sheen', 'Clearcoat', 'Transmission')):
        return None
    # Blender 3.4's defaults where a socket is missing (a hand-made node group's stand-in).
    layers = {socket: _in(mw, flat, name) or Literal(default)
              for socket, name, default in _LAYER_SOCKETS}
    if multiscatter:
        layers['TransmissionRoughness'] = Literal(0.0)
    return layers


def _warn_layers_dropped(mw, flat, *params):
    """A mixed Principled BSDF's layers (sheen, clearcoat, transmission) are not carried:
    says so."""
    if any(p.layers is not None for p in params):
        mw.warn(flat, 'the Sheen, Clearcoat and Transmission of a Principled BSDF under a %s '
                'are not carried (only a Principled BSDF that is the surface shader itself has '
                'them): ignored' % flat.node.bl_idname.replace('ShaderNode', ''))


def _fmt(v):
    if isinstance(v, tuple):
        return '(' + ', '.join('%.3g' % x for x in v) + ')'
    return '%.3g' % v


def principled(mw, flat):
    """Principled BSDF (v1 in 3.x, v2 in 4.x: socket names via compat)."""
    node = flat.node
    p = Params()
    p.base_color = _in(mw, flat, 'Base Color')
    p.metallic = _in(mw, flat, 'Metallic')
    p.roughness = _in(mw, flat, 'Roughness')
    spec_ident = compat.find_input(node, 'Specular', 'Specular IOR Level')
    p.specular = mw.input_operand(flat, spec_ident) if spec_ident else Literal(0.5)
    if spec_ident == 'Specular IOR Level':
        mw.warn(flat, 'Principled v2 "Specular IOR Level" is written as memograph Specular '
                '(0.5 = the IOR\'s own reflectance in both); IOR itself is not carried')
    # v1 (3.x): Specular Tint is a factor, carried, and the closures are weighted as Cycles
    # 3.4 weights them. v2 (4.x) is another model (a layered, energy-conserving dielectric
    # with a colour Specular Tint), nearer memograph's own weighting: cycles_principled 0.
    v1 = spec_ident == 'Specular'
    p.cycles_principled = Literal(1.0 if v1 else 0.0)
    tint_ident = compat.find_input(node, 'Specular Tint')
    tint_socket = flat.socket(tint_ident) if tint_ident else None
    if tint_socket is not None and tint_socket.type == 'VALUE':
        p.specular_tint = mw.input_operand(flat, tint_ident) or Literal(0.0)
    p.emission = _in(mw, flat, 'Emission', 'Emission Color') or Literal((0.0, 0.0, 0.0))
    p.emission_strength = _in(mw, flat, 'Emission Strength') or Literal(1.0)
    p.alpha = _in(mw, flat, 'Alpha') or Literal(1.0)
    p.normal = _normal(mw, flat)
    checks = compat.PRINCIPLED_UNCARRIED
    distribution = getattr(node, 'distribution', 'GGX')
    if v1:
        p.layers = _principled_layers(mw, flat, distribution == 'MULTI_GGX')
        if p.layers is not None:
            # Cycles 3.4 shades the clearcoat about Clearcoat Normal, and about the interpolated
            # normal sd->N where it is unlinked, not about the (maybe bumped) Normal.
            clearcoat_normal = _normal(mw, flat, 'Clearcoat Normal')
            if clearcoat_normal is None and p.normal is not None:
                clearcoat_normal = mw.implicit('normal')
            if clearcoat_normal is not None:
                p.layers['ClearcoatNormal'] = clearcoat_normal
    else:
        checks = checks + compat.PRINCIPLED_V2_LAYERS
    if tint_socket is not None and tint_socket.type != 'VALUE':
        checks = checks + (compat.PRINCIPLED_V2_SPECULAR_TINT,)
    _warn_unused(mw, flat, checks)
    if v1 and distribution == 'MULTI_GGX':
        mw.warn(flat, 'Multiscatter GGX is written as single-scatter GGX (Cycles uses '
                'multiscatter above Roughness 0.075, and for Transmission above 0.05: rough '
                'speculars are brighter there)')
    return p


def diffuse(mw, flat):
    mw.warn(flat, 'Diffuse BSDF approximated as Principled: Base Color = Color, Specular 0, '
            'Roughness 1 (Oren-Nayar roughness not carried)')
    return Params(base_color=_in(mw, flat, 'Color'), specular=Literal(0.0),
                  roughness=Literal(1.0), normal=_normal(mw, flat))


def glossy(mw, flat):
    mw.warn(flat, 'Glossy BSDF approximated as Principled Metallic 1 with its Color and '
            'Roughness (distribution %s not carried)' % getattr(flat.node, 'distribution', '?'))
    return Params(base_color=_in(mw, flat, 'Color'), metallic=Literal(1.0),
                  roughness=_in(mw, flat, 'Roughness'), normal=_normal(mw, flat))


def emission(mw, flat):
    # Not an approximation on its own: memograph's emission output is exactly this.
    return Params(base_color=Literal((0.0, 0.0, 0.0)), specular=Literal(0.0),
                  emission=_in(mw, flat, 'Color'), emission_strength=_in(mw, flat, 'Strength'),
                  pure_emission=True)


def transparent(mw, flat):
    mw.warn(flat, 'Transparent BSDF approximated as opacity 0 (its tint Color is not '
            'carried)')
    return Params(alpha=Literal(0.0))


def mix_shader(mw, flat):
    a = mw.shader(flat.input('Shader'))
    b = mw.shader(flat.input('Shader_001'))
    _warn_layers_dropped(mw, flat, a, b)
    if not (a.pure_emission and b.pure_emission):  # two emissions mix exactly
        mw.warn(flat, 'Mix Shader approximated by blending the two shaders\' parameters '
                '(base colour, metallic, roughness, specular, specular tint, Cycles weighting, '
                'emission, alpha, normal) by Fac')
    fac = mw.input_operand(flat, 'Fac')
    clamped = mw.builder.new_link()
    mw.builder.add('Saturate', [('In', fac)], [('Out', clamped)], comment=flat.label + ' Fac')
    out = Params()
    a.emission_product(mw)
    b.emission_product(mw)
    for field in FIELDS:
        va, vb = getattr(a, field), getattr(b, field)
        if _same(va, vb):
            setattr(out, field, va)
            continue
        link = mw.builder.new_link()
        mw.builder.add('Mix', [('A', va), ('B', vb), ('Factor', clamped)], [('Out', link)],
                       comment='%s %s' % (flat.label, field))
        setattr(out, field, link)
    if a.normal is not None or b.normal is not None:
        na = a.normal if a.normal is not None else mw.implicit('normal')
        nb = b.normal if b.normal is not None else mw.implicit('normal')
        link = mw.builder.new_link()
        mw.builder.add('Mix', [('A', na), ('B', nb), ('Factor', clamped)], [('Out', link)],
                       comment='%s normal' % flat.label)
        out.normal = link
    out.pure_emission = a.pure_emission and b.pure_emission
    return out


def add_shader(mw, flat):
    a = mw.shader(flat.input('Shader'))
    b = mw.shader(flat.input('Shader_001'))
    if not (a.pure_emission or b.pure_emission):
        _warn_layers_dropped(mw, flat, a, b)
    if not (a.pure_emission and b.pure_emission):  # two emissions add exactly
        mw.warn(flat, 'Add Shader approximated: emissions are summed, the surface parameters '
                'are those of the %s shader' % ('second' if a.pure_emission else 'first'))
    surface = b if a.pure_emission else a
    # An emission added to a Principled BSDF keeps its layers: the sum is exact.
    other = a if a.pure_emission else b
    out = Params(base_color=surface.base_color, metallic=surface.metallic,
                 roughness=surface.roughness, specular=surface.specular,
                 specular_tint=surface.specular_tint,
                 cycles_principled=surface.cycles_principled, alpha=surface.alpha,
                 normal=surface.normal,
                 layers=surface.layers if other.pure_emission else None)
    ea, eb = a.emission_product(mw), b.emission_product(mw)
    link = mw.builder.new_link()
    mw.builder.add('Add', [('A', ea), ('B', eb)], [('Out', link)], comment=flat.label)
    out.emission = link
    out.pure_emission = a.pure_emission and b.pure_emission
    return out


def _same(a, b):
    if isinstance(a, Link) and isinstance(b, Link):
        return a.id == b.id
    if isinstance(a, Literal) and isinstance(b, Literal):
        return a.value == b.value
    return False


def other_shader(mw, flat):
    """Any other shader: its Color (and Roughness) when it has them, else the defaults."""
    node = flat.node
    kw = {}
    used = []
    if compat.find_input(node, 'Color'):
        kw['base_color'] = _in(mw, flat, 'Color')
        used.append('Base Color = Color')
    if compat.find_input(node, 'Roughness'):
        kw['roughness'] = _in(mw, flat, 'Roughness')
        used.append('Roughness')
    n = _normal(mw, flat)
    if n is not None:
        kw['normal'] = n
        used.append('Normal')
    mw.warn(flat, '%s is not supported: approximated as the default Principled BSDF%s'
            % (node.bl_idname, (' with ' + ', '.join(used)) if used else ''))
    return Params(**kw)


SHADER_WRITERS = {
    'ShaderNodeBsdfPrincipled': principled,
    'ShaderNodeBsdfDiffuse': diffuse,
    'ShaderNodeBsdfGlossy': glossy,
    'ShaderNodeEmission': emission,
    'ShaderNodeBsdfTransparent': transparent,
    'ShaderNodeMixShader': mix_shader,
    'ShaderNodeAddShader': add_shader,
}


def evaluate(mw, source):
    """The Params of a shader Source (Out of a shader node, unlinked, or a converted value)."""
    if source is None or isinstance(source, Const):
        return black()
    if isinstance(source, Convert):
        # A colour/value into a shader socket: Cycles and EEVEE show it as emission.
        value = mw.operand(source.source)
        mw.warn_material('a %s value is linked into a shader socket: written as emission'
                         % source.source.kind)
        return Params(base_color=Literal((0.0, 0.0, 0.0)), specular=Literal(0.0),
                      emission=value, pure_emission=True)
    flat = source.node
    fn = SHADER_WRITERS.get(flat.bl_idname, other_shader)
    return fn(mw, flat)


def write_outputs(mw, params):
    """Writes the material's output nodes for params."""
    b = mw.builder
    if params.pure_emission:
        b.add('EmissionOutput', [('Color', params.emission),
                                 ('Strength', params.emission_strength)], [],
              comment='Emission shader')
        b.add('BaseColorOutput', [('In', Literal((0.0, 0.0, 0.0)))], [])
        b.add('SpecularOutput', [('In', Literal(0.0))], [])
        if not (isinstance(params.alpha, Literal) and params.alpha.value == 1.0):
            b.add('OpacityOutput', [('In', params.alpha)], [])
        return
    b.add('PrincipledOutput', [
        ('BaseColor', params.base_color), ('Metallic', params.metallic),
        ('Roughness', params.roughness), ('Specular', params.specular),
        ('Emission', params.emission), ('EmissionStrength', params.emission_strength),
        ('Alpha', params.alpha), ('SpecularTint', params.specular_tint),
        ('CyclesPrincipled', params.cycles_principled)], [])
    if params.layers is not None:
        # The sheen's weight and tint come from the same base colour and metallic.
        b.add('PrincipledLayers', [('BaseColor', params.base_color),
                                   ('Metallic', params.metallic),
                                   ('Roughness', params.roughness)] +
              [(socket, params.layers[socket]) for socket, _, _ in _LAYER_SOCKETS] +
              [(socket, params.layers[socket]) for socket in ('ClearcoatNormal',)
               if socket in params.layers], [],
              comment='Principled sheen, clearcoat and transmission')
    if params.normal is not None:
        b.add('NormalOutput', [('In', params.normal)], [])

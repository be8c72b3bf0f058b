"""Blender version differences, handled as name lookups with fallbacks.

Checked on Blender 3.4 (the tests run there). The 4.x branches follow the 4.0-4.2 Python API
and release notes (Principled BSDF v2 in 4.0, Musgrave folded into Noise in 4.1, fractal
Voronoi in 4.0) and are unit-tested with fake node objects only
(tests/blender/exporter_unit_test.py).
"""


def find_input(node, *names):
    """The identifier of the first available input whose identifier or name is in names
    (tried in order: the 3.4 name first, then 4.x renames), or None."""
    for name in names:
        for s in node.inputs:
            if s.identifier == name and s.enabled:
                return s.identifier
        for s in node.inputs:
            if s.name == name and s.enabled:
                return s.identifier
    return None


_OFF = (0.0,)
_WHITE = ((1.0, 1.0, 1.0),)

# Principled features memograph's BRDF does not have: (names 3.4 then 4.x, values meaning
# "off", what to call it). A linked socket or another value is reported. 3.4's Specular
# Tint (a factor) is carried (shaders.principled); 4.x's colour Specular Tint is not.
# 3.4's (v1) Sheen, Sheen Tint, Clearcoat, Clearcoat Roughness, Transmission, Transmission
# Roughness, IOR and Clearcoat Normal are carried as the PrincipledLayers lobes
# (shaders.principled); 4.x's Sheen Weight, Coat Weight, Transmission Weight and Coat Normal,
# another model (PRINCIPLED_V2_LAYERS), are not.
PRINCIPLED_UNCARRIED = (
    (('Subsurface', 'Subsurface Weight'), _OFF, 'Subsurface'),
    (('Anisotropic',), _OFF, 'Anisotropic'),
    (('Coat Normal',), ((0.0, 0.0, 0.0),), 'Coat Normal'),
    (('Tangent',), ((0.0, 0.0, 0.0),), 'Tangent'),
    (('Thin Film Thickness',), _OFF, 'Thin Film'),
)
PRINCIPLED_V2_LAYERS = (
    (('Sheen Weight',), _OFF, 'Sheen'),
    (('Coat Weight',), _OFF, 'Coat'),
    (('Transmission Weight',), _OFF, 'Transmission'),
)
PRINCIPLED_V2_SPECULAR_TINT = (('Specular Tint',), _WHITE, 'Specular Tint (4.x colour)')

# Inputs that exist only in 4.x and that no 3.4-based spec carries: (node, identifier) ->
# values that mean "as in 3.4". Another value, or a link, is reported by check_new_inputs.
NEW_IN_4X = {
    ('ShaderNodeTexVoronoi', 'Detail'): (0.0,),
    ('ShaderNodeTexVoronoi', 'Roughness'): None,  # irrelevant while Detail is 0
    ('ShaderNodeTexVoronoi', 'Lacunarity'): None,
    ('ShaderNodeTexNoise', 'Lacunarity'): (2.0,),
}


def check_new_inputs(node, inputs_value, warn, carried=()):
    """Warns for 4.x-only inputs in use that the node's writer does not carry (carried:
    the identifiers its spec maps). inputs_value(identifier) -> (linked, value)."""
    for (idname, ident), ok in NEW_IN_4X.items():
        if node.bl_idname != idname or ok is None or ident in carried:
            continue
        for s in node.inputs:
            if s.identifier == ident and s.enabled:
                linked, value = inputs_value(ident)
                if linked:
                    warn('%s is linked (Blender 4.x input) but not carried: ignored' % s.name)
                elif value not in ok:
                    warn('%s = %g (Blender 4.x input) is not carried: %g is used'
                         % (s.name, value, ok[0]))


MUSGRAVE_TYPES = ('MULTIFRACTAL', 'RIDGED_MULTIFRACTAL', 'HYBRID_MULTIFRACTAL',
                  'FBM', 'HETERO_TERRAIN')


def noise_type(node):
    """Blender 4.1 folded Musgrave into Noise (node.noise_type). Returns the type, or None
    on Blender < 4.1 (plain fBm noise)."""
    return getattr(node, 'noise_type', None)


def version_warnings(node):
    """Warnings for 4.x features a 3.4-based writer would silently drop."""
    out = []
    kind = noise_type(node) if node.bl_idname == 'ShaderNodeTexNoise' else None
    if kind not in (None, 'FBM'):
        out.append('Blender 4.1+ Noise type %s (the former Musgrave Texture) is not carried: '
                   'written as fBm Noise' % kind)
    if node.bl_idname == 'ShaderNodeTexNoise' and hasattr(node, 'normalize'):
        # Only 4.x Noise has `normalize`; 4.0 also changed the fBm normalisation.
        out.append('Blender 4.x Noise: NoiseTexture computes Blender 3.4\'s fBm '
                   'normalisation%s; results differ when Detail > 0'
                   % ('' if node.normalize else ' ("Normalize" off is not carried)'))
    if node.bl_idname == 'ShaderNodeTexVoronoi' and getattr(node, 'normalize', False):
        out.append('Blender 4.x Voronoi "Normalize" is not carried: ignored')
    return out

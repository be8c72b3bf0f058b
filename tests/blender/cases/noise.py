"""Noise family cases: Noise, Musgrave, White Noise, Wave and Magic textures against Cycles 3.4
(nodes/noise.inc). Every dimension and mode of each node, with the inputs that change the
code path (fractional Detail, Distortion, W, negative coordinates for the lattice hashes).

White noise hashes the exact float bits of its input, and the two bakes' UVs at a pixel
may differ in the last bit (see the smoke cases), which gives a different random value, not
a small error. Its cases (and the `_exact` cases, which show that the other nodes match
Cycles to float rounding whatever the bakes' UVs do) read a snapped input built in Blender
by `_snapped`: floor(UV * 64 + offset) * step, identical bits in both bakes.
"""
from .case import Case, snapped_input as _snapped


DIMS = ('1D', '2D', '3D', '4D')
# (u, v, 0) * 2 - 1 over the plane: negative and positive lattice cells.
CENTRED = ('uv3', 2.0, -1.0)

CASES = []


def _drive(dim, w):
    """Vector (disabled in Blender for 1D, so not driven there) plus the W drive."""
    return dict(w) if dim == '1D' else dict({'Vector': CENTRED}, **w)


# Noise Texture: per dimension, plain noise (one octave), fractal noise with a fractional
# Detail, and distortion; Fac and Color outputs. W drives 1D and 4D.
for dim in DIMS:
    d = dim.lower()
    w = {'W': ('u', -1.5, 3.0)} if dim == '1D' else ({'W': ('v', 0.25, 1.5)} if dim == '4D' else {})
    CASES += [
        Case(name='noise_%s_plain_fac' % d, node='ShaderNodeTexNoise', kind='noise',
             props={'noise_dimensions': dim}, inputs={'Scale': 3.0, 'Detail': 0.0},
             drive=_drive(dim, w), output='Fac'),
        Case(name='noise_%s_detail_color' % d, node='ShaderNodeTexNoise', kind='noise',
             props={'noise_dimensions': dim},
             inputs={'Scale': 4.0, 'Detail': 3.5, 'Roughness': 0.65},
             drive=_drive(dim, w), output='Color'),
        Case(name='noise_%s_distortion_color' % d, node='ShaderNodeTexNoise', kind='noise',
             props={'noise_dimensions': dim},
             inputs={'Scale': 2.5, 'Detail': 2.0, 'Roughness': 0.5, 'Distortion': 1.7},
             drive=_drive(dim, w), output='Color'),
    ]
CASES += [
    Case(name='noise_3d_detail15_fac', node='ShaderNodeTexNoise', kind='noise',
         props={'noise_dimensions': '3D'}, inputs={'Scale': 5.0, 'Detail': 15.0, 'Roughness': 0.5},
         drive={'Vector': 'uv3'}, output='Fac', note='16 octaves'),
]
# Bit-identical inputs (see _snapped): the implementation itself, independent of how the
# bakes place UVs; every dimension with fractional Detail and distortion.
for dim in DIMS:
    CASES.append(Case(
        name='noise_%s_exact_color' % dim.lower(), node='ShaderNodeTexNoise', kind='noise',
        props={'noise_dimensions': dim},
        inputs={'Scale': 2.0, 'Detail': 4.5, 'Roughness': 0.6, 'Distortion': 0.8},
        extra=_snapped({'Vector': 'vec', 'W': 'y'}), output='Color',
        note='snapped input: exact in both bakes'))

# Musgrave Texture: 5 types x 4 dimensions. Fractional Detail everywhere (ridged uses only
# its integer part); Offset and Gain where the type reads them.
MUSGRAVE = {
    'MULTIFRACTAL': {'Detail': 3.5, 'Dimension': 1.2, 'Lacunarity': 2.3},
    'RIDGED_MULTIFRACTAL': {'Detail': 4.0, 'Dimension': 1.1, 'Lacunarity': 2.1, 'Offset': 1.0,
                            'Gain': 2.0},
    'HYBRID_MULTIFRACTAL': {'Detail': 3.5, 'Dimension': 0.9, 'Lacunarity': 2.0, 'Offset': 0.7,
                            'Gain': 1.5},
    'FBM': {'Detail': 3.5, 'Dimension': 1.5, 'Lacunarity': 2.5},
    'HETERO_TERRAIN': {'Detail': 3.5, 'Dimension': 1.3, 'Lacunarity': 2.2, 'Offset': 0.4},
}
for mtype, inputs in MUSGRAVE.items():
    for dim in DIMS:
        w = {'W': ('u', -1.5, 3.0)} if dim == '1D' else (
            {'W': ('v', 0.25, 1.5)} if dim == '4D' else {})
        CASES.append(Case(
            name='musgrave_%s_%s' % (mtype.lower(), dim.lower()), node='ShaderNodeTexMusgrave',
            kind='noise', props={'musgrave_type': mtype, 'musgrave_dimensions': dim},
            inputs=dict({'Scale': 3.0}, **inputs), drive=_drive(dim, w),
            output='Fac'))

for mtype in ('RIDGED_MULTIFRACTAL', 'HYBRID_MULTIFRACTAL', 'HETERO_TERRAIN'):
    CASES.append(Case(
        name='musgrave_%s_4d_exact' % mtype.lower(), node='ShaderNodeTexMusgrave', kind='noise',
        props={'musgrave_type': mtype, 'musgrave_dimensions': '4D'},
        inputs=dict({'Scale': 2.0}, **MUSGRAVE[mtype]),
        extra=_snapped({'Vector': 'vec', 'W': 'x'}), output='Fac',
        note='snapped input: exact in both bakes'))

# White Noise: snapped inputs (negative, zero and positive cells), both outputs.
for dim in DIMS:
    d = dim.lower()
    for out in ('Value', 'Color'):
        CASES.append(Case(name='white_noise_%s_%s' % (d, out.lower()),
                          node='ShaderNodeTexWhiteNoise', props={'noise_dimensions': dim},
                          extra=_snapped({'Vector': 'vec', 'W': 'x'}, step=0.37), output=out,
                          note='snapped input: exact in both bakes'))

# Wave Texture: bands in every direction (sine), rings in every direction (saw), the
# triangle profile, and distortion with detail, detail scale/roughness and phase.
WAVE_VEC = ('uv3', 1.0, (-0.5, -0.3, 0.35))
for direction in ('X', 'Y', 'Z', 'DIAGONAL'):
    CASES.append(Case(name='wave_bands_%s_sin' % direction.lower(), node='ShaderNodeTexWave',
                      props={'wave_type': 'BANDS', 'bands_direction': direction,
                             'wave_profile': 'SIN'},
                      inputs={'Scale': 2.0}, drive={'Vector': WAVE_VEC}, output='Fac'))
# The saw jumps from 1 to 0: any difference of the bakes' UVs can flip a pixel that lies on
# a jump, so the saw cases read a snapped copy of WAVE_VEC (floor(64 uv + offset) / 64).
WAVE_SNAPPED = _snapped({'Vector': 'vec'}, step=1.0 / 64.0, offset=(-32.0, -19.0, 22.0))
for direction in ('X', 'Y', 'Z', 'SPHERICAL'):
    CASES.append(Case(name='wave_rings_%s_saw' % direction.lower(), node='ShaderNodeTexWave',
                      props={'wave_type': 'RINGS', 'rings_direction': direction,
                             'wave_profile': 'SAW'},
                      inputs={'Scale': 1.5}, extra=WAVE_SNAPPED, output='Fac',
                      note='snapped input (saw discontinuities)'))
CASES += [
    Case(name='wave_bands_diagonal_tri', node='ShaderNodeTexWave',
         props={'wave_type': 'BANDS', 'bands_direction': 'DIAGONAL', 'wave_profile': 'TRI'},
         inputs={'Scale': 2.0, 'Phase Offset': 0.7}, drive={'Vector': WAVE_VEC}, output='Color'),
    Case(name='wave_bands_x_distorted_sin', node='ShaderNodeTexWave',
         props={'wave_type': 'BANDS', 'bands_direction': 'X', 'wave_profile': 'SIN'},
         inputs={'Scale': 2.0, 'Distortion': 2.0, 'Detail': 3.5, 'Detail Scale': 2.0,
                 'Detail Roughness': 0.7, 'Phase Offset': 1.3},
         drive={'Vector': WAVE_VEC}, output='Fac'),
    Case(name='wave_bands_y_distorted_exact', node='ShaderNodeTexWave',
         props={'wave_type': 'BANDS', 'bands_direction': 'Y', 'wave_profile': 'SIN'},
         inputs={'Scale': 2.0, 'Distortion': 6.0, 'Detail': 3.5, 'Detail Scale': 2.0,
                 'Detail Roughness': 0.7, 'Phase Offset': 1.3},
         extra=WAVE_SNAPPED, output='Fac', note='snapped input: exact in both bakes'),
    Case(name='wave_rings_spherical_distorted_tri', node='ShaderNodeTexWave',
         props={'wave_type': 'RINGS', 'rings_direction': 'SPHERICAL', 'wave_profile': 'TRI'},
         inputs={'Scale': 1.5, 'Distortion': 3.0, 'Detail': 2.0, 'Detail Scale': 1.5,
                 'Detail Roughness': 0.5}, drive={'Vector': WAVE_VEC}, output='Fac'),
    Case(name='wave_rings_y_distorted_saw', node='ShaderNodeTexWave',
         props={'wave_type': 'RINGS', 'rings_direction': 'Y', 'wave_profile': 'SAW'},
         inputs={'Scale': 1.0, 'Distortion': 2.0, 'Detail': 0.0, 'Detail Scale': 3.0},
         extra=WAVE_SNAPPED, output='Fac', note='snapped input (saw discontinuities)'),
]

# Magic Texture: depths 0..10 (the nested steps), distortion, both outputs. From depth 3
# on, the feedback amplifies any difference of the bakes' UVs (an earlier bake placed them
# ~3e-5 off the pixel centres: up to 9e-3 error at depth 10), so those depths read a
# snapped input (exact in both bakes).
MAGIC_SNAPPED = _snapped({'Vector': 'vec'}, step=1.0 / 32.0)
for depth, distortion in ((0, 1.0), (1, 1.0), (2, 1.0), (3, 2.0), (5, 1.5), (7, 1.2), (10, 1.3)):
    if depth < 3:
        how = dict(drive={'Vector': CENTRED})
    else:
        how = dict(extra=MAGIC_SNAPPED, note='snapped input: exact in both bakes')
    CASES.append(Case(name='magic_depth%d_color' % depth, node='ShaderNodeTexMagic',
                      props={'turbulence_depth': depth},
                      inputs={'Scale': 1.0, 'Distortion': distortion}, output='Color', **how))
CASES += [
    Case(name='magic_depth2_fac', node='ShaderNodeTexMagic', props={'turbulence_depth': 2},
         inputs={'Scale': 2.0, 'Distortion': 1.0}, drive={'Vector': 'uv3'}, output='Fac'),
    Case(name='magic_depth4_nodistortion', node='ShaderNodeTexMagic',
         props={'turbulence_depth': 4}, inputs={'Scale': 2.0, 'Distortion': 0.0},
         drive={'Vector': CENTRED}, output='Color', note='Distortion 0: no final division'),
    Case(name='magic_depth6_exact', node='ShaderNodeTexMagic', props={'turbulence_depth': 6},
         inputs={'Scale': 3.0, 'Distortion': 1.7}, extra=_snapped({'Vector': 'vec'}),
         output='Color', note='snapped input: exact in both bakes'),
]

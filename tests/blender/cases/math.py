"""Cycles comparison cases: Math, Vector Math, Map Range, Clamp, Mix (float, vector, color)
and the legacy MixRGB (nodes/blender_math.inc, nodes/math.inc, nodes/color.inc).

Inputs are driven across negative, zero-crossing and > 1 ranges so that every guard of
Cycles 3.4 (safe_divide, safe_powf, safe_logf, safe_sqrtf, safe_modulo, wrapf, pingpongf,
the burn/dodge/divide guards, ...) is exercised. The drives put pixel centres at
u, v = (i + 0.5) / 64.

The drives are chosen to stay well conditioned even when the baked UV at a pixel centre is
off by ~3e-5 (an earlier revision of the harness showed that: Math ADD of 4u and 4v off by
1.9e-4), since the node under test amplifies such an error by its gradient. So
|gradient * drive scale| stays well below 40: divisors, log bases, wrap ranges, ping-pong
scales and power bases stay away from the singular point (each sign gets its own case), and
the guards' own branches (a divisor of exactly 0, a negative log argument, ...) get
constant-input cases. Discontinuous operations (floor, modulo, snap, wrap, comparisons,
steps, burn/dodge's jumps) use constants and offsets that keep every pixel centre well away
from a jump (checked against the baked images).
"""
from .case import Case, snapped_input

MATH_OPS = ['ADD', 'SUBTRACT', 'MULTIPLY', 'DIVIDE', 'MULTIPLY_ADD', 'POWER', 'LOGARITHM',
            'SQRT', 'INVERSE_SQRT', 'ABSOLUTE', 'EXPONENT', 'MINIMUM', 'MAXIMUM', 'LESS_THAN',
            'GREATER_THAN', 'SIGN', 'COMPARE', 'SMOOTH_MIN', 'SMOOTH_MAX', 'ROUND', 'FLOOR',
            'CEIL', 'TRUNC', 'FRACT', 'MODULO', 'WRAP', 'SNAP', 'PINGPONG', 'SINE', 'COSINE',
            'TANGENT', 'ARCSINE', 'ARCCOSINE', 'ARCTANGENT', 'ARCTAN2', 'SINH', 'COSH', 'TANH',
            'RADIANS', 'DEGREES']

# Default drives: Value over u in [-2, 2], Value_001 over v in [-2.1, 2.2] (never equal to
# Value at a pixel centre, so comparisons are decided by more than the bake's UV error).
_A = ('u', -2.0, 4.0)
_B = ('v', -2.1, 4.3)

# Per operation: (drive, constant inputs). Ranges chosen to cross each guard.
MATH_SETUP = {
    'DIVIDE': ({'Value': _A, 'Value_001': ('v', 0.5, 2.0)}, {}),
    'MULTIPLY_ADD': ({'Value': _A, 'Value_001': _B, 'Value_002': ('u', 1.0, -3.0)}, {}),
    'POWER': ({'Value': ('u', 0.6, 1.3), 'Value_001': ('v', -2.0, 4.5)}, {}),
    'LOGARITHM': ({'Value': ('u', 0.4, 3.0), 'Value_001': ('v', 1.8, 3.0)}, {}),
    'SQRT': ({'Value': ('u', -1.0, 4.0)}, {}),
    # 1/sqrt is steep at 0+: the non-positive side (0) has its own cases.
    'INVERSE_SQRT': ({'Value': ('u', 0.3, 3.0)}, {}),
    'EXPONENT': ({'Value': ('u', -3.0, 4.5)}, {}),
    'COMPARE': ({'Value': ('u', -1.0, 2.0), 'Value_001': ('v', -1.0, 2.0)},
                {'Value_002': 0.3}),
    'SMOOTH_MIN': ({'Value': ('u', -1.0, 2.0), 'Value_001': ('v', -1.0, 2.0),
                    'Value_002': ('u', -0.3, 1.5)}, {}),
    'SMOOTH_MAX': ({'Value': ('u', -1.0, 2.0), 'Value_001': ('v', -1.0, 2.0),
                    'Value_002': ('v', -0.3, 1.5)}, {}),
    'ROUND': ({'Value': ('u', -3.0, 6.0)}, {}),
    'FLOOR': ({'Value': ('u', -3.0, 6.0)}, {}),
    'CEIL': ({'Value': ('u', -3.0, 6.0)}, {}),
    'TRUNC': ({'Value': ('u', -3.0, 6.0)}, {}),
    'FRACT': ({'Value': ('u', -3.0, 6.0)}, {}),
    # The discontinuous operations get constant divisors / ranges whose jumps fall >= 1/96
    # of a period from every pixel centre (the bake's UV error moves a jump by < 1e-3 of one).
    'MODULO': ({'Value': ('u', -3.0, 6.0)}, {'Value_001': 0.375}),
    'WRAP': ({'Value': ('u', -3.0, 6.0)}, {'Value_001': 1.2, 'Value_002': 0.3}),
    # Snap's jumps: a constant increment puts every pixel centre >= 1/8 step from one.
    'SNAP': ({'Value': ('u', -3.0, 6.0)}, {'Value_001': 0.375}),
    'PINGPONG': ({'Value': ('u', -3.0, 6.0), 'Value_001': ('v', 0.3137, 1.2)}, {}),
    'SINE': ({'Value': ('u', -4.0, 8.0)}, {}),
    'COSINE': ({'Value': ('u', -4.0, 8.0)}, {}),
    # tan is steep near pi/2: a 1-ulp difference in the driven input is 1e-3 there.
    'TANGENT': ({'Value': ('u', -1.2, 2.4)}, {}),
    'ARCTANGENT': ({'Value': ('u', -4.0, 8.0)}, {}),
    'SINH': ({'Value': ('u', -2.5, 5.0)}, {}),
    'COSH': ({'Value': ('u', -2.5, 5.0)}, {}),
    'TANH': ({'Value': ('u', -3.0, 6.0)}, {}),
    'RADIANS': ({'Value': ('u', -360.0, 720.0)}, {}),
    # 180/pi times the drive scale times the bake's UV error must stay below 1e-3.
    'DEGREES': ({'Value': ('u', -0.25, 0.5)}, {}),
    'ARCTAN2': ({'Value': _A, 'Value_001': ('u', 1.0, -3.0)}, {}),
}


UNARY_MATH = ('SQRT', 'INVERSE_SQRT', 'ABSOLUTE', 'EXPONENT', 'SIGN', 'ROUND', 'FLOOR', 'CEIL',
              'TRUNC', 'FRACT', 'SINE', 'COSINE', 'TANGENT', 'ARCSINE', 'ARCCOSINE',
              'ARCTANGENT', 'SINH', 'COSH', 'TANH', 'RADIANS', 'DEGREES')


def _math_cases():
    out = []
    for op in MATH_OPS:
        default = {'Value': _A} if op in UNARY_MATH else {'Value': _A, 'Value_001': _B}
        drive, inputs = MATH_SETUP.get(op, (default, {}))
        for clamp in (False, True):
            out.append(Case(name='math_%s%s' % (op.lower(), '_clamp' if clamp else ''),
                            node='ShaderNodeMath',
                            props={'operation': op, 'use_clamp': clamp},
                            drive=dict(drive), inputs=dict(inputs), output='Value'))
    # The guards' own branches, with constant arguments.
    extra = [
        ('math_divide_by_zero', 'DIVIDE', {'Value': _A}, {'Value_001': 0.0}),
        ('math_inverse_sqrt_negative', 'INVERSE_SQRT', {'Value': ('u', -2.0, 1.9)}, {}),
        ('math_inverse_sqrt_zero', 'INVERSE_SQRT', {}, {'Value': 0.0}),
        ('math_divide_negative', 'DIVIDE', {'Value': _A, 'Value_001': ('v', -2.5, 2.0)}, {}),
        ('math_logarithm_base_below_one', 'LOGARITHM',
         {'Value': ('u', 0.4, 3.0), 'Value_001': ('v', 0.1, 0.5)}, {}),
        ('math_logarithm_negative_argument', 'LOGARITHM', {'Value_001': ('v', 1.5, 3.0)},
         {'Value': -0.5}),
        ('math_logarithm_negative_base', 'LOGARITHM', {'Value': ('u', 0.2, 4.0)},
         {'Value_001': -2.0}),
        ('math_modulo_negative', 'MODULO', {'Value': ('u', -3.0, 6.0)}, {'Value_001': -0.75}),
        ('math_wrap_reversed', 'WRAP', {'Value': ('u', -3.0, 6.0)},
         {'Value_001': -0.45, 'Value_002': 0.3}),
        ('math_snap_negative', 'SNAP', {'Value': ('u', -3.0, 6.0)}, {'Value_001': -0.75}),
        ('math_pingpong_negative', 'PINGPONG',
         {'Value': ('u', -3.0, 6.0), 'Value_001': ('v', -1.5137, 1.2)}, {}),
        ('math_arctan2_first_quadrant', 'ARCTAN2',
         {'Value': ('u', 0.2, 2.0), 'Value_001': ('v', 0.2, 2.0)}, {}),
        ('math_power_negative_base_odd', 'POWER', {'Value': ('u', -1.5, 3.0)},
         {'Value_001': 3.0}),
        ('math_power_negative_base_even', 'POWER', {'Value': ('u', -1.5, 3.0)},
         {'Value_001': 2.0}),
        ('math_power_negative_base_fraction', 'POWER',
         {'Value': ('u', -1.5, 3.0), 'Value_001': ('v', 0.1, 2.5)}, {}),
        ('math_power_negative_exponent', 'POWER', {'Value': ('u', 0.5, 2.0)},
         {'Value_001': -1.5}),
        ('math_power_zero_exponent', 'POWER', {'Value': _A}, {'Value_001': 0.0}),
        ('math_modulo_by_zero', 'MODULO', {'Value': _A}, {'Value_001': 0.0}),
        ('math_snap_by_zero', 'SNAP', {'Value': _A}, {'Value_001': 0.0}),
        ('math_snap_exact_multiple', 'SNAP', {}, {'Value': 0.9, 'Value_001': 0.1}),
        ('math_wrap_empty_range', 'WRAP', {'Value': _A}, {'Value_001': 0.7, 'Value_002': 0.7}),
        ('math_pingpong_zero_scale', 'PINGPONG', {'Value': _A}, {'Value_001': 0.0}),
        ('math_smooth_min_zero', 'SMOOTH_MIN', {'Value': _A, 'Value_001': _B},
         {'Value_002': 0.0}),
        ('math_logarithm_base_one', 'LOGARITHM', {'Value': ('u', 0.1, 3.0)},
         {'Value_001': 1.0}),
        ('math_compare_exact', 'COMPARE', {'Value': _A, 'Value_001': _A}, {'Value_002': 0.0}),
        ('math_arctan2_negative_x', 'ARCTAN2', {'Value': _A}, {'Value_001': -0.5}),
    ]
    for name, op, drive, inputs in extra:
        out.append(Case(name=name, node='ShaderNodeMath', props={'operation': op},
                        drive=drive, inputs=inputs, output='Value'))
    # Snap at exact multiples per texel (see vmath_snap_exact_multiples_driven).
    out.append(Case(name='math_snap_exact_multiples_driven', node='ShaderNodeMath',
                    props={'operation': 'SNAP'}, inputs={'Value_001': 0.1},
                    extra=snapped_input({'Value': 'x'}, step=0.1), output='Value',
                    note='snapped input: exact multiples of the increment'))
    return out


VECTOR_OPS = ['ADD', 'SUBTRACT', 'MULTIPLY', 'DIVIDE', 'MULTIPLY_ADD', 'CROSS_PRODUCT',
              'PROJECT', 'REFLECT', 'REFRACT', 'FACEFORWARD', 'DOT_PRODUCT', 'DISTANCE',
              'LENGTH', 'SCALE', 'NORMALIZE', 'ABSOLUTE', 'MINIMUM', 'MAXIMUM', 'FLOOR', 'CEIL',
              'FRACTION', 'MODULO', 'WRAP', 'SNAP', 'SINE', 'COSINE', 'TANGENT']
VALUE_OPS = ('DOT_PRODUCT', 'DISTANCE', 'LENGTH')

# (u, v, 0) * scale + offset: the three inputs span negative and > 1 values.
_VA = ('uv3', (4.0, 3.0, 0.0), (-2.0, -1.5, 0.7))
_VB = ('uv3', (-3.0, 2.0, 0.0), (1.5, -1.0, -0.6))
_VC = ('uv3', (2.0, -2.5, 0.0), (-1.0, 1.1, 0.4))

VECTOR_SETUP = {
    'SCALE': {'Vector': _VA, 'Scale': ('v', -1.5, 3.0)},
    # An IOR ratio below 1 keeps k = 1 - eta^2 (1 - (N.I)^2) away from 0, where sqrt(k) is
    # steep; total internal reflection has its own case.
    'REFRACT': {'Vector': _VA, 'Vector_001': _VB, 'Scale': ('v', 0.5, 0.3)},
    'WRAP': {'Vector': ('uv3', (6.0, 6.0, 0.0), (-3.0, -3.0, 2.3))},
    'SNAP': {'Vector': ('uv3', (6.0, 6.0, 0.0), (-3.0, -3.0, 2.3))},
    'MODULO': {'Vector': ('uv3', (6.0, 6.0, 0.0), (-3.0, -3.0, 2.3))},
    'FLOOR': {'Vector': ('uv3', (6.0, 6.0, 0.0), (-3.0, -3.0, 2.3))},
    'CEIL': {'Vector': ('uv3', (6.0, 6.0, 0.0), (-3.0, -3.0, 2.3))},
    'FRACTION': {'Vector': ('uv3', (6.0, 6.0, 0.0), (-3.0, -3.0, 2.3))},
    'SINE': {'Vector': ('uv3', (8.0, 8.0, 0.0), (-4.0, -4.0, 2.0))},
    'COSINE': {'Vector': ('uv3', (8.0, 8.0, 0.0), (-4.0, -4.0, 2.0))},
    'TANGENT': {'Vector': ('uv3', (2.4, 2.4, 0.0), (-1.2, -1.2, 0.3))},
}


# The inputs Blender enables per operation (beyond Vector).
_VECTOR_ARGS = {'MULTIPLY_ADD': ('Vector_001', 'Vector_002'),
                'FACEFORWARD': ('Vector_001', 'Vector_002'),
                'WRAP': ('Vector_001', 'Vector_002'), 'REFRACT': ('Vector_001', 'Scale'),
                'SCALE': ('Scale',), 'LENGTH': (), 'NORMALIZE': (), 'ABSOLUTE': (),
                'FLOOR': (), 'CEIL': (), 'FRACTION': (), 'SINE': (), 'COSINE': (),
                'TANGENT': ()}


def _vector_cases():
    # Constant divisors / ranges for the discontinuous operations (see MODULO in MATH_SETUP):
    # z: a reversed wrap range, a negative increment.
    constants = {'WRAP': {'Vector_001': (1.2, 0.7, -0.4), 'Vector_002': (0.3, -0.8, 0.5)},
                 'SNAP': {'Vector_001': (0.375, -0.75, -0.45)},
                 'MODULO': {'Vector_001': (0.375, -0.75, 0.45)}}
    out = []
    for op in VECTOR_OPS:
        args = _VECTOR_ARGS.get(op, ('Vector_001',))
        default = {'Vector': _VA}
        default.update({k: v for k, v in (('Vector_001', _VB), ('Vector_002', _VC))
                        if k in args})
        drive = VECTOR_SETUP.get(op, default)
        out.append(Case(name='vmath_%s' % op.lower(), node='ShaderNodeVectorMath',
                        props={'operation': op}, drive=dict(drive),
                        inputs=dict(constants.get(op, {})),
                        output='Value' if op in VALUE_OPS else 'Vector'))
    # Guards: a zero component in the divisor / increment / normal, the zero vector.
    for op in ('DIVIDE', 'MODULO', 'SNAP'):
        out.append(Case(name='vmath_%s_zero_component' % op.lower(),
                        node='ShaderNodeVectorMath', props={'operation': op},
                        drive={'Vector': ('uv3', (6.0, 6.0, 0.0), (-3.0, -3.0, 2.3))},
                        inputs={'Vector_001': (0.375, -0.75, 0.0)}, output='Vector'))
    # Snap at exact multiples: Cycles divides exactly (0.3 / 0.1 rounds to 3 in float32, so
    # 0.3 stays 0.3); a division through a reciprocal gives 2.9999998 and a whole step less.
    # The constant is the plain example; the driven one puts k * 0.1 (k over -32 .. 31,
    # identical bits in both bakes) on every texel, each an exact multiple of the increment.
    out.append(Case(name='vmath_snap_exact_multiples', node='ShaderNodeVectorMath',
                    props={'operation': 'SNAP'},
                    inputs={'Vector': (0.3, 0.6, 0.9), 'Vector_001': (0.1, 0.1, 0.1)},
                    output='Vector'))
    out.append(Case(name='vmath_snap_exact_multiples_driven', node='ShaderNodeVectorMath',
                    props={'operation': 'SNAP'}, inputs={'Vector_001': (0.1, 0.1, 0.1)},
                    extra=snapped_input({'Vector': 'vec'}, step=0.1,
                                        offset=(-32.0, -32.0, 3.0)),
                    output='Vector', note='snapped input: exact multiples of the increment'))
    # Wrap divides the same way before floor.
    out.append(Case(name='vmath_wrap_exact_multiples_driven', node='ShaderNodeVectorMath',
                    props={'operation': 'WRAP'},
                    inputs={'Vector_001': (0.1, 0.1, 0.1), 'Vector_002': (0.0, 0.0, 0.0)},
                    extra=snapped_input({'Vector': 'vec'}, step=0.1,
                                        offset=(-32.0, -32.0, 3.0)),
                    output='Vector', note='snapped input: exact multiples of the range'))
    out.append(Case(name='vmath_wrap_empty_range', node='ShaderNodeVectorMath',
                    props={'operation': 'WRAP'}, drive={'Vector': _VA},
                    inputs={'Vector_001': (0.5, 0.5, 0.5), 'Vector_002': (0.5, -1.0, 0.5)},
                    output='Vector'))
    # Faceforward's other branch: the reference (1, 0, 0) flips the sign at u = 0.5, a pixel
    # edge.
    out.append(Case(name='vmath_faceforward_flip', node='ShaderNodeVectorMath',
                    props={'operation': 'FACEFORWARD'}, drive={'Vector': _VA, 'Vector_001': _VB},
                    inputs={'Vector_002': (1.0, 0.0, 0.0)}, output='Vector'))
    out.append(Case(name='vmath_project_onto_zero', node='ShaderNodeVectorMath',
                    props={'operation': 'PROJECT'}, drive={'Vector': _VA},
                    inputs={'Vector_001': (0.0, 0.0, 0.0)}, output='Vector'))
    out.append(Case(name='vmath_normalize_zero', node='ShaderNodeVectorMath',
                    props={'operation': 'NORMALIZE'}, inputs={'Vector': (0.0, 0.0, 0.0)},
                    output='Vector'))
    out.append(Case(name='vmath_refract_total_internal', node='ShaderNodeVectorMath',
                    props={'operation': 'REFRACT'}, drive={'Vector': _VA},
                    inputs={'Vector_001': (0.0, 0.0, 1.0), 'Scale': 2.5}, output='Vector'))
    return out


INTERPOLATIONS = ['LINEAR', 'STEPPED', 'SMOOTHSTEP', 'SMOOTHERSTEP']


def _steps(inputs, interp, key, value):
    """Steps is only an (enabled) input of the stepped interpolation."""
    if interp == 'STEPPED':
        inputs = dict(inputs)
        inputs[key] = value
    return inputs


def _map_range_cases():
    out = []
    for interp in INTERPOLATIONS:
        for clamp in (True, False):
            tag = interp.lower() + ('_clamp' if clamp else '')
            out.append(Case(
                name='maprange_float_' + tag, node='ShaderNodeMapRange',
                props={'data_type': 'FLOAT', 'interpolation_type': interp, 'clamp': clamp},
                drive={'Value': ('u', -0.5, 2.0)},
                inputs=_steps({'From Min': 0.2, 'From Max': 0.8, 'To Min': -1.0,
                               'To Max': 2.0}, interp, 'Steps', 4.0),
                output='Result'))
            # Reversed source and target ranges.
            out.append(Case(
                name='maprange_float_reversed_' + tag, node='ShaderNodeMapRange',
                props={'data_type': 'FLOAT', 'interpolation_type': interp, 'clamp': clamp},
                drive={'Value': ('u', -0.5, 2.0)},
                inputs=_steps({'From Min': 0.9, 'From Max': 0.1, 'To Min': 1.5,
                               'To Max': -0.5}, interp, 'Steps', 3.0),
                output='Result'))
            out.append(Case(
                name='maprange_vector_' + tag, node='ShaderNodeMapRange',
                props={'data_type': 'FLOAT_VECTOR', 'interpolation_type': interp,
                       'clamp': clamp},
                drive={'Vector': ('uv3', (2.0, 2.0, 0.0), (-0.5, -0.5, 0.5))},
                # y: a reversed source range; z: an empty one (factor 0: To Min).
                inputs=_steps({'From_Min_FLOAT3': (0.2, 0.9, 0.5),
                               'From_Max_FLOAT3': (0.8, 0.1, 0.5),
                               'To_Min_FLOAT3': (-1.0, 2.0, 0.3),
                               'To_Max_FLOAT3': (2.0, -1.0, 0.7)},
                              interp, 'Steps_FLOAT3', (4.0, 2.5, 3.0)),
                output='Vector'))
    # Steps' guard (Steps <= 0 gives factor 0) and a fractional step count.
    for tag, steps in (('zero', 0.0), ('negative', -2.0), ('fractional', 2.5)):
        out.append(Case(
            name='maprange_float_stepped_steps_' + tag, node='ShaderNodeMapRange',
            props={'data_type': 'FLOAT', 'interpolation_type': 'STEPPED', 'clamp': False},
            drive={'Value': ('u', -0.5, 2.0)},
            inputs={'From Min': 0.2, 'From Max': 0.8, 'To Min': -1.0, 'To Max': 2.0,
                    'Steps': steps},
            output='Result'))
    for clamp in (True, False):
        out.append(Case(
            name='maprange_float_empty_source%s' % ('_clamp' if clamp else ''),
            node='ShaderNodeMapRange',
            props={'data_type': 'FLOAT', 'interpolation_type': 'LINEAR', 'clamp': clamp},
            drive={'Value': ('u', -0.5, 2.0)},
            inputs={'From Min': 0.5, 'From Max': 0.5, 'To Min': 0.25, 'To Max': 2.0},
            output='Result'))
    out.append(Case(
        name='maprange_vector_stepped_steps_guard', node='ShaderNodeMapRange',
        props={'data_type': 'FLOAT_VECTOR', 'interpolation_type': 'STEPPED', 'clamp': False},
        drive={'Vector': ('uv3', (2.0, 2.0, 0.0), (-0.5, -0.5, 0.5))},
        inputs={'From_Min_FLOAT3': (0.2, 0.9, 0.1), 'From_Max_FLOAT3': (0.8, 0.1, 0.9),
                'To_Min_FLOAT3': (-1.0, 2.0, 0.3), 'To_Max_FLOAT3': (2.0, -1.0, 0.7),
                'Steps_FLOAT3': (0.0, -2.0, 2.5)},
        output='Vector'))
    return out


def _clamp_cases():
    out = []
    for ctype in ('MINMAX', 'RANGE'):
        # Min over v crosses Max = 0.8, so half the plane has Min > Max.
        out.append(Case(name='clamp_' + ctype.lower(), node='ShaderNodeClamp',
                        props={'clamp_type': ctype},
                        drive={'Value': ('u', -1.0, 3.0), 'Min': ('v', -0.5, 2.5)},
                        inputs={'Max': 0.8}, output='Result'))
    return out


BLEND_TYPES = ['MIX', 'DARKEN', 'MULTIPLY', 'BURN', 'LIGHTEN', 'SCREEN', 'DODGE', 'ADD',
               'OVERLAY', 'SOFT_LIGHT', 'LINEAR_LIGHT', 'DIFFERENCE', 'SUBTRACT', 'DIVIDE',
               'HUE', 'SATURATION', 'COLOR', 'VALUE']

# Colors with negative, zero-crossing and > 1 channels; B's blue is constant and positive.
_CA = ('uv3', (1.6, 1.2, 0.0), (-0.2, -0.1, 0.45))
# B's blue stays above its red and green, so B is never grey (its hue is well conditioned).
_CB = ('uv3', (-1.2, 0.9, 0.0), (1.0, 0.1, 1.5))
# Divide: B's channels stay away from 0 (A / B is steep there), one of them negative.
_CB_DIVIDE = ('uv3', (0.8, 0.9, 0.0), (0.4, 0.3, -0.6))


def _mix_cases():
    out = []
    for clamp_factor in (True, False):
        tag = '' if clamp_factor else '_noclamp'
        out.append(Case(name='mix_float' + tag, node='ShaderNodeMix',
                        props={'data_type': 'FLOAT', 'clamp_factor': clamp_factor},
                        drive={'Factor_Float': ('u', -0.5, 2.0), 'A_Float': ('v', -1.0, 3.0)},
                        inputs={'B_Float': 0.75}, output='Result_Float'))
        out.append(Case(name='mix_vector' + tag, node='ShaderNodeMix',
                        props={'data_type': 'VECTOR', 'factor_mode': 'UNIFORM',
                               'clamp_factor': clamp_factor},
                        drive={'Factor_Float': ('u', -0.5, 2.0), 'A_Vector': _VA},
                        inputs={'B_Vector': (0.5, -1.0, 2.0)}, output='Result_Vector'))
        out.append(Case(name='mix_vector_non_uniform' + tag, node='ShaderNodeMix',
                        props={'data_type': 'VECTOR', 'factor_mode': 'NON_UNIFORM',
                               'clamp_factor': clamp_factor},
                        drive={'Factor_Vector': ('uv3', (2.0, -1.5, 0.0), (-0.5, 1.2, 0.3)),
                               'A_Vector': _VA},
                        inputs={'B_Vector': (0.5, -1.0, 2.0)}, output='Result_Vector'))
    # Float and vector mixes ignore the blend type and the result clamp in Cycles 3.4.
    out.append(Case(name='mix_float_blend_ignored', node='ShaderNodeMix',
                    props={'data_type': 'FLOAT', 'blend_type': 'MULTIPLY',
                           'clamp_result': True},
                    drive={'Factor_Float': ('u', -0.5, 2.0), 'A_Float': ('v', -1.0, 3.0)},
                    inputs={'B_Float': 1.75}, output='Result_Float'))
    for blend in BLEND_TYPES:
        name = blend.lower()
        cb = _CB_DIVIDE if blend == 'DIVIDE' else _CB
        out.append(Case(name='mix_color_' + name, node='ShaderNodeMix',
                        props={'data_type': 'RGBA', 'blend_type': blend},
                        drive={'Factor_Float': ('u', -0.25, 1.5), 'A_Color': _CA,
                               'B_Color': cb},
                        output='Result_Color'))
        out.append(Case(name='mix_color_%s_unclamped_factor_clamped_result' % name,
                        node='ShaderNodeMix',
                        props={'data_type': 'RGBA', 'blend_type': blend,
                               'clamp_factor': False, 'clamp_result': True},
                        # Offset chosen so burn's and dodge's 0/1 jumps (at 1 - t + t B = 0
                        # and 1 - t B = 0) stay >= 1.9e-3 from every pixel centre.
                        drive={'Factor_Float': ('v', -0.2175, 1.3), 'A_Color': _CA,
                               'B_Color': cb},
                        output='Result_Color'))
        out.append(Case(name='mixrgb_' + name, node='ShaderNodeMixRGB',
                        props={'blend_type': blend, 'use_clamp': False},
                        drive={'Fac': ('u', -0.25, 1.5), 'Color1': _CA, 'Color2': cb},
                        output='Color'))
    # Divide's guard: a B channel of exactly 0 keeps A's channel.
    out.append(Case(name='mix_color_divide_by_zero_channel', node='ShaderNodeMix',
                    props={'data_type': 'RGBA', 'blend_type': 'DIVIDE'},
                    drive={'Factor_Float': ('u', -0.25, 1.5), 'A_Color': _CA,
                           'B_Color': ('uv3', (0.8, 0.9, 0.0), (0.4, 0.3, 0.0))},
                    output='Result_Color'))
    for blend in ('ADD', 'DODGE', 'LINEAR_LIGHT'):
        out.append(Case(name='mixrgb_%s_clamp' % blend.lower(), node='ShaderNodeMixRGB',
                        props={'blend_type': blend, 'use_clamp': True},
                        drive={'Fac': ('u', -0.25, 1.5), 'Color1': _CA, 'Color2': _CB},
                        output='Color'))
    return out


CASES = _math_cases() + _vector_cases() + _map_range_cases() + _clamp_cases() + _mix_cases()

"""Color and converter nodes against Cycles 3.4: Hue/Saturation/Value, Bright/Contrast,
Gamma, Invert, RGB to BW, Separate/Combine Color (RGB, HSV, HSL) and their legacy RGB/HSV
forms, Separate/Combine XYZ, Blackbody, Wavelength, ColorRamp (every interpolation, RGB and
HSV/HSL colour modes), RGB Curves, Vector Curves and Float Curve (horizontal and extrapolated
ends). Inputs are driven over ranges that reach the nodes' edge cases: negative and >1
colours, hues outside [0, 1], temperatures and wavelengths beyond the tables, curve inputs
outside the curve's x range.
"""
from .case import Case

# A colour over the plane: (1.2u - 0.1, 1.2v - 0.1, 0.5): every hue sector, slightly negative
# and >1 components at the edges. Its grey point (u = v = 0.5) lies on a pixel corner, as far
# from the pixel centres as it can: hue is ill-conditioned next to grey, and Cycles' baked UV
# differs from the exact pixel centre by ~1e-5.
COLOR_DRIVE = ('uv3', (1.2, 1.2, 0.0), (-0.1, -0.1, 0.5))
# A wider one, mostly outside [0, 1].
WIDE_DRIVE = ('uv3', (3.0, 2.0, 0.0), (-1.0, -0.5, 0.3))


def _ramp(interpolation, color_mode='RGB', hue='NEAR'):
    """A 4-stop ramp (the default two stops moved and recoloured, plus two new ones)."""
    def setup(node):
        ramp = node.color_ramp
        ramp.color_mode = color_mode
        if color_mode == 'RGB':
            ramp.interpolation = interpolation
        else:
            ramp.hue_interpolation = hue
        els = ramp.elements
        els[0].position = 0.1
        els[0].color = (0.9, 0.1, 0.05, 1.0)
        els[1].position = 0.85
        els[1].color = (0.05, 0.2, 0.9, 0.3)
        e = els.new(0.4)
        e.color = (0.2, 0.8, 0.1, 0.6)
        e = els.new(0.55)
        e.color = (1.0, 0.9, 0.7, 0.9)
    return setup


def _curve_points(curve, points, handle='AUTO'):
    """Puts curve's points at `points` (x, y pairs, ascending x); a new curve has two."""
    pts = curve.points
    while len(pts) > len(points):
        pts.remove(pts[len(pts) - 1])
    while len(pts) < len(points):
        pts.new(0.5, 0.5)
    for p, (x, y) in zip(pts, points):
        p.location = (x, y)
        p.handle_type = handle


def _rgb_curves(extend):
    def setup(node):
        m = node.mapping
        m.extend = extend
        _curve_points(m.curves[3], [(0.0, 0.05), (0.3, 0.45), (0.7, 0.6), (1.0, 0.95)])  # C
        _curve_points(m.curves[0], [(0.0, 0.1), (0.5, 0.7), (1.0, 0.9)])                  # R
        _curve_points(m.curves[1], [(0.0, 0.0), (0.4, 0.2), (1.0, 1.0)], 'VECTOR')        # G
        _curve_points(m.curves[2], [(0.1, 0.2), (0.9, 0.8)])                              # B
        m.update()
    return setup


def _vector_curves(extend):
    def setup(node):
        m = node.mapping
        m.extend = extend
        _curve_points(m.curves[0], [(-1.0, -0.5), (0.0, 0.4), (1.0, 0.8)])
        _curve_points(m.curves[1], [(-1.0, 1.0), (-0.2, 0.1), (0.5, -0.3), (1.0, 0.0)])
        _curve_points(m.curves[2], [(-0.8, -1.0), (0.8, 1.0)], 'VECTOR')
        m.update()
    return setup


def _float_curve(extend, handle='AUTO'):
    def setup(node):
        m = node.mapping
        m.extend = extend
        _curve_points(m.curves[0], [(0.0, 0.2), (0.25, 0.8), (0.6, 0.3), (1.0, 0.6)], handle)
        m.update()
    return setup


def _sep_cases(node, mode_prop, modes, color_input, outputs, prefix):
    out = []
    for mode in modes:
        for o in outputs:
            props = {mode_prop: mode} if mode_prop else {}
            out.append(Case(name='%s_%s_%s' % (prefix, mode.lower(), o.lower()), node=node,
                            props=props, drive={color_input: COLOR_DRIVE}, output=o))
    return out


CASES = [
    # Hue/Saturation/Value
    Case(name='color_hsv_default', node='ShaderNodeHueSaturation', drive={'Color': COLOR_DRIVE}),
    Case(name='color_hsv_adjust', node='ShaderNodeHueSaturation',
         inputs={'Hue': 0.3, 'Saturation': 1.6, 'Value': 0.8, 'Fac': 0.7},
         drive={'Color': COLOR_DRIVE}),
    Case(name='color_hsv_driven', node='ShaderNodeHueSaturation',
         inputs={'Color': (0.8, 0.3, 0.1), 'Value': 1.3},
         drive={'Hue': ('u', -0.3, 1.6), 'Saturation': ('v', 0.0, 2.5)}),
    Case(name='color_hsv_wide', node='ShaderNodeHueSaturation',
         inputs={'Hue': 0.62, 'Saturation': 0.5, 'Fac': 1.2}, drive={'Color': WIDE_DRIVE}),
    # Bright/Contrast
    Case(name='color_bright_contrast', node='ShaderNodeBrightContrast',
         inputs={'Bright': 0.1, 'Contrast': 0.5}, drive={'Color': COLOR_DRIVE}),
    Case(name='color_bright_contrast_driven', node='ShaderNodeBrightContrast',
         inputs={'Color': (0.2, 0.5, 0.9)},
         drive={'Bright': ('u', -0.5, 1.0), 'Contrast': ('v', -1.5, 3.0)}),
    # Gamma
    Case(name='color_gamma', node='ShaderNodeGamma', inputs={'Gamma': 2.2},
         drive={'Color': WIDE_DRIVE}, note='negative components pass through'),
    Case(name='color_gamma_driven', node='ShaderNodeGamma', inputs={'Color': (0.2, 0.5, 1.7)},
         drive={'Gamma': ('u', -1.0, 4.0)}),
    Case(name='color_gamma_zero', node='ShaderNodeGamma', inputs={'Gamma': 0.0},
         drive={'Color': WIDE_DRIVE}),
    # Invert
    Case(name='color_invert', node='ShaderNodeInvert', drive={'Color': COLOR_DRIVE}),
    Case(name='color_invert_fac', node='ShaderNodeInvert',
         drive={'Color': WIDE_DRIVE, 'Fac': ('v', -0.5, 2.0)}),
    # RGB to BW
    Case(name='color_rgb_to_bw', node='ShaderNodeRGBToBW', drive={'Color': WIDE_DRIVE}),
    # Combine Color (every mode) and its legacy forms
    Case(name='color_combine_rgb', node='ShaderNodeCombineColor', props={'mode': 'RGB'},
         inputs={'Blue': 0.7}, drive={'Red': 'u', 'Green': ('v', -0.2, 1.4)}),
    Case(name='color_combine_hsv', node='ShaderNodeCombineColor', props={'mode': 'HSV'},
         inputs={'Blue': 0.8}, drive={'Red': ('u', -0.2, 1.4), 'Green': ('v', -0.1, 1.3)},
         note='hue and saturation outside [0, 1]'),
    Case(name='color_combine_hsl', node='ShaderNodeCombineColor', props={'mode': 'HSL'},
         inputs={'Green': 0.7}, drive={'Red': ('u', -0.2, 1.4), 'Blue': ('v', -0.1, 1.2)}),
    Case(name='color_combine_rgb_legacy', node='ShaderNodeCombineRGB',
         inputs={'B': 0.3}, drive={'R': 'u', 'G': 'v'}),
    Case(name='color_combine_hsv_legacy', node='ShaderNodeCombineHSV',
         inputs={'V': 0.9}, drive={'H': 'u', 'S': 'v'}),
    # Separate/Combine XYZ
    Case(name='color_separate_xyz_z', node='ShaderNodeSeparateXYZ',
         drive={'Vector': ('uv3', (1.0, 1.0, 0.0), (0.0, 0.0, -0.75))}, output='Z'),
    Case(name='color_combine_xyz', node='ShaderNodeCombineXYZ',
         inputs={'X': -0.25}, drive={'Y': 'u', 'Z': ('v', 0.5, 2.0)}),
    # Blackbody: below the fit (800 K), every fitted segment, above 12000 K (two ranges, so
    # that the steep low end is not stretched over the whole plane).
    Case(name='color_blackbody_low', node='ShaderNodeBlackbody',
         drive={'Temperature': ('u', 600.0, 1800.0)}),
    Case(name='color_blackbody_high', node='ShaderNodeBlackbody',
         drive={'Temperature': ('v', 2000.0, 11000.0)}),
    # Wavelength: below, inside and above the 380..780 nm table.
    Case(name='color_wavelength', node='ShaderNodeWavelength',
         drive={'Wavelength': ('u', 360.0, 440.0)}),
    # ColorRamp: every interpolation (RGB colour mode), HSV/HSL colour modes, both outputs.
    Case(name='color_ramp_linear', node='ShaderNodeValToRGB', extra=_ramp('LINEAR'),
         drive={'Fac': ('u', -0.2, 1.4)}, output='Color'),
    Case(name='color_ramp_linear_alpha', node='ShaderNodeValToRGB', extra=_ramp('LINEAR'),
         drive={'Fac': ('u', -0.2, 1.4)}, output='Alpha'),
    Case(name='color_ramp_ease', node='ShaderNodeValToRGB', extra=_ramp('EASE'),
         drive={'Fac': ('u', -0.2, 1.4)}, output='Color'),
    Case(name='color_ramp_cardinal', node='ShaderNodeValToRGB', extra=_ramp('CARDINAL'),
         drive={'Fac': ('u', -0.2, 1.4)}, output='Color'),
    Case(name='color_ramp_b_spline', node='ShaderNodeValToRGB', extra=_ramp('B_SPLINE'),
         drive={'Fac': ('u', -0.2, 1.4)}, output='Color'),
    Case(name='color_ramp_constant', node='ShaderNodeValToRGB', extra=_ramp('CONSTANT'),
         drive={'Fac': ('u', -0.2, 1.4)}, output='Color',
         note='steps sit between table entries: a pixel on a step may differ'),
    Case(name='color_ramp_constant_alpha', node='ShaderNodeValToRGB', extra=_ramp('CONSTANT'),
         drive={'Fac': ('u', -0.2, 1.4)}, output='Alpha'),
    Case(name='color_ramp_hsv', node='ShaderNodeValToRGB', extra=_ramp('LINEAR', 'HSV', 'FAR'),
         drive={'Fac': 'u'}, output='Color'),
    Case(name='color_ramp_hsl', node='ShaderNodeValToRGB', extra=_ramp('LINEAR', 'HSL', 'CW'),
         drive={'Fac': 'u'}, output='Color'),
    # Curves: a non-trivial curve set, horizontal and extrapolated ends, inputs beyond x range.
    Case(name='color_rgb_curves', node='ShaderNodeRGBCurve', extra=_rgb_curves('HORIZONTAL'),
         inputs={'Fac': 0.8}, drive={'Color': WIDE_DRIVE}),
    Case(name='color_rgb_curves_extrapolated', node='ShaderNodeRGBCurve',
         extra=_rgb_curves('EXTRAPOLATED'), drive={'Color': WIDE_DRIVE}),
    Case(name='color_rgb_curves_fac', node='ShaderNodeRGBCurve', extra=_rgb_curves('HORIZONTAL'),
         drive={'Color': COLOR_DRIVE, 'Fac': ('v', -0.5, 2.0)}),
    Case(name='color_vector_curves', node='ShaderNodeVectorCurve',
         extra=_vector_curves('HORIZONTAL'),
         drive={'Vector': ('uv3', (3.0, 3.0, 0.0), (-1.5, -1.5, 0.3))}),
    Case(name='color_vector_curves_extrapolated', node='ShaderNodeVectorCurve',
         extra=_vector_curves('EXTRAPOLATED'), inputs={'Fac': 0.9},
         drive={'Vector': ('uv3', (3.0, 3.0, 0.0), (-1.5, -1.5, 0.9))}),
    Case(name='color_float_curve', node='ShaderNodeFloatCurve', extra=_float_curve('HORIZONTAL'),
         drive={'Value': ('u', -0.3, 1.6)}),
    # AUTO handles make the first table step steep (slope ~50), which magnifies the bake's
    # UV rounding past 1e-3 when extrapolated: the extrapolated case uses VECTOR handles.
    Case(name='color_float_curve_extrapolated', node='ShaderNodeFloatCurve',
         extra=_float_curve('EXTRAPOLATED', 'VECTOR'), drive={'Value': ('u', -0.3, 1.6),
                                                     'Factor': ('v', 0.0, 1.0)}),
]

# Separate Color in every mode, every output; legacy Separate RGB / HSV.
CASES += _sep_cases('ShaderNodeSeparateColor', 'mode', ('RGB', 'HSV', 'HSL'), 'Color',
                    ('Red', 'Green', 'Blue'), 'color_separate')
CASES += _sep_cases('ShaderNodeSeparateRGB', None, ('legacy',), 'Image', ('R', 'G', 'B'),
                    'color_separate_rgb')
CASES += _sep_cases('ShaderNodeSeparateHSV', None, ('legacy',), 'Color', ('H', 'S', 'V'),
                    'color_separate_hsv')

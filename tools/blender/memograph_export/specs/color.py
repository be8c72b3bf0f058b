"""Color and converter nodes (nodes/color.inc, nodes/converter.inc), Cycles 3.4-exact.

ColorRamp (ShaderNodeValToRGB) and the curve nodes (ShaderNodeRGBCurve, ShaderNodeVectorCurve,
ShaderNodeFloatCurve) need their tables and are custom writers in the exporter; the table
layouts they must write are at the top of those nodes' descriptions in nodes/converter.inc.

Legacy nodes map to the current ones: Separate/Combine RGB to Separate/Combine Color with
Mode 0 (the socket's default), Separate/Combine HSV to the same nodes with Mode 1 (written
through a computed prop, since those nodes have no `mode` property).
"""
from ..spec import NodeSpec

# Separate/Combine Color Mode: the index in Blender 3.4's enum_items (RGB, HSV, HSL).
_HSV_MODE = ('Mode', lambda node: 1)

NODES = {
    'ShaderNodeHueSaturation': NodeSpec(
        mgraph='HueSaturationValue',
        inputs={'Hue': 'Hue', 'Saturation': 'Saturation', 'Value': 'Value', 'Fac': 'Fac',
                'Color': 'Color'},
        outputs={'Color': 'Out'}),
    'ShaderNodeBrightContrast': NodeSpec(
        mgraph='BrightnessContrast',
        inputs={'Color': 'Color', 'Bright': 'Bright', 'Contrast': 'Contrast'},
        outputs={'Color': 'Out'}),
    'ShaderNodeGamma': NodeSpec(
        mgraph='Gamma',
        inputs={'Color': 'Color', 'Gamma': 'Gamma'},
        outputs={'Color': 'Out'}),
    'ShaderNodeInvert': NodeSpec(
        mgraph='Invert',
        inputs={'Fac': 'Fac', 'Color': 'Color'},
        outputs={'Color': 'Out'}),
    'ShaderNodeRGBToBW': NodeSpec(
        mgraph='RGBToBW',
        inputs={'Color': 'Color'},
        outputs={'Val': 'Val'}),
    'ShaderNodeSeparateColor': NodeSpec(
        mgraph='SeparateColor',
        inputs={'Color': 'Color'},
        outputs={'Red': 'Red', 'Green': 'Green', 'Blue': 'Blue'},
        props={'mode': 'Mode'}),
    'ShaderNodeCombineColor': NodeSpec(
        mgraph='CombineColor',
        inputs={'Red': 'Red', 'Green': 'Green', 'Blue': 'Blue'},
        outputs={'Color': 'Color'},
        props={'mode': 'Mode'}),
    'ShaderNodeSeparateRGB': NodeSpec(
        mgraph='SeparateColor',
        inputs={'Image': 'Color'},
        outputs={'R': 'Red', 'G': 'Green', 'B': 'Blue'}),
    'ShaderNodeCombineRGB': NodeSpec(
        mgraph='CombineColor',
        inputs={'R': 'Red', 'G': 'Green', 'B': 'Blue'},
        outputs={'Image': 'Color'}),
    'ShaderNodeSeparateHSV': NodeSpec(
        mgraph='SeparateColor',
        inputs={'Color': 'Color'},
        outputs={'H': 'Red', 'S': 'Green', 'V': 'Blue'},
        props={'mode': _HSV_MODE}),
    'ShaderNodeCombineHSV': NodeSpec(
        mgraph='CombineColor',
        inputs={'H': 'Red', 'S': 'Green', 'V': 'Blue'},
        outputs={'Color': 'Color'},
        props={'mode': _HSV_MODE}),
    'ShaderNodeSeparateXYZ': NodeSpec(
        mgraph='SeparateXYZ',
        inputs={'Vector': 'Vector'},
        outputs={'X': 'X', 'Y': 'Y', 'Z': 'Z'}),
    'ShaderNodeCombineXYZ': NodeSpec(
        mgraph='CombineXYZ',
        inputs={'X': 'X', 'Y': 'Y', 'Z': 'Z'},
        outputs={'Vector': 'Vector'}),
    'ShaderNodeBlackbody': NodeSpec(
        mgraph='Blackbody',
        inputs={'Temperature': 'Temperature'},
        outputs={'Color': 'Color'}),
    'ShaderNodeWavelength': NodeSpec(
        mgraph='Wavelength',
        inputs={'Wavelength': 'Wavelength'},
        outputs={'Color': 'Color'}),
}

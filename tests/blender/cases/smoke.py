"""Harness smoke cases: the simplest nodes, to check orientation and the pipeline itself.
Separate XYZ of UV must match exactly (it checks that both bakes put UV (u, v) at the same
pixel)."""
from .case import Case

CASES = [
    Case(name='smoke_separate_xyz_uv_x', node='ShaderNodeSeparateXYZ',
         drive={'Vector': 'uv3'}, output='X'),
    Case(name='smoke_separate_xyz_uv_y', node='ShaderNodeSeparateXYZ',
         drive={'Vector': 'uv3'}, output='Y'),
    Case(name='smoke_combine_xyz_uv', node='ShaderNodeCombineXYZ',
         drive={'X': 'u', 'Y': ('v', -1.0, 3.0)}, inputs={'Z': 0.25}, output='Vector'),
    Case(name='smoke_rgb', node='ShaderNodeRGB', output='Color',
         extra=lambda node: setattr(node.outputs['Color'], 'default_value', (0.2, 0.5, 0.9, 1.0))),
    Case(name='smoke_value', node='ShaderNodeValue', output='Value',
         extra=lambda node: setattr(node.outputs['Value'], 'default_value', 0.375)),
    Case(name='smoke_negative', node='ShaderNodeCombineXYZ',
         drive={'X': ('u', -2.0, 1.0)}, inputs={'Y': -0.5, 'Z': 3.0}, output='Vector',
         note='negative and >1 values survive both bakes'),
    Case(name='smoke_uv_scaled', node='ShaderNodeVectorMath', props={'operation': 'ADD'},
         drive={'Vector': ('uv3', (2.0, 3.0, 1.0), (0.5, -1.0, 0.25))}, inputs={'Vector_001': 0.0},
         output='Vector', note='the Vector Math Multiply Add driver'),
    Case(name='smoke_object_coords', node='ShaderNodeVectorMath', props={'operation': 'ADD'},
         drive={'Vector': 'object'}, inputs={'Vector_001': (0.0, 0.0, 0.5)}, output='Vector',
         note='object = (2u-1, 2v-1, 0) on the default plane'),
    Case(name='smoke_tilted_normal', node='ShaderNodeVectorMath', props={'operation': 'ADD'},
         drive={'Vector': 'normal'}, inputs={'Vector_001': 0.0}, output='Vector',
         normal=(1.0, -2.0, 2.0), note='the plane tilted to normal (1, -2, 2) / 3'),
    Case(name='smoke_generated_coords', node='ShaderNodeVectorMath', props={'operation': 'ADD'},
         drive={'Vector': 'generated'}, inputs={'Vector_001': 0.0}, output='Vector'),
]

"""Voronoi Texture -> nodes/voronoi.inc VoronoiTexture (Cycles 3.4 semantics).

Blender has an input and an output both named W; an mgraph node cannot have two sockets of
one name, so Blender's W output is VoronoiTexture's `WOut`. The enums are written as their
Blender 3.4 enum_items indices: voronoi_dimensions 1D..4D -> Dimensions 0..3, feature
F1, F2, SMOOTH_F1, DISTANCE_TO_EDGE, N_SPHERE_RADIUS -> Feature 0..4, distance EUCLIDEAN,
MANHATTAN, CHEBYCHEV, MINKOWSKI -> Metric 0..3. Blender 4.0's fractal inputs (Detail,
Roughness, Lacunarity, Normalize) do not exist in 3.4 and are not mapped: the exporter warns
when a linked or unknown socket is not listed here.
"""
from ..spec import NodeSpec

NODES = {
    'ShaderNodeTexVoronoi': NodeSpec(
        mgraph='VoronoiTexture',
        inputs={'Vector': 'Vector', 'W': 'W', 'Scale': 'Scale', 'Smoothness': 'Smoothness',
                'Exponent': 'Exponent', 'Randomness': 'Randomness'},
        outputs={'Distance': 'Distance', 'Color': 'Color', 'Position': 'Position',
                 'W': 'WOut', 'Radius': 'Radius'},
        props={'voronoi_dimensions': 'Dimensions', 'feature': 'Feature',
               'distance': 'Metric'},
        implicit_vector='generated'),
}

"""Image Texture by interpolation, on images the case builds inside Blender (packed, so the
export unpacks them next to the graph). Linear on a smooth periodic image (Cycles filters
without mip-maps; on a smooth image the two agree); Closest on pixel art of unrelated colours,
the UV doubled and shifted by whole texels (negative u and v: the floor and the repeat wrap),
so every bake pixel centre is an eighth of a texel or more from a texel edge and the texels
must match exactly (linear filtering blends neighbours and misses by up to 0.87). Extend and
Clip, with Closest and with Linear (ImageTextureBilinear: the four texels, no mip-maps), on
the same UV, which runs half an image beyond every edge; Cubic and Smart likewise. sRGB pixel
art filtered (where Cycles linearises). Alpha below 1: Cycles' association of an 8-bit
image's colour with its alpha, with Alpha unlinked and linked. Box projection on a tilted
plane (Case.normal), in every zone of its blend. Colour cases on images with alpha say so;
the others use opaque images.
"""
from math import cos, pi, sin

from .case import Case


def _pixel_art(width, height):
    px = []
    for j in range(height):
        for i in range(width):
            k = i + width * j
            px += [((k * 37) % 11) / 10.0, ((k * 53) % 7) / 6.0, ((k * 29) % 5) / 4.0, 1.0]
    return px


def _pixel_art_alpha(width, height):
    px = _pixel_art(width, height)
    for k in range(width * height):
        px[4 * k + 3] = ((k * 13) % 9) / 8.0
    return px


def _smooth(width, height):
    px = []
    for j in range(height):
        for i in range(width):
            px += [0.5 + 0.45 * sin(2.0 * pi * i / width), 0.5 + 0.45 * cos(2.0 * pi * j / height),
                   0.5 + 0.45 * sin(2.0 * pi * (i / width + j / height)), 1.0]
    return px


def _smooth_alpha(width, height):
    px = _smooth(width, height)
    for j in range(height):
        for i in range(width):
            px[4 * (i + width * j) + 3] = 0.5 + 0.45 * cos(2.0 * pi * (i / width - j / height))
    return px


def _image(name, width, height, pixels, colorspace, interpolation, extension='REPEAT'):
    def extra(node):
        import bpy  # only inside Blender
        img = bpy.data.images.get(name)
        if img is None:
            img = bpy.data.images.new(name, width, height, alpha=True)
            img.pixels = pixels(width, height)
            img.pack()
            img.colorspace_settings.name = colorspace
        node.image = img
        node.interpolation = interpolation
        node.extension = extension
    return extra


_SHIFTED = {'Vector': ('uv3', 2.0, (-0.5, -0.5, 0.0))}


def _box(name, width, height, pixels, colorspace, interpolation, extension, blend):
    """Case arguments for Box projection: props (projection, projection_blend, and, for the
    table, interpolation and extension) and extra(node, tree): the image, and a Vector that
    varies on all three axes, so that every plane's lookup moves over the image: UV through a
    Mapping (rotated, doubled, shifted: about -0.9 to 1.9 on each axis, beyond every edge)."""
    set_image = _image(name, width, height, pixels, colorspace, interpolation, extension)

    def extra(node, nt):
        set_image(node)
        coord = nt.nodes.new('ShaderNodeTexCoord')
        mapping = nt.nodes.new('ShaderNodeMapping')
        mapping.inputs['Location'].default_value = (-0.4, -0.3, 0.2)
        mapping.inputs['Rotation'].default_value = (0.5, -0.4, 0.3)
        mapping.inputs['Scale'].default_value = (2.0, 2.0, 2.0)
        nt.links.new(coord.outputs['UV'], mapping.inputs['Vector'])
        nt.links.new(mapping.outputs['Vector'], node.inputs['Vector'])
    return {'props': {'projection': 'BOX', 'projection_blend': blend,
                      'interpolation': interpolation, 'extension': extension},
            'extra': extra}


def _mapped(name, width, height, pixels, colorspace, interpolation, extension, projection):
    """Case arguments for Sphere and Tube projection: props and extra(node, tree) with the
    same rotated, doubled, shifted Vector as the Box cases (about -0.9 to 1.9 on each axis, so
    around the centre 0.5 where the projections' angles turn)."""
    args = _box(name, width, height, pixels, colorspace, interpolation, extension, 0.0)
    args['props'] = {'projection': projection, 'interpolation': interpolation,
                     'extension': extension}
    set_vector = args['extra']

    def extra(node, nt):
        set_vector(node, nt)
        node.projection = projection
    args['extra'] = extra
    return args


def _color_plus_alpha(name, interpolation, extension):
    """extra(node, tree) for a Vector Math ADD of an Image Texture's Color and Alpha: with
    Alpha linked, Cycles divides the filtered, associated colour by the filtered alpha."""
    set_image = _image(name, 8, 4, _pixel_art_alpha, 'sRGB', interpolation, extension)

    def extra(node, nt):
        tex = nt.nodes.new('ShaderNodeTexImage')
        set_image(tex)
        nt.links.new(tex.outputs['Color'], node.inputs[0])
        nt.links.new(tex.outputs['Alpha'], node.inputs[1])
    return extra


# Box projection: the plane tilted (Case.normal) into each zone of Cycles' weight triangle:
# a corner (one plane), the three edges (two planes) and the middle (three planes), both
# signs of each axis (the sides whose u Cycles turns), Blend 0, 0.2 and 1, every
# interpolation and extension. Colour on opaque images.
_XY = (1.0, 0.9, 0.05)      # Blend 0: x alone; 0.2: x and y
_YZ = (0.05, -0.9, 1.0)     # Blend 0.2: y and z
_XZ = (-1.0, 0.05, -0.9)    # Blend 0.2: x and z
_XYZ = (-0.8, 0.9, -1.0)    # Blend 0.2: all three
_TILT = (1.0, -0.7, 0.5)    # Blend 1: all three, weights |n| / sum |n|

CASES = [
    Case(name='image_linear_smooth', node='ShaderNodeTexImage', drive={'Vector': 'uv3'},
         output='Color', extra=_image('mg_case_smooth', 32, 32, _smooth, 'sRGB', 'Linear'),
         note='smooth periodic image'),
    Case(name='image_closest_pixel_art', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color', extra=_image('mg_case_art', 8, 4, _pixel_art, 'sRGB', 'Closest'),
         note='8x4 pixel art, sRGB'),
    Case(name='image_closest_pixel_art_noncolor', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Closest'),
         note='8x4 pixel art, Non-Color'),
    Case(name='image_closest_alpha', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Alpha',
         extra=_image('mg_case_art_alpha', 8, 4, _pixel_art_alpha, 'sRGB', 'Closest'),
         note='8x4 pixel art, alpha 0 to 1'),
    # Extend and Clip: the UV runs from -0.5 to 1.5, half an image beyond every edge.
    Case(name='image_closest_extend', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art', 8, 4, _pixel_art, 'sRGB', 'Closest', 'EXTEND'),
         note='8x4 pixel art, sRGB'),
    Case(name='image_closest_clip', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art', 8, 4, _pixel_art, 'sRGB', 'Closest', 'CLIP'),
         note='8x4 pixel art, sRGB'),
    Case(name='image_closest_clip_alpha', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Alpha',
         extra=_image('mg_case_art', 8, 4, _pixel_art, 'sRGB', 'Closest', 'CLIP'),
         note='8x4 pixel art, sRGB'),
    Case(name='image_linear_extend', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Linear', 'EXTEND'),
         note='8x4 pixel art, Non-Color'),
    Case(name='image_linear_clip', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Linear', 'CLIP'),
         note='8x4 pixel art, Non-Color'),
    Case(name='image_linear_clip_alpha', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Alpha',
         extra=_image('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Linear', 'CLIP'),
         note='8x4 pixel art, Non-Color'),
    # Cubic (a B-spline: it blurs) and Smart (Cubic on the CPU), Non-Color, every extension.
    Case(name='image_cubic_repeat', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Cubic', 'REPEAT'),
         note='8x4 pixel art, Non-Color'),
    Case(name='image_cubic_extend', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Cubic', 'EXTEND'),
         note='8x4 pixel art, Non-Color'),
    Case(name='image_cubic_clip', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Cubic', 'CLIP'),
         note='8x4 pixel art, Non-Color'),
    Case(name='image_smart_repeat', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Smart', 'REPEAT'),
         note='8x4 pixel art, Non-Color'),
    # 8-bit sRGB images with filtering, on pixel art whose neighbours differ by up to 1: where
    # Cycles linearises shows between texels. It filters the stored bytes and linearises each
    # lookup (NODE_IMAGE_COMPRESS_AS_SRGB in svm_image_texture), as memograph's SRGBToLinear
    # after the filter; linearising each texel before filtering would miss by about 0.29.
    Case(name='image_linear_extend_srgb', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art', 8, 4, _pixel_art, 'sRGB', 'Linear', 'EXTEND'),
         note='8x4 pixel art, sRGB: linearised after filtering'),
    Case(name='image_cubic_repeat_srgb', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art', 8, 4, _pixel_art, 'sRGB', 'Cubic', 'REPEAT'),
         note='8x4 pixel art, sRGB: linearised after filtering'),
    # Straight alpha on an 8-bit image: Cycles associates each texel (C * A / 255, rounded
    # down) before filtering; with Alpha unlinked its Color stays associated, with Alpha
    # linked it is divided by the filtered alpha (memograph: Premultiply 1 and 2).
    Case(name='image_closest_premultiplied', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art_alpha', 8, 4, _pixel_art_alpha, 'sRGB', 'Closest'),
         note='8x4 pixel art, alpha 0 to 1, Alpha unlinked: associated'),
    Case(name='image_linear_premultiplied_clip', node='ShaderNodeTexImage', drive=_SHIFTED,
         output='Color',
         extra=_image('mg_case_art_alpha', 8, 4, _pixel_art_alpha, 'sRGB', 'Linear', 'CLIP'),
         note='8x4 pixel art, alpha 0 to 1, Alpha unlinked: associated'),
    Case(name='image_linear_repeat_premultiplied', node='ShaderNodeTexImage',
         drive={'Vector': 'uv3'}, output='Color', tolerance=1e-2,
         extra=_image('mg_case_smooth_alpha', 32, 32, _smooth_alpha, 'sRGB', 'Linear'),
         note='smooth image, alpha 0.05 to 0.95, mip-mapped: associated after filtering, so '
              'Cycles\' 8-bit rounding down (up to 1/255 before linearising) and the blend '
              'between texels differ'),
    Case(name='image_cubic_unassociated', node='ShaderNodeVectorMath', props={'operation': 'ADD'},
         output='Vector',
         extra=_color_plus_alpha('mg_case_art_alpha', 'Cubic', 'REPEAT'),
         note='Color + Alpha of 8x4 pixel art, alpha 0 to 1: Alpha linked, divided back'),
    # Box projection.
    Case(name='image_box_flat_linear', node='ShaderNodeTexImage', output='Color',
         **_box('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Linear', 'REPEAT', 0.0),
         note='box on the flat plane: the z plane alone'),
    Case(name='image_box_blend0_closest_extend', node='ShaderNodeTexImage', output='Color',
         normal=_XY,
         **_box('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Closest', 'EXTEND', 0.0),
         note='box, normal (1, 0.9, 0.05), Blend 0: x alone'),
    Case(name='image_box_blend02_xy_linear_clip', node='ShaderNodeTexImage', output='Color',
         normal=_XY,
         **_box('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Linear', 'CLIP', 0.2),
         note='box, normal (1, 0.9, 0.05), Blend 0.2: x and y'),
    Case(name='image_box_blend02_yz_cubic', node='ShaderNodeTexImage', output='Color',
         normal=_YZ,
         **_box('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Cubic', 'REPEAT', 0.2),
         note='box, normal (0.05, -0.9, 1), Blend 0.2: y and z'),
    Case(name='image_box_blend02_xz_closest', node='ShaderNodeTexImage', output='Color',
         normal=_XZ,
         **_box('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Closest', 'REPEAT', 0.2),
         note='box, normal (-1, 0.05, -0.9), Blend 0.2: x and z'),
    Case(name='image_box_blend02_xyz_linear_extend', node='ShaderNodeTexImage',
         output='Color', normal=_XYZ,
         **_box('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Linear', 'EXTEND', 0.2),
         note='box, normal (-0.8, 0.9, -1), Blend 0.2: all three'),
    Case(name='image_box_blend1_cubic_clip', node='ShaderNodeTexImage', output='Color',
         normal=_TILT,
         **_box('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Cubic', 'CLIP', 1.0),
         note='box, normal (1, -0.7, 0.5), Blend 1: all three'),
    Case(name='image_box_blend1_smart_srgb', node='ShaderNodeTexImage', output='Color',
         normal=_XYZ,
         **_box('mg_case_art', 8, 4, _pixel_art, 'sRGB', 'Smart', 'REPEAT', 1.0),
         note='box, sRGB: linearised per lookup, before the planes blend'),
    Case(name='image_box_blend02_linear_srgb', node='ShaderNodeTexImage', output='Color',
         normal=_XY,
         **_box('mg_case_art', 8, 4, _pixel_art, 'sRGB', 'Linear', 'REPEAT', 0.2),
         note='box, sRGB, Blend 0.2: x and y'),
    Case(name='image_box_premultiplied', node='ShaderNodeTexImage', output='Color',
         normal=_XY,
         **_box('mg_case_art_alpha', 8, 4, _pixel_art_alpha, 'sRGB', 'Linear', 'EXTEND', 0.2),
         note='box, alpha 0 to 1, Alpha unlinked: associated per lookup'),
    # Sphere and Tube: the vector mapped to a UV (Cycles' map_to_sphere / map_to_tube), then
    # a Flat lookup. Not with Linear and Repeat: that lookup is mip-mapped, and near the
    # centre, where the projections squeeze the image, it blurs (0.15) where Cycles does not.
    Case(name='image_sphere_linear_clip', node='ShaderNodeTexImage', output='Color',
         **_mapped('mg_case_smooth', 32, 32, _smooth, 'sRGB', 'Linear', 'CLIP', 'SPHERE'),
         note='sphere, smooth image, sRGB'),
    Case(name='image_sphere_closest', node='ShaderNodeTexImage', output='Color',
         **_mapped('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Closest', 'REPEAT',
                   'SPHERE'),
         note='sphere, 8x4 pixel art, Non-Color'),
    Case(name='image_tube_cubic', node='ShaderNodeTexImage', output='Color',
         **_mapped('mg_case_art_data', 8, 4, _pixel_art, 'Non-Color', 'Cubic', 'REPEAT',
                   'TUBE'),
         note='tube, 8x4 pixel art, Non-Color'),
    Case(name='image_tube_linear_extend', node='ShaderNodeTexImage', output='Color',
         **_mapped('mg_case_art', 8, 4, _pixel_art, 'sRGB', 'Linear', 'EXTEND', 'TUBE'),
         note='tube, 8x4 pixel art, sRGB'),
    Case(name='image_box_blend02_alpha', node='ShaderNodeTexImage', output='Alpha',
         normal=_XZ,
         **_box('mg_case_art_alpha', 8, 4, _pixel_art_alpha, 'sRGB', 'Closest', 'REPEAT',
                    0.2),
         note='box, alpha, Blend 0.2: x and z'),
]

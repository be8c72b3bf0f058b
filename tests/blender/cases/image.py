"""Image Texture by interpolation, on images the case builds inside Blender (packed, so the
export unpacks them next to the graph). Linear on a smooth periodic image (Cycles filters
without mip-maps; on a smooth image the two agree); Closest on pixel art of unrelated colours,
the UV doubled and shifted by whole texels (negative u and v: the floor and the repeat wrap),
so every bake pixel centre is an eighth of a texel or more from a texel edge and the texels
must match exactly (linear filtering blends neighbours and misses by up to 0.87). Extend and
Clip, with Closest and with Linear (ImageTextureBilinear: the four texels, no mip-maps), on
the same UV, which runs half an image beyond every edge; Cubic and Smart likewise. The images
whose Color is compared are opaque: with Alpha unlinked Cycles gives the colour
premultiplied.
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
    # Extend and Clip: the UV runs from -0.5 to 1.5, half an image beyond every edge. Linear
    # on Non-Color images (Cycles linearises sRGB texels before filtering, memograph after).
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
    Case(name='image_cubic_unassociated', node='ShaderNodeVectorMath', props={'operation': 'ADD'},
         output='Vector',
         extra=_color_plus_alpha('mg_case_art_alpha', 'Cubic', 'REPEAT'),
         note='Color + Alpha of 8x4 pixel art, alpha 0 to 1: Alpha linked, divided back'),
]

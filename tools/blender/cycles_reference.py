"""Cycles as memograph's reference (docs/guide/blender.md): the settings under which memograph is
compared with Cycles 3.4, for renders (CPU, no denoiser, no adaptive sampling, no clamping,
no light threshold, a one-pixel box filter: memograph's pixel, the Standard view transform,
a linear 32-bit EXR read back as a PFM) and for the node bakes (CPU, one sample, no
denoiser). Runs inside Blender (`blender -b --python ...`); used by the node and scene tests
and the Blender example."""

import array
import os
import sys

import bpy


def write_pfm(path, width, height, rgba):
    """3-channel little-endian PFM; Blender's pixels and PFM's rows both start at the bottom."""
    rgb = array.array('f', [0.0]) * (width * height * 3)
    for c in range(3):
        rgb[c::3] = array.array('f', rgba[c::4])
    if sys.byteorder != 'little':
        rgb.byteswap()
    with open(path, 'wb') as f:
        f.write(b'PF\n%d %d\n-1.0\n' % (width, height))
        f.write(rgb.tobytes())


def configure_bake(scene):
    """Cycles set up for baking material outputs: CPU, one sample (an emission bake of a
    texel centre needs no more), no denoiser, at most two threads."""
    scene.render.engine = 'CYCLES'
    scene.cycles.device = 'CPU'
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    scene.render.threads_mode = 'FIXED'
    scene.render.threads = max(1, min(2, os.cpu_count() or 1))


def render_reference_pfm(pfm_path, size, samples, max_bounces=None):
    """Renders the current scene at size x size with `samples` samples per pixel and writes
    it to pfm_path (the EXR Blender writes stays beside it). max_bounces: Cycles' total
    bounce limit, or None for Blender's default."""
    sc = bpy.context.scene
    sc.render.engine = 'CYCLES'
    sc.cycles.device = 'CPU'
    sc.cycles.samples = samples
    sc.cycles.use_denoising = False
    sc.cycles.use_adaptive_sampling = False
    sc.cycles.sample_clamp_direct = 0.0
    sc.cycles.sample_clamp_indirect = 0.0
    sc.cycles.light_sampling_threshold = 0.0
    sc.cycles.filter_type = 'BOX'
    sc.cycles.filter_width = 1.0
    if max_bounces is not None:
        sc.cycles.max_bounces = max_bounces
    sc.render.resolution_x = sc.render.resolution_y = size
    sc.render.resolution_percentage = 100
    sc.render.threads_mode = 'FIXED'
    sc.render.threads = max(1, min(2, os.cpu_count() or 1))
    sc.view_settings.view_transform = 'Standard'
    exr = os.path.splitext(pfm_path)[0] + '.exr'
    sc.render.filepath = exr
    sc.render.image_settings.file_format = 'OPEN_EXR'
    sc.render.image_settings.color_depth = '32'
    bpy.ops.render.render(write_still=True)
    write_pfm(pfm_path, size, size, list(bpy.data.images.load(exr).pixels))

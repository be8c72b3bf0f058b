"""Writes the table of Blender's shader nodes and what the exporter does with each:

    blender -b --factory-startup --python tools/blender/node_support_table.py -- FILE.md

Every node of the Add menu's Input, Output, Shader, Texture, Color, Vector and Converter
categories (Blender's own nodeitems_builtins.shader_node_categories) gets one row, its
status taken from the exporter's node map (writers.build_table(), shaders.SHADER_WRITERS):

  supported      a writer carries every output (and its spec every linked input);
  approximated   a writer exists, but outputs it lacks, or what APPROXIMATIONS says, differ;
  not supported  no writer: the outputs become the sockets' defaults, with a warning.

The table replaces the text between the BEGIN and END markers in FILE.md.
tests/blender/exporter_unit_test.py checks that the table names every node type the
exporter knows.
"""
import os
import sys

BEGIN = '<!-- blender-node-table: begin (tools/blender/node_support_table.py) -->'
END = '<!-- blender-node-table: end -->'
CATEGORIES = ('Shader', 'Texture', 'Color', 'Vector', 'Converter', 'Input', 'Output')

# What differs from Cycles for nodes that have a writer (docs/guide/blender.md, nodes.md).
APPROXIMATIONS = {
    'ShaderNodeBsdfPrincipled': '3.x Sheen, Clearcoat, Transmission (and their tint, '
                                'roughness, IOR sockets) as lobes `PrincipledLayers`, Clearcoat '
                                'Normal as the clearcoat lobe\'s own normal; under a Mix or Add '
                                'Shader with other BSDFs (3.x) `PrincipledBsdf` lobes (with its '
                                'Normal and Clearcoat Normal), its Alpha a Transparent lobe (as '
                                'Cycles expands it); '
                                'Subsurface, Anisotropic, Multiscatter GGX not carried (warned)',
    'ShaderNodeBsdfDiffuse': 'Principled with Specular 0, Roughness 1 (Oren-Nayar dropped)',
    'ShaderNodeBsdfGlossy': 'Principled metal (distribution dropped)',
    'ShaderNodeBsdfTransparent': 'opacity 0 (tint dropped)',
    'ShaderNodeAddShader': 'emissions summed, the surface of the non-emission side',
    'ShaderNodeTexImage': 'Linear with Repeat mip-mapped, associated with alpha after '
                          'filtering',
    'ShaderNodeVectorTransform': 'object space from the location only; camera = world',
    'ShaderNodeBump': 'heights differenced over memograph\'s footprint, not Cycles\' dP',
    'ShaderNodeTexCoord': 'From Instancer not carried',
    'ShaderNodeNormalMap': 'tangent space from the active UV only',
    'ShaderNodeTangent': 'the active UV map only',
    'ShaderNodeAttribute': 'the mesh\'s colour attribute only',
    'ShaderNodeAmbientOcclusion': 'rays about the interpolated normal (a linked Normal '
                                  'is warned and ignored); Distance and the settings must be '
                                  'constants; both architectures trace them',
    'ShaderNodeBevel': 'a linked Normal is warned and ignored; Radius and Samples must be '
                       'constants; both architectures trace them (the first 4 hits of a disk ray, '
                       'not a random 4)',
    'ShaderNodeLightPath': 'a Transparent BSDF\'s ray keeps the state it came with (a linked '
                           'Transparent Depth is 0); Is Shadow Ray is 1 only in a graph with a '
                           'Transparent BSDF, which shadow rays evaluate; '
                           'diffuse or glossy as memograph\'s BSDF picks its lobe',
}

# Why a node has no writer, where there is more to say than "no memograph node".
NOT_SUPPORTED = {
    'ShaderNodeCameraData': 'needs the render camera',
    'ShaderNodeScript': 'OSL scripts are not compiled',
    'ShaderNodeOutputLight': 'a light\'s node tree: lights are exported as lights',
    'ShaderNodeOutputWorld': 'the world is exported as a constant or an image (sidecar)',
    'ShaderNodeOutputAOV': 'memograph renders no AOVs',
    'ShaderNodeHoldout': 'memograph renders no holdouts',
    'ShaderNodeWireframe': 'needs the triangle\'s edges',
    'ShaderNodeTexIES': 'a light texture',
    'ShaderNodeTexPointDensity': 'needs particle or volume data',
    'ShaderNodeParticleInfo': 'no particles',
    'ShaderNodeHairInfo': 'no hair',
    'ShaderNodePointInfo': 'no point clouds',
    'ShaderNodeVolumeInfo': 'no volumes',
    'ShaderNodeLightFalloff': 'a light\'s node tree',
    'ShaderNodeShaderToRGB': 'EEVEE only',
    'ShaderNodeEeveeSpecular': 'EEVEE only',
    'ShaderNodeVolumeAbsorption': 'no volumes',
    'ShaderNodeVolumeScatter': 'no volumes',
    'ShaderNodeVolumePrincipled': 'no volumes',
    'ShaderNodeOutputLineStyle': 'Freestyle',
}
# Shaders written exactly as BSDF lobes (memograph_export/lobes.py, nodes/bsdf.inc) when the
# surface's tree holds only these, 3.x Principled BSDFs and Emission (a Mix or Add Shader whose
# sides need more than lobes.MAX_LOBES lobes, or two Principled BSDFs, at one hit chooses one
# side per hit); in a tree with any other shader (Subsurface, ...) APPROXIMATIONS' Principled
# fallback.
LOBE_SHADERS = {
    'ShaderNodeBsdfDiffuse': 'lobe `DiffuseBsdf` (Lambert; Oren-Nayar at Roughness > 0)',
    'ShaderNodeBsdfGlossy': 'lobe `GlossyBsdf` (GGX, Beckmann, Sharp; Multiscatter GGX and '
                            'Ashikhmin-Shirley as single-scatter GGX, warned)',
    'ShaderNodeBsdfVelvet': 'lobe `VelvetBsdf` (Ashikhmin velvet)',
    'ShaderNodeBsdfRefraction': 'lobe `RefractionBsdf` (GGX, Beckmann, Sharp; the path goes '
                                'through)',
    'ShaderNodeBsdfGlass': 'lobe `GlassBsdf` (GGX, Beckmann, Sharp, split by Fresnel as Cycles '
                           '3.4; Multiscatter GGX as GGX, warned)',
    'ShaderNodeBsdfTransparent': 'lobe `TransparentBsdf` (straight through, tinted; shadow '
                                 'rays pass it tinted, at most 8 such surfaces)',
    'ShaderNodeBsdfTranslucent': 'lobe `TranslucentBsdf` (Lambert on the far side)',
    'ShaderNodeMixShader': '`MixShader` splits the weight by Fac (textured Fac too); '
                           '`ChooseShader` picks one side per hit where both do not fit one '
                           'hit (noisier, the same mean)',
    'ShaderNodeAddShader': 'both shaders at its weight; `ChooseShader` picks one per hit where '
                           'both do not fit one hit',
}
# Each BSDF but Transparent is shaded about its own Normal (the sink's Normal input).
for _bsdf in ('ShaderNodeBsdfDiffuse', 'ShaderNodeBsdfGlossy', 'ShaderNodeBsdfVelvet',
              'ShaderNodeBsdfRefraction', 'ShaderNodeBsdfGlass', 'ShaderNodeBsdfTranslucent'):
    LOBE_SHADERS[_bsdf] += ', about its own Normal,'
LOBE_CONDITION = ('in a tree of Diffuse, Glossy, Velvet, Refraction, Glass, Transparent, '
                  'Translucent, 3.x Principled BSDF, Emission, Mix and Add Shader only; else ')

HANDLED_BY_WALK = {
    'ShaderNodeOutputMaterial': 'the walk starts here (Surface carried; Volume, '
                                'Displacement warned)',
}


def rows(categories, table, shader_writers, node_outputs):
    """[(category, bl_idname, label, status, how)] from the exporter's maps.
    node_outputs(bl_idname) -> [(identifier, name)] of a fresh node's enabled outputs."""
    out = []
    for category, items in categories:
        for bl_idname, label in items:
            writer = table.get(bl_idname)
            spec = getattr(writer, 'spec', None)
            if bl_idname in HANDLED_BY_WALK:
                status, how = 'supported', HANDLED_BY_WALK[bl_idname]
            elif bl_idname in LOBE_SHADERS:
                fallback = APPROXIMATIONS.get(bl_idname) or (
                    'parameters blended by Fac' if bl_idname == 'ShaderNodeMixShader' else
                    'a default Principled with its Color, Roughness and Normal')
                status = 'supported'
                how = '%s %s%s (warned)' % (LOBE_SHADERS[bl_idname], LOBE_CONDITION, fallback)
            elif bl_idname in shader_writers:
                note = APPROXIMATIONS.get(bl_idname)
                if bl_idname == 'ShaderNodeBsdfPrincipled':
                    status = 'approximated'
                elif bl_idname in ('ShaderNodeEmission', 'ShaderNodeMixShader'):
                    status, note = 'supported', 'exact'
                else:
                    status = 'approximated' if note else 'supported'
                how = note or ''
            elif writer is not None:
                missing = []
                if spec is not None:
                    missing = [name for ident, name in node_outputs(bl_idname)
                               if ident not in spec.outputs]
                notes = []
                if missing:
                    notes.append('outputs not carried: ' + ', '.join(missing))
                if bl_idname in APPROXIMATIONS:
                    notes.append(APPROXIMATIONS[bl_idname])
                status = 'approximated' if notes else 'supported'
                how = '; '.join(notes) or ('mgraph `%s`' % spec.mgraph
                                           if spec is not None and isinstance(spec.mgraph, str)
                                           else 'custom writer')
            elif bl_idname.startswith('ShaderNodeBsdf') or bl_idname in (
                    'ShaderNodeSubsurfaceScattering', 'ShaderNodeBackground'):
                status = 'approximated'
                how = 'a default Principled with its Color, Roughness and Normal (warned)'
            else:
                status = 'not supported'
                how = NOT_SUPPORTED.get(bl_idname, 'no memograph node')
                if category != 'Output':
                    how += '; its outputs become the defaults (warned)'
            out.append((category, bl_idname, label, status, how))
    return out


def markdown(table_rows):
    lines = ['| category | node | type | status | how / why |',
             '| --- | --- | --- | --- | --- |']
    for category, bl_idname, label, status, how in table_rows:
        lines.append('| %s | %s | `%s` | %s | %s |' % (category, label, bl_idname, status,
                                                       how.replace('|', '\\|')))
    return '\n'.join(lines)


def main(argv):
    import bpy
    import nodeitems_builtins
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, here)
    sys.dont_write_bytecode = True
    from memograph_export import shaders, writers

    by_name = {c.name: c for c in nodeitems_builtins.shader_node_categories}
    categories = []
    for name in CATEGORIES:
        items = []
        for item in by_name[name].items(None):
            idname = getattr(item, 'nodetype', None)
            if idname and idname not in [i for i, _ in items]:
                items.append((idname, item.label))
        categories.append((name, items))
    # Types the exporter writes that the 3.4 menu no longer offers (legacy nodes of older
    # files): listed too, so that the table names every type the exporter knows.
    table = writers.build_table()
    listed = {i for _, items in categories for i, _ in items}
    legacy = sorted((set(table) | set(shaders.SHADER_WRITERS)) - listed)
    categories.append(('Legacy (not in the Add menu)',
                       [(i, getattr(bpy.types, i).bl_rna.name) for i in legacy]))
    tree = bpy.data.node_groups.new('node_support_table', 'ShaderNodeTree')

    def node_outputs(bl_idname):
        node = tree.nodes.new(bl_idname)
        return [(s.identifier, s.name) for s in node.outputs if s.enabled]

    text = markdown(rows(categories, table, shaders.SHADER_WRITERS,
                         node_outputs))
    path = argv[0]
    with open(path) as f:
        doc = f.read()
    start, end = doc.index(BEGIN) + len(BEGIN), doc.index(END)
    with open(path, 'w') as f:
        f.write(doc[:start] + '\n' + text + '\n' + doc[end:])
    print('node_support_table: %d nodes written to %s' % (
        sum(len(i) for _, i in categories), path))


if __name__ == '__main__':
    main(sys.argv[sys.argv.index('--') + 1:] if '--' in sys.argv else [])

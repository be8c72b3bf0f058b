"""memograph exporter: Blender material node trees -> memograph .mgraph graphs.

Layout (one module per concern, after io_scene_gltf2):
  spec.py      declarative NodeSpec and the loader of specs/<family>.py
  specs/       one declarative table per node family
  graph.py     Blender-side walking: flattens a material's node tree (groups, reroutes,
               muted nodes, implicit conversions) into a small graph of real nodes
  writers.py   the table node type -> writer (specs + custom writers) and the writers
  shaders.py   shader nodes (Principled BSDF, Mix Shader, ...) -> memograph outputs
  mgraph.py    the .mgraph text builder (deterministic link numbering, literals)
  compat.py    Blender version differences (4.x socket renames) as name lookups
  exporter.py  export_materials(): the public entry point, files and the index
  ui.py        the File > Export operator and menu (the only UI code)

Nothing here imports bpy at module level except ui.py (and the functions that get bpy data
passed in), so the pure-Python parts are unit-tested outside Blender.
"""

bl_info = {
    'name': 'memograph exporter',
    'author': 'memograph',
    'version': (0, 1, 0),
    'blender': (3, 4, 0),
    'location': 'File > Export > memograph (.mgraph)',
    'description': 'Exports material node trees as memograph .mgraph graphs',
    'category': 'Import-Export',
}


def register():
    from . import ui
    ui.register()


def unregister():
    from . import ui
    ui.unregister()

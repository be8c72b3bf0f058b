"""File > Export > memograph (.mgraph): the operator and its menu entry (UI only; the
export itself is exporter.export_materials)."""

import bpy
from bpy.props import BoolProperty, StringProperty


class EXPORT_SCENE_OT_memograph(bpy.types.Operator):
    """Export materials as memograph .mgraph graphs (one file per material)"""

    bl_idname = 'export_scene.memograph'
    bl_label = 'Export memograph'
    bl_options = {'PRESET'}

    directory: StringProperty(name='Directory', subtype='DIR_PATH',
                              description='Folder that receives the .mgraph files')
    filter_folder: BoolProperty(default=True, options={'HIDDEN'})
    use_selection: BoolProperty(name='Selected Objects Only', default=False,
                                description='Export only the materials of selected objects')
    export_scene: BoolProperty(name='Export Scene (glTF)', default=True,
                               description='Also write scene.gltf (Blender\'s glTF exporter) '
                                           'and its sidecar scene.memograph')

    def execute(self, context):
        from . import exporter
        if not self.directory:
            self.report({'ERROR'}, 'No output directory')
            return {'CANCELLED'}
        if self.use_selection:
            mats = []
            for obj in context.selected_objects:
                for slot in getattr(obj, 'material_slots', ()):
                    if slot.material is not None and slot.material not in mats:
                        mats.append(slot.material)
        else:
            mats = list(bpy.data.materials)
        try:
            result = exporter.export_materials(mats, bpy.path.abspath(self.directory))
        except Exception as exc:  # the export's own errors, shown in the UI
            self.report({'ERROR'}, 'memograph export failed: %s' % exc)
            return {'CANCELLED'}
        for material, node, message in result.warnings:
            self.report({'WARNING'}, '%s: %s: %s' % (material, node, message))
        for material, message in result.errors:
            self.report({'ERROR'}, '%s: %s' % (material, message))
        if self.export_scene and not result.errors:
            from . import scene as scene_export
            try:
                _, _, scene_warnings = scene_export.export_scene(
                    bpy.path.abspath(self.directory), result.names, context,
                    use_selection=self.use_selection)
            except Exception as exc:  # the graphs are written: report, keep them
                # A warning, not an error: from a script an ERROR report raises.
                self.report({'WARNING'}, 'memograph scene export failed (the glTF exporter '
                            'needs numpy): %s' % exc)
                scene_warnings = []
            for message in scene_warnings:
                self.report({'WARNING'}, 'scene: %s' % message)
        self.report({'INFO'}, 'memograph: wrote %d material(s), %d warning(s)'
                    % (len(result.files), len(result.warnings)))
        return {'FINISHED'}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}


def menu_func_export(self, context):
    self.layout.operator(EXPORT_SCENE_OT_memograph.bl_idname, text='memograph (.mgraph)')


def register():
    bpy.utils.register_class(EXPORT_SCENE_OT_memograph)
    bpy.types.TOPBAR_MT_file_export.append(menu_func_export)


def unregister():
    bpy.types.TOPBAR_MT_file_export.remove(menu_func_export)
    bpy.utils.unregister_class(EXPORT_SCENE_OT_memograph)

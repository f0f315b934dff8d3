"""The radfarm tab of the 3D view's sidebar (N)."""

import bpy

from . import job_runner
from . import operators


class RADFARM_PT_bake(bpy.types.Panel):
    bl_idname = "RADFARM_PT_bake"
    bl_label = "radfarm"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "radfarm"

    def draw(self, context):
        settings = context.scene.radfarm
        layout = self.layout
        layout.use_property_split = True
        layout.prop(settings, "where", expand=True)
        if settings.where == "FARM":
            layout.prop(settings, "control")
        layout.prop(settings, "folder")
        layout.prop(settings, "selected_only")
        layout.prop(settings, "result")
        quality = layout.column(heading="Quality")
        quality.prop(settings, "tolerance")
        quality.prop(settings, "patch_size")
        quality.prop(settings, "seconds")
        quality.prop(settings, "lightmap_size")
        runner = operators._Bake.runner
        if operators.baking():
            layout.label(text=operators.status_line(runner), icon="TIME")
            layout.operator("radfarm.cancel", icon="CANCEL")
        else:
            if runner is not None and runner.message:
                layout.label(text=runner.message, icon="ERROR")
            elif runner is not None and runner.state == job_runner.DONE and operators._Bake.summary:
                layout.label(text=operators._Bake.summary, icon="CHECKMARK")
            layout.operator("radfarm.bake", icon="LIGHT_SUN")
            layout.operator("radfarm.apply", icon="FILE_REFRESH")


def register():
    bpy.utils.register_class(RADFARM_PT_bake)


def unregister():
    bpy.utils.unregister_class(RADFARM_PT_bake)

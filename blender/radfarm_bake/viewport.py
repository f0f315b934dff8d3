"""Sets Blender's viewports so a bake's result shows as radfarm lit it."""

import bpy


def _shadings():
    # Every 3D view of every screen, and the scene's own (what Workbench renders use).
    for screen in bpy.data.screens:
        for area in screen.areas:
            for space in area.spaces:
                if space.type == "VIEW_3D":
                    yield space.shading


def show_vertex_colours(scene, exposure_stops):
    """Solid shading from the lit copies' colour attribute, flat (the light is in the colours),
    backface culling on: a two-sided wall comes back as two surfaces back to back, each with the
    light of its own side, and only the side facing the eye should show."""
    _colour_management(scene, exposure_stops)
    for shading in list(_shadings()) + [scene.display.shading]:
        shading.type = "SOLID"
        shading.light = "FLAT"
        shading.color_type = "VERTEX"
        shading.show_backface_culling = True


def show_materials(scene, exposure_stops):
    """Material Preview: the lightmaps are emission in the objects' materials."""
    _colour_management(scene, exposure_stops)
    for shading in _shadings():
        shading.type = "MATERIAL"


def _colour_management(scene, exposure_stops):
    # The colours are linear radiance: the Standard transform at the exposure of radfarm's own
    # image shows them as image.png does (Filmic would compress them again).
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.exposure = exposure_stops

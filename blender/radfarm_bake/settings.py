"""The panel's settings (per scene) and the add-on's preferences (per user)."""

import os
import shutil

import bpy

_PACKAGE = __package__


class RadfarmPreferences(bpy.types.AddonPreferences):
    bl_idname = _PACKAGE

    radfarm_path: bpy.props.StringProperty(
        name="radfarm program",
        description="The radfarm command to run (empty: the one that installed the add-on, else "
        "radfarm on the PATH)",
        subtype="FILE_PATH",
    )

    def draw(self, context):
        self.layout.prop(self, "radfarm_path")
        self.layout.label(text="Running: " + (radfarm_program(context) or "no radfarm found"))


def radfarm_program(context):
    """The preference, else the program `radfarm blender-addon install` recorded, else PATH's."""
    preferences = context.preferences.addons[_PACKAGE].preferences
    if preferences.radfarm_path:
        return bpy.path.abspath(preferences.radfarm_path)
    recorded = os.path.join(os.path.dirname(__file__), "radfarm_program")
    if os.path.isfile(recorded):
        with open(recorded) as f:
            path = f.read().strip()
        if os.access(path, os.X_OK):
            return path
    return shutil.which("radfarm")


class RadfarmSettings(bpy.types.PropertyGroup):
    where: bpy.props.EnumProperty(
        name="Where",
        items=(("LOCAL", "This machine", "Run radfarm render here"),
               ("FARM", "Farm", "Submit to a radfarm master through its control socket")),
        default="LOCAL",
    )
    control: bpy.props.StringProperty(
        name="Control socket",
        description="The master's control socket (radfarmd's state folder, control.sock)",
        default=os.environ.get("RADFARM_CONTROL", "/var/lib/radfarm/control.sock"),
        subtype="FILE_PATH",
    )
    folder: bpy.props.StringProperty(
        name="Folder",
        description="Where the exported scene and the result go (// is the .blend file's "
        "folder; an unsaved file uses a temporary folder)",
        default="//radfarm",
        subtype="DIR_PATH",
    )
    selected_only: bpy.props.BoolProperty(
        name="Selected only", description="Export the selected objects only", default=False)
    result: bpy.props.EnumProperty(
        name="Result",
        items=(("LIT_COPIES", "Lit copies",
                "Import the lit objects beside yours (yours hidden), shown in Solid view"),
               ("LIGHTMAPS", "Lightmaps",
                "Add each lightmap to your own object's materials (objects with a second UV "
                "map); the others come back as lit copies, their lightmaps in UVs radfarm "
                "made; shown in Material Preview")),
        default="LIT_COPIES",
    )
    tolerance: bpy.props.FloatProperty(
        name="Tolerance", description="Stop when the unshot light is below this share of the "
        "emitted light", default=0.001, min=1e-6, max=0.5, precision=4)
    patch_size: bpy.props.FloatProperty(
        name="Patch size", description="Largest patch edge in metres (0: automatic)",
        default=0.0, min=0.0, unit="LENGTH")
    seconds: bpy.props.FloatProperty(
        name="Time budget", description="Seconds for the whole render (0: no limit)",
        default=0.0, min=0.0)
    lightmap_size: bpy.props.IntProperty(
        name="Lightmap size", description="Texels on a lightmap's side (0: by each object's "
        "area)", default=0, min=0, max=8192)


CLASSES = (RadfarmPreferences, RadfarmSettings)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.radfarm = bpy.props.PointerProperty(type=RadfarmSettings)


def unregister():
    del bpy.types.Scene.radfarm
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)

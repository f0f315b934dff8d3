"""radfarm Bake: light the open scene with radfarm (on this machine or a farm) from Blender.

The radfarm tab of the 3D view's sidebar: Bake exports the scene, runs radfarm, shows its progress
and ETA in the status bar, and applies the result (lit copies or lightmaps) with the viewport set
to show it. Installed by `radfarm blender-addon install`; docs/USAGE.md, "From Blender".
"""

bl_info = {
    "name": "radfarm Bake",
    "description": "Light the scene by radiosity with radfarm, here or on a farm, and apply it",
    "author": "radfarm developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > radfarm",
    "category": "Lighting",
}

from . import operators  # noqa: E402  (bl_info first: Blender reads it without importing)
from . import panel  # noqa: E402
from . import settings  # noqa: E402

_MODULES = (settings, operators, panel)


def register():
    for module in _MODULES:
        module.register()


def unregister():
    for module in reversed(_MODULES):
        module.unregister()

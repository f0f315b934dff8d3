"""Writes the open scene as radfarm reads it: scene.glb and a job file beside it."""

import os

import bpy


def export_scene(folder, settings):
    """Exports to FOLDER/scene.glb and writes FOLDER/job.toml; returns the job file's path.

    The glTF choices the round trip needs, made here so the user makes none: modifiers applied
    (radfarm lights the mesh as it is drawn), +Y up (glTF's axes, which radfarm reads as they
    are), every UV map (a second one is where a lightmap goes), lamps in the units of emission
    strength (radfarm's solver works in the emitters' radiance, so a lamp's watts are divided by
    4 pi without the 683 lm/W that would make it 683 times brighter than an emissive mesh), no
    animation, and the objects by name (lit.glb gives them back under those names).
    """
    os.makedirs(folder, exist_ok=True)
    scene_path = os.path.join(folder, "scene.glb")
    bpy.ops.export_scene.gltf(
        filepath=scene_path,
        export_format="GLB",
        use_selection=settings.selected_only,
        use_visible=True,
        export_apply=True,
        export_yup=True,
        export_texcoords=True,
        export_normals=True,
        export_materials="EXPORT",
        export_colors=False,
        export_cameras=True,
        export_lights=True,
        convert_lighting_mode="COMPAT",
        export_animations=False,
        export_skins=False,
        export_morph=False,
        export_extras=False,
    )
    job_path = os.path.join(folder, "job.toml")
    with open(job_path, "w") as job:
        job.write(job_text(settings))
    return job_path


def job_text(settings):
    """The job file: the panel's quality settings; every other key keeps radfarm's default."""
    lines = ["# Written by the radfarm Blender add-on for its last bake.",
             'scene = "scene.glb"', ""]
    if settings.patch_size > 0:
        lines += ["[mesh]", "patch_size = %r" % settings.patch_size, ""]
    lines += ["[solver]", "tolerance = %r" % settings.tolerance]
    if settings.seconds > 0:
        lines.append("seconds = %r" % settings.seconds)
    lines.append("")
    if settings.lightmap_size > 0:
        lines += ["[output]", "lightmap_size = %d" % settings.lightmap_size, ""]
    return "\n".join(lines)

"""Bake, Cancel and Apply. Bake from the UI is a modal operator: a window timer polls the running
radfarm commands (job_runner.py) and the UI never waits for them; from a script or in background
mode, where Blender calls execute (no window events), Bake waits for the result itself."""

import atexit
import os
import tempfile

import bpy

from . import apply
from . import export
from . import job_runner
from .settings import radfarm_program


class _Bake:
    """The bake in progress or the last one: one at a time per Blender session."""

    runner = None
    out_dir = None
    summary = ""  # what the last apply did, for the panel


def work_folder(settings):
    """The folder for the export and the result: the panel's, or a temporary one for a file
    never saved (// means the .blend file's folder)."""
    if settings.folder.startswith("//") and not bpy.data.filepath:
        if _Bake.out_dir is None:
            return tempfile.mkdtemp(prefix="radfarm-")
        return os.path.dirname(_Bake.out_dir)
    return bpy.path.abspath(settings.folder)


def baking():
    return _Bake.runner is not None and _Bake.runner.state == job_runner.RUNNING


def status_line(runner):
    eta = "" if runner.eta_seconds is None else ", ETA %ds" % runner.eta_seconds
    return "radfarm: %s, %d%%%s" % (runner.stage, int(100 * runner.progress), eta)


def _advance(context, wait_seconds=0.0):
    """Takes in what the bake's commands printed (waiting up to WAIT_SECONDS for it) and shows it
    in the status bar and the panel; returns True while the bake runs. Both ways of running Bake
    call it: the modal operator at each timer tick, and execute in a loop."""
    running = _Bake.runner.poll(wait_seconds)
    if context.workspace is not None:
        context.workspace.status_text_set(status_line(_Bake.runner) if running else None)
    for area in context.screen.areas if context.screen is not None else []:
        if area.type == "VIEW_3D":
            area.tag_redraw()
    return running


def _export_originals(settings, folder):
    # The export sees the user's own objects as they were before any bake: the originals lit
    # copies hid are shown, the lit copies hidden, the lightmaps unplugged from the materials,
    # and all put back as they were afterwards.
    shown = apply.show_originals()
    collection = bpy.data.collections.get(apply.LIT_COLLECTION)
    copies = [o for o in collection.objects if o.visible_get()] if collection else []
    for obj in copies:
        obj.hide_set(True)
    unplugged = apply.unplug_lightmaps()
    try:
        return export.export_scene(folder, settings)
    finally:
        apply.plug_lightmaps(unplugged)
        for obj in copies:
            obj.hide_set(False)
        for obj in shown:
            obj.hide_set(True)
            obj["radfarm_hidden"] = True


class RADFARM_OT_bake(bpy.types.Operator):
    bl_idname = "radfarm.bake"
    bl_label = "Bake"
    bl_description = "Export the scene, light it with radfarm and apply the result"
    bl_options = {"REGISTER", "UNDO"}

    _timer = None

    @classmethod
    def poll(cls, context):
        return not baking()

    def _start(self, context):
        settings = context.scene.radfarm
        program = radfarm_program(context)
        if program is None:
            self.report({"ERROR"}, "radfarm not found: set its path in the add-on's preferences")
            return False
        folder = work_folder(settings)
        try:
            job_file = _export_originals(settings, folder)
        except (OSError, RuntimeError) as error:
            self.report({"ERROR"}, "radfarm: the export failed: %s" % error)
            return False
        _Bake.out_dir = os.path.join(folder, "out")
        control = bpy.path.abspath(settings.control) if settings.where == "FARM" else None
        _Bake.runner = job_runner.JobRunner(program, job_file, _Bake.out_dir, control)
        return True

    def _finish(self, context):
        runner = _Bake.runner
        if runner.state == job_runner.DONE:
            _Bake.summary = apply.apply_result(context, _Bake.out_dir,
                                               context.scene.radfarm.result)
            self.report({"INFO"}, _Bake.summary)
            return {"FINISHED"}
        if runner.state == job_runner.FAILED:
            self.report({"ERROR"}, "radfarm: " + runner.message)
        else:
            self.report({"WARNING"}, "radfarm: cancelled")
        return {"CANCELLED"}

    def execute(self, context):
        if not self._start(context):
            return {"CANCELLED"}
        while _advance(context, wait_seconds=1.0):
            pass
        return self._finish(context)

    def invoke(self, context, event):
        if not self._start(context):
            return {"CANCELLED"}
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.25, window=context.window)
        wm.modal_handler_add(self)
        _advance(context)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type != "TIMER":  # ours, or another's: polling more often does no harm
            return {"PASS_THROUGH"}
        if _advance(context):
            return {"PASS_THROUGH"}
        context.window_manager.event_timer_remove(self._timer)
        return self._finish(context)


class RADFARM_OT_cancel(bpy.types.Operator):
    bl_idname = "radfarm.cancel"
    bl_label = "Cancel"
    bl_description = "Stop the bake (a farm job is cancelled on the master)"

    @classmethod
    def poll(cls, context):
        return baking()

    def execute(self, context):
        _Bake.runner.cancel()
        return {"FINISHED"}


class RADFARM_OT_apply(bpy.types.Operator):
    bl_idname = "radfarm.apply"
    bl_label = "Apply Again"
    bl_description = "Apply the last bake's result again, as the panel's Result says"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return (not baking() and _Bake.out_dir is not None
                and os.path.isfile(os.path.join(_Bake.out_dir, "lit.glb")))

    def execute(self, context):
        _Bake.summary = apply.apply_result(context, _Bake.out_dir, context.scene.radfarm.result)
        self.report({"INFO"}, _Bake.summary)
        return {"FINISHED"}


@bpy.app.handlers.persistent
def _cancel_on_load(_):
    # Opening another file ends the modal operator that polled the bake: nothing would ever
    # apply it, so it stops, and its folder belongs to the file it came from.
    if baking():
        _Bake.runner.cancel()
    _Bake.runner = None
    _Bake.out_dir = None
    _Bake.summary = ""


def _cancel_on_quit():
    # Quitting Blender leaves no radfarm command running and no farm job nobody will fetch.
    if baking():
        _Bake.runner.cancel()


CLASSES = (RADFARM_OT_bake, RADFARM_OT_cancel, RADFARM_OT_apply)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.app.handlers.load_pre.append(_cancel_on_load)
    atexit.register(_cancel_on_quit)


def unregister():
    if _cancel_on_load in bpy.app.handlers.load_pre:
        bpy.app.handlers.load_pre.remove(_cancel_on_load)
    atexit.unregister(_cancel_on_quit)
    if baking():
        _Bake.runner.cancel()
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)

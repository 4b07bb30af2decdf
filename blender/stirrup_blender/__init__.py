# stirrup in Blender: ride, check and review a shot without leaving it (docs/blender.md).
#
# Pick the horse and rider armatures in the 3D view's sidebar (Stirrup tab). Ride keys the rider's own
# bones over the scene's frame range from the horse's action (or a generated gait when it has none),
# seated as `stirrup bake --rider-only` seats her; Live keeps her on the horse while the horse's keys are
# edited or the frame changes; Check runs `stirrup check` on the shot and marks flagged frames on the
# timeline; Review movie renders stirrup's side, perspective or close movie of the shot as it stands.
# The work is the stirrup program's: the add-on exports the armatures with Blender's own glTF exporter,
# writes a scene and the mappings, runs the program and reads its files back.
bl_info = {
    "name": "stirrup",
    "author": "stirrup maintainers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Stirrup",
    "description": "Seat a rider on a keyed horse with stirrup (Kuhnel 2003's rig), check the shot, render review movies",
    "doc_url": "https://github.com/stirrup/stirrup/blob/main/docs/blender.md",
    "category": "Animation",
}

if "bpy" in locals():  # a reload (F3 > Reload Scripts): take the modules' new code
    import importlib
    for _m in (program, gltf_files, transforms, layer, controls, export, mapping, reduce, tack, ride, live, check, review, properties, panel):  # noqa: F821
        importlib.reload(_m)
else:
    from . import program, gltf_files, transforms, layer, controls, export, mapping, reduce, tack, ride, live, check, review, properties, panel

import bpy
from bpy.app.handlers import persistent

_classes = properties.classes + ride.classes + live.classes + check.classes + review.classes + panel.classes


@persistent
def _before_load(_):
    """Live ends with the file it was on (its process, handlers and timer)."""
    live.stop_all()


@persistent
def _on_load(_):
    """A file saved while Live was on holds its helper armature and constraints, her action set aside and the
    ride's layer muted, and Live is off now: all put back."""
    controls.clear_leftovers()
    for scene in bpy.data.scenes:
        s = scene.stirrup
        if s.get("live"):
            s["live"] = False  # (no update call: there is no session to stop)
            live.restore(s)


def register():
    for c in _classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.stirrup = bpy.props.PointerProperty(type=properties.StirrupSettings)
    bpy.app.handlers.load_pre.append(_before_load)
    bpy.app.handlers.load_post.append(_on_load)


def unregister():
    for handlers, h in ((bpy.app.handlers.load_pre, _before_load), (bpy.app.handlers.load_post, _on_load)):
        if h in handlers:
            handlers.remove(h)
    live.stop_all()
    del bpy.types.Scene.stirrup
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)

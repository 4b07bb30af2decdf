# What the add-on keeps in the .blend: the armatures chosen, the profile and seat, the mapping choices
# (as `stirrup character map` made them, editable), the last check's findings and the live state.
import bpy

from . import live, program


def _is_armature(self, obj):
    return obj.type == "ARMATURE"


class StirrupRole(bpy.types.PropertyGroup):
    role: bpy.props.StringProperty(name="Role")
    joint: bpy.props.StringProperty(name="Bone", description="The bone that plays this role (a deform bone of the armature)")


class StirrupMapping(bpy.types.PropertyGroup):
    """One character's mapping (rig/mapping/character_mapping.h): which bone plays which role, and how its glTF
    world becomes stirrup's, as of when the armature object stood at `object_matrix`."""
    armature: bpy.props.StringProperty(name="Made for", description="The armature object this mapping was made for")
    roles: bpy.props.CollectionProperty(type=StirrupRole)
    roles_index: bpy.props.IntProperty()
    scale_cm: bpy.props.FloatProperty(name="Scale (cm a unit)", default=100.0, min=1e-6)
    forward: bpy.props.FloatVectorProperty(name="Forward", size=3, default=(0.0, 0.0, 1.0), description="Its forward in the glTF file (Y up)")
    up: bpy.props.FloatVectorProperty(name="Up", size=3, default=(0.0, 1.0, 0.0), description="Its up in the glTF file (Y up)")
    offset_cm: bpy.props.FloatVectorProperty(name="Offset (cm)", size=3, default=(0.0, 0.0, 0.0))
    object_matrix: bpy.props.FloatVectorProperty(size=16, default=(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1))
    report: bpy.props.StringProperty(name="character map said")
    controls_text: bpy.props.StringProperty(
        name="Controls", default="",
        description="A rider's control rig that is neither Rigify's nor a bare skeleton: the Blender text holding which "
                    "control follows which deform bone (JSON: follow, twist, pole, set; docs/blender.md)")


class StirrupFinding(bpy.types.PropertyGroup):
    frame: bpy.props.IntProperty()
    rule: bpy.props.StringProperty()
    severity: bpy.props.StringProperty()
    text: bpy.props.StringProperty()


def _live_update(self, context):
    try:
        if self.live:
            live.start(context)
        else:
            live.stop(context)
    except program.StirrupError as e:
        live.stop(context)
        self["live"] = False  # off again without calling back
        live.report_error(str(e))


def _go_to_finding(self, context):
    if 0 <= self.findings_index < len(self.findings):
        context.scene.frame_set(self.findings[self.findings_index].frame)


class StirrupSettings(bpy.types.PropertyGroup):
    horse: bpy.props.PointerProperty(name="Horse", type=bpy.types.Object, poll=_is_armature,
                                     description="The horse's armature: its action is the ride")
    rider: bpy.props.PointerProperty(name="Rider", type=bpy.types.Object, poll=_is_armature,
                                     description="The rider's armature: ride keys its bones")
    profile: bpy.props.EnumProperty(name="Profile", items=[
        ("thesis", "Thesis", "Kuhnel's rider as the thesis tuned her"),
        ("english", "English", "An English rider"),
        ("novice", "Novice", "A novice: looser, later")], default="thesis")
    stirrup_holes_up: bpy.props.IntProperty(
        name="Stirrup holes up", default=2, min=0, max=8,
        description="seat.stirrup_holes_up: her leathers taken up this many 2.5 cm holes from the tread at her ankle "
                    "with the leg hanging (0 dressage, 2 general purpose, 4 jumping)")
    gait: bpy.props.EnumProperty(name="Gait", items=[
        ("walk", "Walk", ""), ("trot", "Trot", ""), ("canter", "Canter", ""), ("gallop", "Gallop", "")],
        default="trot", description="The gait stirrup generates for a horse without an action (ride keys the horse too)")
    limbs: bpy.props.EnumProperty(name="Limbs", items=[
        ("IK", "IK", "Her feet on foot_ik, her hands on hand_ik, knees and elbows by the IK base's twist or the pole"),
        ("FK", "FK", "Her limbs on their FK controls")], default="IK",
        description="Which of a control rig's limb controls Ride keys (the IK/FK switch keyed to match)")
    reduce_keys: bpy.props.BoolProperty(
        name="Reduce keys", default=False,
        description="Thin the ride's keys with Blender's decimation to the fewest that keep her joints within the tolerance")
    reduce_tolerance_cm: bpy.props.FloatProperty(
        name="Tolerance (cm)", default=0.25, min=0.01, max=10.0,
        description="How far (cm, in the world) reduced keys may let any of her joints stray from the ride")
    horse_map: bpy.props.PointerProperty(type=StirrupMapping)
    rider_map: bpy.props.PointerProperty(type=StirrupMapping)
    live: bpy.props.BoolProperty(name="Live", default=False, update=_live_update,
                                 description="Keep the rider on the horse while its keys are edited or the frame changes")
    live_saved_action: bpy.props.PointerProperty(type=bpy.types.Action)
    camera: bpy.props.EnumProperty(name="View", items=[
        ("side", "Side", "stirrup's side view"), ("persp", "Perspective", "stirrup's perspective view"),
        ("close", "Close", "stirrup's close view of the rider")], default="side")
    work_dir: bpy.props.StringProperty(name="Working folder", subtype="DIR_PATH", default="",
                                       description="Where the exports, scene and mappings go (empty: a folder in Blender's temporary folder)")
    check_summary: bpy.props.StringProperty()
    check_unmeasured: bpy.props.StringProperty(description="The rules the last check could not measure on this shot")
    findings: bpy.props.CollectionProperty(type=StirrupFinding)
    findings_index: bpy.props.IntProperty(update=_go_to_finding, description="The finding shown: its frame made current")
    last_ride: bpy.props.StringProperty()


classes = [program.StirrupPreferences, StirrupRole, StirrupMapping, StirrupFinding, StirrupSettings]

# The sidebar panel (3D view, "Stirrup" tab): the armatures, the profile and seat, Ride, Live, Check and
# Review movie, and the mapping choices kept in the .blend.
import os
import textwrap

import bpy

from . import export, live, mapping, program, review


class STIRRUP_OT_map(bpy.types.Operator):
    """Map the armature with `stirrup character map` now (its choices are kept in the .blend and can be edited)"""
    bl_idname = "stirrup.map"
    bl_label = "Map"
    bl_options = {"REGISTER", "UNDO"}
    kind: bpy.props.EnumProperty(items=[("horse", "Horse", ""), ("rider", "Rider", "")])

    def execute(self, context):
        s = context.scene.stirrup
        obj = getattr(s, self.kind)
        if obj is None:
            self.report({"ERROR"}, "no %s chosen: pick the %s's armature in the Stirrup panel" % (self.kind, self.kind))
            return {"CANCELLED"}
        try:
            work = export.work_dir(context)
            glb = export.export(context, [obj], os.path.join(work, self.kind + "-rest.glb"), False)
            data, said = mapping.made(self.kind, glb, work, context)
        except program.StirrupError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        mapping.keep(context, getattr(s, self.kind + "_map"), obj, data, said)
        self.report({"INFO"}, said.strip().splitlines()[0] if said.strip() else "mapped")
        return {"FINISHED"}


class STIRRUP_UL_roles(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_propname, index):
        row = layout.row(align=True)
        row.label(text=item.role)
        arm = getattr(context.scene.stirrup, self.list_id.split("_")[-1], None)
        if arm is not None:
            row.prop_search(item, "joint", arm.data, "bones", text="")
        else:
            row.prop(item, "joint", text="")


class STIRRUP_UL_findings(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_propname, index):
        icon = {"failure": "ERROR", "warning": "INFO"}.get(item.severity, "DOT")
        layout.label(text="%d  %s" % (item.frame, item.rule), icon=icon)


def _lines(layout, context, text, icon="NONE"):
    """`text` as labels wrapped to the sidebar's width (a label is cut off, not wrapped)."""
    chars = max(16, int(context.region.width / (6.5 * context.preferences.system.ui_scale)) - (6 if icon != "NONE" else 2))
    for k, line in enumerate(textwrap.wrap(text, chars) or [""]):
        layout.label(text=line, icon=icon if k == 0 else "BLANK1" if icon != "NONE" else "NONE")


class VIEW3D_PT_stirrup(bpy.types.Panel):
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Stirrup"
    bl_label = "stirrup"

    def draw(self, context):
        s = context.scene.stirrup
        col = self.layout.column()
        col.prop(s, "horse")
        col.prop(s, "rider")
        col.prop(s, "profile")
        col.prop(s, "stirrup_holes_up")
        if s.horse is not None and not export.has_action(s.horse):
            col.prop(s, "gait")
        row = col.row(align=True)
        row.prop(s, "limbs", expand=True)
        row = col.row(align=True)
        row.prop(s, "reduce_keys")
        sub = row.row(align=True)
        sub.active = s.reduce_keys
        sub.prop(s, "reduce_tolerance_cm", text="cm")
        row = col.row(align=True)
        row.scale_y = 1.4
        row.operator("stirrup.ride", icon="ARMATURE_DATA")
        row.prop(s, "live", toggle=True, icon="REC" if s.live else "PLAY")
        if s.last_ride:
            _lines(col, context, s.last_ride)
        session = live.session()
        if session is not None:
            row = col.row()
            row.label(text="live: %.1f ms in stirrup" % session.last_ms)
            row.operator("stirrup.live_refresh", text="", icon="FILE_REFRESH")
        if live.last_error():
            _lines(col, context, live.last_error(), icon="ERROR")
        col.separator()
        col.operator("stirrup.check", icon="CHECKMARK")
        if s.check_summary:
            _lines(col, context, s.check_summary)
            if s.check_unmeasured:
                _lines(col, context, "not measured: " + s.check_unmeasured, icon="INFO")
            if s.findings:
                col.template_list("STIRRUP_UL_findings", "", s, "findings", s, "findings_index", rows=3)
                if 0 <= s.findings_index < len(s.findings):
                    f = s.findings[s.findings_index]
                    _lines(col, context, "frame %d, %s: %s" % (f.frame, f.severity, f.text))
        col.separator()
        col.prop(s, "camera")
        col.operator("stirrup.review_movie", icon="RENDER_ANIMATION")
        if review.rendering():
            col.label(text="rendering: the status bar shows how far (Esc stops)")


class _MappingPanel:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Stirrup"
    bl_parent_id = "VIEW3D_PT_stirrup"
    bl_options = {"DEFAULT_CLOSED"}
    kind = ""

    def draw(self, context):
        s = context.scene.stirrup
        mp = getattr(s, self.kind + "_map")
        col = self.layout.column()
        col.operator("stirrup.map", text="Map %s again" % self.kind if mp.roles else "Map %s" % self.kind).kind = self.kind
        if not mp.roles:
            col.label(text="Not mapped yet: Ride or Map runs stirrup character map")
            return
        if mp.report:
            _lines(col, context, mp.report)
        col.template_list("STIRRUP_UL_roles", "roles_" + self.kind, mp, "roles", mp, "roles_index", rows=4)
        col.prop(mp, "scale_cm")
        col.prop(mp, "forward")
        col.prop(mp, "up")
        col.prop(mp, "offset_cm")
        if self.kind == "rider":
            col.prop_search(mp, "controls_text", bpy.data, "texts", text="Controls")


class VIEW3D_PT_stirrup_horse_map(_MappingPanel, bpy.types.Panel):
    bl_label = "Horse mapping"
    kind = "horse"


class VIEW3D_PT_stirrup_rider_map(_MappingPanel, bpy.types.Panel):
    bl_label = "Rider mapping"
    kind = "rider"


classes = [STIRRUP_OT_map, STIRRUP_UL_roles, STIRRUP_UL_findings, VIEW3D_PT_stirrup, VIEW3D_PT_stirrup_horse_map,
           VIEW3D_PT_stirrup_rider_map]

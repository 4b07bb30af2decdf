# Finding and running the stirrup program. Its errors are one line on stderr (docs/install.md, "Input
# limits"), which is what the add-on reports.
import os
import shutil
import subprocess

import bpy

ADDON = __package__


class StirrupError(Exception):
    """A one-line error for a Blender report: stirrup's own, or the add-on's naming what is wrong."""


def candidates():
    """Where the program is looked for, in order, after the preferences' path: PATH, then beside the add-on:
    P/bin/stirrup for P/share/stirrup/blender/stirrup_blender (an install), build/bin/stirrup for
    build/blender/addons/stirrup_blender (the build tree's link); the add-on's folder as Blender found it
    and, when that is a link (into Blender's own add-ons folder), where it leads."""
    found = [shutil.which("stirrup")]
    here = os.path.dirname(os.path.abspath(__file__))
    for folder in dict.fromkeys([here, os.path.dirname(os.path.realpath(__file__))]):
        found.append(os.path.normpath(os.path.join(folder, "..", "..", "..", "..", "bin", "stirrup")))
        found.append(os.path.normpath(os.path.join(folder, "..", "..", "..", "bin", "stirrup")))
    return [f for f in found if f]


def find_program(context=None):
    """The stirrup program: the add-on preferences' path when set, else PATH, else beside the add-on."""
    context = context or bpy.context
    prefs = context.preferences.addons.get(ADDON)
    path = prefs.preferences.program if prefs else ""
    if path:
        path = bpy.path.abspath(path)
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
        raise StirrupError("the stirrup program in the add-on's preferences, %s, is not an executable file" % path)
    for c in candidates():
        if os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    raise StirrupError("the stirrup program was not found on PATH or beside the add-on "
                       "(install stirrup, or set its path in the add-on's preferences)")


def last_line(text):
    lines = [l.strip() for l in text.replace("\r", "\n").splitlines() if l.strip()]
    return lines[-1] if lines else ""


def run(args, context=None, ok_codes=(0,)):
    """Runs `stirrup ARGS...` and returns its stdout; an exit status outside ok_codes raises StirrupError
    with the program's one-line error. Returns (exit code, stdout)."""
    program = find_program(context)
    try:
        p = subprocess.run([program] + [str(a) for a in args], capture_output=True, text=True)
    except OSError as e:
        raise StirrupError("could not run %s: %s" % (program, e))
    if p.returncode not in ok_codes:
        raise StirrupError(last_line(p.stderr) or "stirrup %s failed with exit status %d" % (args[0], p.returncode))
    return p.returncode, p.stdout


class StirrupPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON
    program: bpy.props.StringProperty(
        name="stirrup program", subtype="FILE_PATH", default="",
        description="The stirrup program; empty: found on PATH or beside the add-on's install")

    def draw(self, context):
        self.layout.prop(self, "program")
        try:
            self.layout.label(text="Using " + find_program(context))
        except StirrupError as e:
            self.layout.label(text=str(e), icon="ERROR")

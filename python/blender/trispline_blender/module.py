"""Finding the `trispline` Python module from inside Blender, and the add-on's preferences.

Blender ignores PYTHONPATH unless started with --python-use-system-env, so the module is looked for, in order:
  1. `import trispline` as is (installed by `cmake --install build --component python`, on Debian's sys.path);
  2. the preference Module folder (Edit ▸ Preferences ▸ Add-ons ▸ trispline);
  3. the folder named in module_path.txt beside this file (written by python/blender/make_zip.py);
  4. build/python of the checkout this add-on lives in (python/blender/trispline_blender → ../../../build/python),
     which is what a symlink into Blender's scripts/addons gives.
"""

import importlib
import os
import sys

import bpy

ADDON = __package__


def _candidates(context):
    here = os.path.dirname(os.path.realpath(__file__))
    prefs = context.preferences.addons.get(ADDON) if context else None
    if prefs and prefs.preferences.module_folder:
        yield bpy.path.abspath(prefs.preferences.module_folder)
    listed = os.path.join(here, "module_path.txt")
    if os.path.isfile(listed):
        with open(listed, encoding="utf-8") as f:
            for line in f:
                if line.strip():
                    yield line.strip()
    yield os.path.normpath(os.path.join(here, "..", "..", "..", "build", "python"))


def import_trispline(context=None):
    """The trispline module, or raise ImportError saying where it was looked for and how to fix it."""
    try:
        return importlib.import_module("trispline")
    except ImportError:
        pass
    tried = []
    for folder in _candidates(context or bpy.context):
        tried.append(folder)
        if not os.path.isfile(os.path.join(folder, "trispline", "__init__.py")):
            continue
        if folder not in sys.path:
            sys.path.insert(0, folder)
        sys.modules.pop("trispline", None)
        try:
            return importlib.import_module("trispline")
        except ImportError as e:  # found but not loadable (another Python, missing NumPy, ...)
            raise ImportError(f"trispline in {folder} cannot be imported: {e}") from e
    raise ImportError(
        "the trispline Python module was not found (looked in: "
        + ", ".join(tried)
        + "). Build it (cmake --build build --target _trispline) and set Edit ▸ Preferences ▸ Add-ons ▸ trispline ▸ "
        "Module folder to the checkout's build/python"
    )


def module_or_report(operator, context):
    """The module, or None after reporting the error on `operator` (the operator then returns {'CANCELLED'})."""
    try:
        return import_trispline(context)
    except ImportError as e:
        operator.report({"ERROR"}, str(e))
        return None


class TrisplinePreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON

    module_folder: bpy.props.StringProperty(
        name="Module folder",
        description="Folder holding the trispline Python package (a checkout's build/python); empty: found "
        "automatically",
        subtype="DIR_PATH",
        default="",
    )

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "module_folder")
        try:
            mod = import_trispline(context)
            layout.label(text="trispline module: " + mod.__file__, icon="CHECKMARK")
        except ImportError as e:
            layout.label(text=str(e)[:200], icon="ERROR")

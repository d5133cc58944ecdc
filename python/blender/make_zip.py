#!/usr/bin/python3
"""Zip the trispline Blender add-on for Edit ▸ Preferences ▸ Add-ons ▸ Install (docs/python.md, "Blender add-on").

    python3 python/blender/make_zip.py [--out trispline_blender.zip] [--module-dir build/python]

The zip holds python/blender/trispline_blender/ and, unless --module-dir is "", a module_path.txt naming the folder
holding the `trispline` Python package (default: this checkout's build/python), where the installed add-on looks
for the module when `import trispline` alone fails (module.py).
"""

import argparse
import os
import sys
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
ADDON = os.path.join(HERE, "trispline_blender")


def make_zip(out, module_dir):
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        for name in sorted(os.listdir(ADDON)):
            if name.endswith(".py"):
                z.write(os.path.join(ADDON, name), f"trispline_blender/{name}")
        if module_dir:
            z.writestr("trispline_blender/module_path.txt", os.path.abspath(module_dir) + "\n")
    return out


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="trispline_blender.zip")
    ap.add_argument("--module-dir", default=os.path.normpath(os.path.join(HERE, "..", "..", "build", "python")))
    a = ap.parse_args(argv)
    if a.module_dir and not os.path.isfile(os.path.join(a.module_dir, "trispline", "__init__.py")):
        print(f"warning: {a.module_dir} holds no trispline package (build it: cmake --build build --target "
              "_trispline)", file=sys.stderr)
    print(make_zip(a.out, a.module_dir))


if __name__ == "__main__":
    main(sys.argv[1:])

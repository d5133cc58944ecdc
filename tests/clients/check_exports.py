#!/usr/bin/env python3
"""Real clients on trispline's exports (ctest label `clients`).

    check_exports.py --trispline BIN --log LOG --out DIR --client validator|blender
                     [--min-materials N] [--min-images N] [--node-path P] [--blender B]

Replays LOG with the real CLI (`trispline replay LOG --out DIR --no-render`), which writes DIR/scene.glb and, for each
`anim.record` line, an animation.glb. Every GLB found under DIR is then read twice:
  * here, from its JSON and binary chunks: the mesh nodes, the vertices and triangles Blender's importer makes of them
    (per primitive the vertices its indices use; triangles with three distinct corners, each once), the materials the
    meshes use and the images those materials' textures use, with every image's bytes present;
  * by the client: `validator` runs the Khronos glTF validator (npm gltf-validator, validate_gltf.js) and demands
    0 errors; `blender` imports the file with Blender's glTF importer (blender_import.py) and demands the same
    objects (names, vertex and triangle counts, material counts, shape keys for morph targets), the same materials
    and every image decoded (non-zero size).
--min-materials / --min-images: what scene.glb must hold at least (a textured scene's export that dropped its
materials fails here). A missing tool is a failure, never a skip.
"""
import argparse
import glob
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
FAILURES = []


def fail(msg):
    FAILURES.append(msg)
    print("FAIL: " + msg)


def read_glb(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF" or version != 2 or length != len(data):
        raise ValueError(f"{path}: not a glTF 2.0 binary (magic {magic!r}, version {version}, length {length})")
    off, doc, binary = 12, None, b""
    while off < len(data):
        clen, ctype = struct.unpack_from("<II", data, off)
        chunk = data[off + 8:off + 8 + clen]
        if ctype == 0x4E4F534A:
            doc = json.loads(chunk.decode("utf-8"))
        elif ctype == 0x004E4942:
            binary = chunk
        off += 8 + clen
    return doc, binary


COMPONENTS = {5121: ("B", 1), 5123: ("H", 2), 5125: ("I", 4)}


def read_indices(doc, binary, accessor_index):
    acc = doc["accessors"][accessor_index]
    fmt, size = COMPONENTS[acc["componentType"]]
    view = doc["bufferViews"][acc["bufferView"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    return list(struct.unpack_from("<%d%s" % (acc["count"], fmt), binary, start))


def expected_of(doc, binary):
    """What Blender's importer makes of the file: {node name: {vertices, triangles, materials, shape_keys}}."""
    objects = {}
    for node in doc.get("nodes", []):
        if "mesh" not in node:
            continue
        mesh = doc["meshes"][node["mesh"]]
        name = node.get("name") or mesh.get("name") or "Mesh"
        vertices = triangles = 0
        materials = []
        targets = 0
        for prim in mesh["primitives"]:
            if prim.get("mode", 4) != 4:
                continue
            count = doc["accessors"][prim["attributes"]["POSITION"]]["count"]
            idx = read_indices(doc, binary, prim["indices"]) if "indices" in prim else list(range(count))
            vertices += len(set(idx))
            seen = set()
            for k in range(0, len(idx) - 2, 3):
                t = idx[k:k + 3]
                if len(set(t)) < 3:
                    continue
                key = frozenset(t)  # Blender's validation removes faces with the same vertices
                if key in seen:
                    continue
                seen.add(key)
                triangles += 1
            if "material" in prim:
                m = doc["materials"][prim["material"]].get("name", "")
                if m not in materials:
                    materials.append(m)
            targets = max(targets, len(prim.get("targets", [])))
        objects[name] = {"vertices": vertices, "triangles": triangles, "materials": materials,
                         "shape_keys": targets + 1 if targets else 0}
    used_materials = set()
    for mesh in doc.get("meshes", []):
        for prim in mesh["primitives"]:
            if "material" in prim:
                used_materials.add(prim["material"])
    used_images = set()
    for mi in used_materials:
        mat = doc["materials"][mi]
        refs = [mat.get("pbrMetallicRoughness", {}).get("baseColorTexture"),
                mat.get("pbrMetallicRoughness", {}).get("metallicRoughnessTexture"),
                mat.get("normalTexture"), mat.get("occlusionTexture"), mat.get("emissiveTexture")]
        for r in refs:
            if r is not None:
                used_images.add(doc["textures"][r["index"]]["source"])
    return objects, used_materials, used_images


def check_images_present(path, doc, binary, used_images):
    for i in used_images:
        im = doc["images"][i]
        if "bufferView" in im:
            view = doc["bufferViews"][im["bufferView"]]
            if view["byteLength"] == 0:
                fail(f"{path}: image {i} has no bytes")
        elif "uri" not in im:
            fail(f"{path}: image {i} has neither bufferView nor uri")


def run_validator(path, node_path):
    env = dict(os.environ, NODE_PATH=node_path)
    node = shutil.which("node")
    if not node:
        fail("node is not installed (scripts/test_tools.sh installs the test clients)")
        return
    if not os.path.isdir(os.path.join(node_path, "gltf-validator")):
        fail(f"gltf-validator is not installed under {node_path} (scripts/test_tools.sh installs it)")
        return
    p = subprocess.run([node, os.path.join(HERE, "validate_gltf.js"), path], capture_output=True, text=True, env=env)
    if p.returncode == 2 or not p.stdout.strip():
        fail(f"{path}: the validator did not run: {p.stderr.strip()}")
        return
    report = json.loads(p.stdout)
    issues = report["issues"]
    print(f"validator {report['validatorVersion']}: {path}: {issues['numErrors']} errors, "
          f"{issues['numWarnings']} warnings, {issues['numInfos']} infos")
    for m in issues["messages"]:
        if m["severity"] == 0:
            print(f"  error {m['code']} {m.get('pointer', '')}: {m['message']}")
    if issues["numErrors"] != 0:
        fail(f"{path}: {issues['numErrors']} validator errors")


def run_blender(path, blender, expected, used_materials, used_images):
    exe = shutil.which(blender)
    if not exe:
        fail(f"{blender} is not installed (scripts/test_tools.sh installs the test clients)")
        return
    # Blender embeds the system Python and finds its modules (numpy) through the python3 on PATH: a pyenv or virtualenv
    # python3 ahead of /usr/bin would hide them.
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join(d for d in env.get("PATH", "").split(os.pathsep) if ".pyenv" not in d and
                                  "VIRTUAL_ENV" not in d)
    for k in ("PYTHONHOME", "PYTHONPATH", "VIRTUAL_ENV", "PYENV_VERSION"):
        env.pop(k, None)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "blender.json")
        p = subprocess.run([exe, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                            os.path.join(HERE, "blender_import.py"), "--", path, out],
                           capture_output=True, text=True, env=env)
        if p.returncode != 0 or not os.path.exists(out):
            fail(f"{path}: Blender's import failed (exit {p.returncode}): {p.stdout[-2000:]} {p.stderr[-2000:]}")
            return
        with open(out) as f:
            got = json.load(f)
    objects = {o["name"]: o for o in got["objects"]}
    print(f"blender: {path}: {len(objects)} mesh objects, {len(got['materials'])} materials, "
          f"{len(got['images'])} images")
    if len(objects) != len(expected):
        fail(f"{path}: Blender made {len(objects)} mesh objects, the file has {len(expected)} mesh nodes")
    for name, e in expected.items():
        o = objects.get(name[:63])  # Blender's names hold 63 bytes
        if o is None:
            fail(f"{path}: no Blender object named '{name}' (got {sorted(objects)[:10]})")
            continue
        for key in ("vertices", "triangles", "shape_keys"):
            if o[key] != e[key]:
                fail(f"{path}: '{name}': Blender has {o[key]} {key}, the file {e[key]}")
        if len(o["materials"]) != len(e["materials"]):
            fail(f"{path}: '{name}': Blender has materials {o['materials']}, the file {e['materials']}")
    if len(got["materials"]) != len(used_materials):
        fail(f"{path}: Blender made {len(got['materials'])} materials, the meshes use {len(used_materials)}")
    if len(got["images"]) != len(used_images):
        fail(f"{path}: Blender loaded {len(got['images'])} images, the materials use {len(used_images)}")
    for name, size in got["images"].items():
        if size[0] <= 0 or size[1] <= 0:
            fail(f"{path}: Blender could not decode image '{name}' (size {size})")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--trispline", required=True)
    ap.add_argument("--log", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--client", choices=["validator", "blender"], required=True)
    ap.add_argument("--min-materials", type=int, default=0)
    ap.add_argument("--min-images", type=int, default=0)
    ap.add_argument("--node-path", default="")
    ap.add_argument("--blender", default="blender")
    a = ap.parse_args()

    shutil.rmtree(a.out, ignore_errors=True)
    p = subprocess.run([a.trispline, "replay", a.log, "--out", a.out, "--no-render"], capture_output=True, text=True)
    print(p.stdout[-3000:], p.stderr[-3000:])
    if p.returncode != 0:
        fail(f"replay of {a.log} exited {p.returncode}")
        return 1
    glbs = sorted(glob.glob(os.path.join(a.out, "**", "*.glb"), recursive=True))
    if not any(os.path.basename(g) == "scene.glb" for g in glbs):
        fail(f"replay wrote no scene.glb into {a.out}")
    for path in glbs:
        doc, binary = read_glb(path)
        expected, used_materials, used_images = expected_of(doc, binary)
        print(f"{path}: {len(expected)} mesh nodes, {len(used_materials)} materials used, "
              f"{len(used_images)} images used")
        if os.path.basename(path) == "scene.glb" or os.path.basename(path) == "animation.glb":
            if len(used_materials) < a.min_materials:
                fail(f"{path}: {len(used_materials)} materials, the scene has at least {a.min_materials}")
            if len(used_images) < a.min_images:
                fail(f"{path}: {len(used_images)} images, the scene's materials use at least {a.min_images}")
        check_images_present(path, doc, binary, used_images)
        if a.client == "validator":
            run_validator(path, a.node_path)
        else:
            run_blender(path, a.blender, expected, used_materials, used_images)
    if FAILURES:
        print(f"{len(FAILURES)} failures")
        return 1
    print(f"ok: {len(glbs)} files")
    return 0


if __name__ == "__main__":
    sys.exit(main())

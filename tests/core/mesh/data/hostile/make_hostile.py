#!/usr/bin/env python3
"""Writes the hostile glTF/GLB fixtures of this folder (run from anywhere; files land next to this script).

Each file is small and breaks one rule of core/mesh/gltf_read.h; tests/core/mesh/test_gltf_hostile.cpp loads every
one and asserts the error substring listed in its kFixtures table. The files also seed a fuzzer.
"""
import base64
import copy
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def data_uri(b):
    return "data:application/octet-stream;base64," + base64.b64encode(b).decode()


# One triangle: POSITION (3 float VEC3, bytes 0..35), uint16 indices {0, 1, 2} (36..41), padded to 44 bytes.
TRI_BIN = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
TRI = {
    "asset": {"version": "2.0"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": 44}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
    ],
}


def tri(bin_=TRI_BIN):
    j = copy.deepcopy(TRI)
    j["buffers"][0]["byteLength"] = len(bin_)
    return j


def glb(j, bin_):
    js = json.dumps(j, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    bin_ = bin_ + b"\0" * (-len(bin_) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js
    if bin_:
        body += struct.pack("<II", len(bin_), 0x004E4942) + bin_
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def write_glb(name, j, bin_):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(glb(j, bin_))


def write_gltf(name, j, bin_=None):
    j = copy.deepcopy(j)
    if bin_ is not None:
        j["buffers"][0]["uri"] = data_uri(bin_)
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(j, f, separators=(",", ":"))


def clip_base(bin_extra=b""):
    """A triangle with one morph target and a LINEAR weights animation (2 keys); accessors 2.. are animation data."""
    target = struct.pack("<9f", 0, 0, 1, 0, 0, 1, 0, 0, 1)
    times = struct.pack("<2f", 0, 1)
    weights = struct.pack("<2f", 0, 1)
    b = TRI_BIN + target + times + weights + bin_extra
    j = tri(b)
    j["bufferViews"] += [
        {"buffer": 0, "byteOffset": 44, "byteLength": 36},
        {"buffer": 0, "byteOffset": 80, "byteLength": 8},
        {"buffer": 0, "byteOffset": 88, "byteLength": 8},
    ]
    j["accessors"] += [
        {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"},
        {"bufferView": 3, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
        {"bufferView": 4, "componentType": 5126, "count": 2, "type": "SCALAR"},
    ]
    j["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": 2}]
    j["meshes"][0]["weights"] = [0]
    j["animations"] = [{"name": "morph", "samplers": [{"input": 3, "output": 4, "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}]
    return j, b


def main():
    # A 3e8-element accessor over a 36-byte view (the probe's 128-byte GLB that reached 7 GB).
    j = tri()
    j["accessors"][0]["count"] = 300_000_000
    write_glb("accessor_huge_count.glb", j, TRI_BIN)

    # byteStride 16 × (2^60) wraps to 0 in 64-bit arithmetic: the old check passed and 3·(2^60 + 1) doubles followed.
    j = tri()
    j["bufferViews"][0]["byteStride"] = 16
    j["accessors"][0]["count"] = 2**60 + 1
    write_gltf("accessor_stride_overflow.gltf", j, TRI_BIN)

    # No buffer view (all zeros) and 3e8 elements: only the vertex budget stands in the way.
    j = tri()
    del j["accessors"][0]["bufferView"]
    j["accessors"][0]["count"] = 300_000_000
    del j["meshes"][0]["primitives"][0]["indices"]
    write_gltf("accessor_no_view_huge_count.gltf", j, TRI_BIN)

    # A sparse part claiming 2^31 − 1 substitutions for a 3-element accessor.
    j = tri()
    j["accessors"][0]["sparse"] = {"count": 2**31 - 1, "indices": {"bufferView": 1, "componentType": 5123},
                                   "values": {"bufferView": 0}}
    write_gltf("sparse_huge_count.gltf", j, TRI_BIN)

    # 4096 buffers all copying one GLB BIN chunk: 4096 × 64 KiB = 256 MiB in tinygltf before any accessor is read
    # (a 1 MiB chunk would make it 4 GiB).
    big = TRI_BIN + bytes(1 << 16)
    j = tri(big)
    j["buffers"] = [{"byteLength": len(big)} for _ in range(4096)]
    write_glb("glb_buffer_copies.glb", j, big)

    # byteLengths adding up to 6 GB (the files are never looked at).
    j = tri()
    j["buffers"] = [{"byteLength": 44, "uri": data_uri(TRI_BIN)},
                    {"byteLength": 3_000_000_000, "uri": "a.bin"}, {"byteLength": 3_000_000_000, "uri": "b.bin"}]
    write_gltf("buffers_over_budget.gltf", j)

    # External buffer URIs that leave the folder.
    for name, uri in [("uri_escape.gltf", "../../../../../../../../../../etc/passwd"),
                      ("uri_percent_escape.gltf", "%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/etc/passwd"),
                      ("uri_absolute.gltf", "/etc/passwd"),
                      ("uri_scheme.gltf", "file:///etc/passwd")]:
        j = tri()
        j["buffers"][0]["uri"] = uri
        write_gltf(name, j)

    # Node graphs that are not forests.
    j = tri()
    j["nodes"] = [{"mesh": 0, "children": [1]}, {"children": [0]}]
    write_gltf("node_cycle.gltf", j, TRI_BIN)
    j = tri()
    j["nodes"] = [{"mesh": 0, "children": [0]}]
    write_gltf("node_self_child.gltf", j, TRI_BIN)
    j = tri()  # diamonds: node i → i+1, i+2; a depth-first walk would visit Fibonacci(60) ≈ 1.5e12 paths
    j["nodes"] = [{"mesh": 0, "children": [c for c in (i + 1, i + 2) if c < 60]} for i in range(60)]
    write_gltf("node_dag.gltf", j, TRI_BIN)

    j = tri()
    j["nodes"][0]["mesh"] = 5
    write_gltf("mesh_index_out_of_range.gltf", j, TRI_BIN)

    b = TRI_BIN[:36] + struct.pack("<3H", 0, 1, 7) + b"\0\0"
    write_glb("indices_out_of_range.glb", tri(b), b)

    j = tri()
    j["bufferViews"][1]["byteLength"] = 8
    j["accessors"][1]["count"] = 4
    write_glb("indices_not_multiple_of_3.glb", j, TRI_BIN)

    b = struct.pack("<9f", 0, 0, 0, 1, float("nan"), 0, 0, 1, 0) + TRI_BIN[36:]
    write_glb("position_nan.glb", tri(b), b)

    b = struct.pack("<9f", 0, 0, 0, 1e30, 0, 0, 0, 1, 0) + TRI_BIN[36:]
    j = tri(b)
    j["nodes"][0]["scale"] = [1e300, 1, 1]
    write_glb("node_transform_overflow.glb", j, b)

    # NORMAL with 2 elements for 3 positions.
    b = TRI_BIN + struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    j = tri(b)
    j["bufferViews"].append({"buffer": 0, "byteOffset": 44, "byteLength": 24})
    j["accessors"].append({"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3"})
    j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2
    write_glb("normal_count_mismatch.glb", j, b)

    # 100 nested arrays in extras (tinygltf converts extras recursively).
    j = tri()
    text = json.dumps(j, separators=(",", ":"))
    deep = "[" * 100 + "]" * 100
    text = text[:-1] + ',"extras":' + deep + "}"
    j2 = json.loads(text)
    j2["buffers"][0]["uri"] = data_uri(TRI_BIN)
    with open(os.path.join(HERE, "json_deep.gltf"), "w") as f:
        f.write(json.dumps(j2, separators=(",", ":")))

    # Clips (MeshClip::load); the mesh itself is valid.
    j, b = clip_base()
    write_gltf("clip_valid.gltf", j, b)

    j, b = clip_base()
    j["accessors"][4]["count"] = 1  # 1 weight for 2 keys
    j["bufferViews"][4]["byteLength"] = 4
    write_gltf("clip_sampler_output_mismatch.gltf", j, b)

    j, b = clip_base()
    j["accessors"][3] = {"componentType": 5126, "count": 300_000_000, "type": "SCALAR"}  # no view: zeros
    j["accessors"][4] = {"componentType": 5126, "count": 300_000_000, "type": "SCALAR"}
    write_gltf("clip_sampler_huge_input.gltf", j, b)

    j, b = clip_base()
    j["accessors"][2]["count"] = 2
    write_gltf("clip_morph_count_mismatch.gltf", j, b)

    # 2000 morph targets on 300,000 vertices: 3.6e9 delta components (~29 GB as doubles).
    j, b = clip_base()
    n = 300_000
    j["accessors"][0] = {"componentType": 5126, "count": n, "type": "VEC3"}  # zeros
    del j["meshes"][0]["primitives"][0]["indices"]
    j["accessors"][2] = {"componentType": 5126, "count": n, "type": "VEC3"}
    j["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": 2}] * 2000
    j["meshes"][0]["weights"] = [0] * 2000
    j["animations"][0]["samplers"][0]["output"] = 4
    j["accessors"][4] = {"componentType": 5126, "count": 4000, "type": "SCALAR"}
    write_gltf("clip_morph_target_budget.gltf", j, b)

    # JOINTS_0 / WEIGHTS_0 with 2 elements for 3 vertices, animated through a joint's rotation.
    j, b = clip_base(struct.pack("<8H", 0, 0, 0, 0, 0, 0, 0, 0) + struct.pack("<8f", 1, 0, 0, 0, 1, 0, 0, 0)
                     + struct.pack("<8f", 0, 0, 0, 1, 0, 0, 0, 1))
    j["bufferViews"] += [{"buffer": 0, "byteOffset": 96, "byteLength": 16},
                         {"buffer": 0, "byteOffset": 112, "byteLength": 32},
                         {"buffer": 0, "byteOffset": 144, "byteLength": 32}]
    j["accessors"] += [{"bufferView": 5, "componentType": 5123, "count": 2, "type": "VEC4"},
                       {"bufferView": 6, "componentType": 5126, "count": 2, "type": "VEC4"},
                       {"bufferView": 7, "componentType": 5126, "count": 2, "type": "VEC4"}]
    prim = j["meshes"][0]["primitives"][0]
    prim["attributes"]["JOINTS_0"] = 5
    prim["attributes"]["WEIGHTS_0"] = 6
    del prim["targets"]
    del j["meshes"][0]["weights"]
    j["nodes"] = [{"mesh": 0, "skin": 0}, {}]
    j["scenes"] = [{"nodes": [0, 1]}]
    j["skins"] = [{"joints": [1]}]
    j["animations"] = [{"name": "turn", "samplers": [{"input": 3, "output": 7}],
                        "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}}]}]
    write_gltf("clip_joints_count_mismatch.gltf", j, b)


if __name__ == "__main__":
    main()

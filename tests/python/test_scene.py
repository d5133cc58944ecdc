"""trispline.Scene: commands as log lines, undo/redo, zero-copy meshes, set_mesh, save/open, replay."""
import gc
import json
import os

import numpy as np
import pytest
import trispline


def test_run_returns_the_report_entry(scene):
    entry = scene.run('{"cmd": "scene.primitive", "kind": "sphere", "name": "ball"}')  # a JSON line works too
    assert {"line", "cmd", "ok", "ms", "stats", "command"} <= set(entry)
    assert entry["cmd"] == "scene.primitive" and entry["ok"] is True and entry["line"] == 2
    assert entry["stats"]["vertices"] == len(scene.vertices("ball"))
    assert entry["command"]["kind"] == "sphere" and "translate" in entry["command"]  # defaults filled in
    assert scene.objects == ["pot", "ball"]


def test_bad_command_raises_command_error_with_field(scene):
    with pytest.raises(trispline.CommandError) as e:
        scene.run({"cmd": "scene.primitive", "kind": "teapotx", "name": "x"})
    assert e.value.field == "kind" and "teapotx" in e.value.message
    with pytest.raises(trispline.CommandError) as e:
        scene.run({"cmd": "no.such"})
    assert e.value.field == "cmd"
    with pytest.raises(trispline.CommandError) as e:
        scene.run({"cmd": "lattice.ring", "object": "nobody", "center": [0, 0, 0], "radius": 1})
    assert e.value.field == "object"
    assert issubclass(trispline.CommandError, Exception)
    assert scene.objects == ["pot"]  # unchanged


def test_numpy_values_in_a_command(scene):
    scene.run({"cmd": "object.transform", "object": "pot", "translate": np.array([1.0, 2.0, 3.0])})
    assert np.allclose(scene.vertices("pot").mean(axis=0) - scene.vertices("pot", "rest").mean(axis=0), [1, 2, 3])
    with pytest.raises(ValueError):
        scene.run({"cmd": "object.transform", "object": "pot", "translate": [float("nan"), 0, 0]})


def test_undo_redo_change_objects(scene):
    scene.run({"cmd": "scene.primitive", "kind": "box", "name": "box"})
    assert scene.undo() is True and scene.objects == ["pot"]
    assert scene.redo() is True and scene.objects == ["pot", "box"]
    assert scene.redo() is False
    assert scene.undo() and scene.undo() and scene.objects == [] and scene.undo() is False


def test_vertices_are_zero_copy_read_only_views(scene):
    V, F = scene.vertices("pot"), scene.faces("pot")
    assert V.dtype == np.float64 and V.shape[1] == 3 and F.dtype == np.int32 and F.shape[1] == 3
    assert np.shares_memory(V, scene.vertices("pot"))
    assert not V.flags.writeable and not F.flags.writeable
    with pytest.raises(ValueError):
        V[0, 0] = 1.0
    assert F.min() >= 0 and F.max() < len(V)
    assert scene.normals("pot").shape == V.shape
    assert scene.uvs("pot") is None or scene.uvs("pot").shape == (len(V), 2)
    copy = V.copy()
    del scene
    gc.collect()
    assert np.array_equal(V, copy)  # the base keeps the mesh alive


def test_unknown_object_raises_key_error(scene):
    for get in (scene.vertices, scene.faces, scene.normals, scene.uvs, scene.lattice):
        with pytest.raises(KeyError):
            get("nobody")


def test_set_mesh_round_trip_and_undo(scene):
    V0 = scene.vertices("pot").copy()
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.int32)
    entry = scene.set_mesh("pot", V, F)
    assert entry["cmd"] == "mesh.set" and entry["stats"]["vertices_after"] == 4
    assert np.array_equal(scene.vertices("pot"), V) and np.array_equal(scene.faces("pot"), F)
    scene.undo()
    assert np.array_equal(scene.vertices("pot"), V0)
    scene.redo()
    assert np.array_equal(scene.vertices("pot"), V)


@pytest.mark.parametrize("V, F, match", [
    (np.zeros((4, 2)), [[0, 1, 2]], r"#N×3"),
    (np.zeros((4, 3), np.complex128), [[0, 1, 2]], "dtype"),
    (np.array([[0, 0, 0], [1, 0, 0], [0, np.nan, 0], [0, 0, 1.0]]), [[0, 1, 2]], "not finite"),
    (np.eye(3), [[0, 1, 3]], "vertex index"),
    (np.eye(3), [[0, 1, -1]], "vertex index"),
    (np.eye(3), [[0.0, 1.0, 2.0]], "int32"),
    (np.eye(3), [[0, 1]], r"#N×3"),
])
def test_set_mesh_refuses_bad_arrays_leaving_the_scene_untouched(scene, V, F, match):
    before = scene.vertices("pot").copy()
    with pytest.raises(ValueError, match=match):
        scene.set_mesh("pot", V, F)
    assert np.array_equal(scene.vertices("pot"), before)
    assert scene.undo() and scene.objects == []  # nothing was pushed: the undo takes back scene.primitive
    with pytest.raises(KeyError):
        trispline.Scene().set_mesh("pot", np.eye(3), [[0, 1, 2]])


def test_save_open_round_trip_is_bit_exact(scene, tmp_path):
    scene.run({"cmd": "scene.primitive", "kind": "sphere", "name": "ball", "translate": [0, 1.5, 0]})
    scene.run({"cmd": "lattice.ring", "object": "ball", "center": [0, 0, 0], "radius": 1.4})
    rng = np.random.default_rng(3)
    V = scene.vertices("pot", "rest") + rng.normal(scale=1e-3, size=scene.vertices("pot").shape)
    scene.set_mesh("pot", V, scene.faces("pot"))
    log = tmp_path / "scene.jsonl"
    scene.save(str(log))
    lines = [json.loads(line) for line in log.read_text().splitlines()]
    assert [line["cmd"] for line in lines] == ["scene.primitive", "scene.primitive", "lattice.ring", "mesh.set"]
    again = trispline.Scene.open(str(log))
    assert again.objects == scene.objects
    for name in scene.objects:
        assert np.array_equal(again.vertices(name), scene.vertices(name))  # bit for bit
        assert np.array_equal(again.faces(name), scene.faces(name))


def test_open_reports_the_failing_line(tmp_path):
    log = tmp_path / "bad.jsonl"
    log.write_text('{"cmd":"scene.primitive","kind":"box","name":"b"}\n{"cmd":"scene.primitive","kind":"x"}\n')
    with pytest.raises(trispline.CommandError) as e:
        trispline.Scene.open(str(log))
    assert e.value.field == "kind" and ":2:" in e.value.message


def test_replay_writes_report_json(source_dir, tmp_path):
    log = tmp_path / "ring.jsonl"
    log.write_text('{"cmd":"scene.primitive","kind":"sphere","name":"ball","translate":[0,1.5,0]}\n'
                   '{"cmd":"lattice.ring","object":"ball","center":[0,0,0],"radius":1.4}\n')
    report = trispline.replay(str(log), str(tmp_path / "out"))
    on_disk = json.loads((tmp_path / "out" / "report.json").read_text())
    assert report["ok"] and on_disk["ok"]
    assert [c["cmd"] for c in on_disk["commands"]] == ["scene.primitive", "lattice.ring"]
    assert all({"line", "cmd", "ok", "ms"} <= set(c) for c in on_disk["commands"])
    assert on_disk["objects"][0]["name"] == "ball" and on_disk["objects"][0]["deformed"]
    assert (tmp_path / "out" / "scene.glb").stat().st_size > 0
    log.write_text('{"cmd":"scene.primitive","kind":"nope"}\n')
    bad = trispline.replay(str(log), str(tmp_path / "out2"))
    assert not bad["ok"] and bad["failed_line"] == 1 and "kind" in bad["error"]


def test_relative_paths_resolve_against_the_working_directory(source_dir, monkeypatch):
    monkeypatch.chdir(os.path.join(source_dir, "assets"))
    s = trispline.Scene()
    entry = s.run({"cmd": "scene.load", "path": "data/bunny.obj", "name": "bunny"})
    assert os.path.isabs(entry["command"]["path"]) and s.vertices("bunny").shape[0] == entry["stats"]["vertices"]

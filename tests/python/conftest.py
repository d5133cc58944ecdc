"""pytest of the trispline module: PYTHONPATH must hold build/python (ctest `python` sets it)."""
import os

import pytest

SOURCE_DIR = os.environ.get("TRISPLINE_SOURCE_DIR",
                            os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))


@pytest.fixture
def source_dir():
    return SOURCE_DIR


@pytest.fixture
def scene():
    import trispline
    s = trispline.Scene()
    s.run({"cmd": "scene.primitive", "kind": "teapot", "name": "pot"})
    return s

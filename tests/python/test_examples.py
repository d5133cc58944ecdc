"""Every script of python/examples runs (in a temporary folder) and exits 0."""
import os
import subprocess
import sys

import pytest

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "python", "examples")


@pytest.mark.parametrize("script", sorted(f for f in os.listdir(EXAMPLES) if f.endswith(".py")))
def test_example_runs(script, tmp_path):
    import trispline
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(trispline.__file__))))
    r = subprocess.run([sys.executable, os.path.join(EXAMPLES, script), str(tmp_path)], cwd=tmp_path, env=env,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr


def test_help_reads_well():
    import pydoc

    import trispline
    text = pydoc.render_doc(trispline, renderer=pydoc.plaintext)
    for name in ("Scene", "Lattice", "ffd_evaluate", "certify", "silhouettes", "replay", "CommandError", "#V×3"):
        assert name in text

"""The Python examples of docs/python.md run as written (from the repository's top folder), and the
package imports from a checkout as documented."""
import os
import re
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), os.pardir, os.pardir))


def blocks(path):
    text = open(os.path.join(ROOT, path)).read()
    return re.findall(r"```python\n(.*?)```", text, re.S)


def test_docs_python_examples_run(monkeypatch, capsys):
    pytest.importorskip("osgeo.gdal")
    pytest.importorskip("dask.array")
    code = blocks("docs/python.md")
    assert len(code) >= 6
    monkeypatch.chdir(ROOT)
    env = {}
    for src in code:  # one namespace, in order, as a reader runs them
        exec(compile(src, "docs/python.md", "exec"), env)
    out = capsys.readouterr().out
    assert "1.30969385311468" in out


def test_readme_python_tour_runs(monkeypatch):
    code = blocks("README.md")
    assert code
    monkeypatch.chdir(ROOT)
    env = {}
    for src in code:
        exec(compile(src, "README.md", "exec"), env)


@pytest.mark.skipif(not os.path.exists(os.path.join(ROOT, "build", "libfracterra.so")), reason="no build/")
def test_import_from_a_checkout(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "FRACTERRA_LIBRARY"}
    env["PYTHONPATH"] = os.path.join(ROOT, "python")
    out = subprocess.run([sys.executable, "-c", "import fracterra; print(fracterra.library_path)"], cwd=tmp_path,
                         env=env, capture_output=True, text=True, check=True).stdout.strip()
    assert out == os.path.join(ROOT, "build", "libfracterra.so")

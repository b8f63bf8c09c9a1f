"""The Python code blocks of docs/python.md run as written (in order, sharing one namespace, in a
scratch folder where examples/ is the repository's)."""
import os
import re

import matplotlib

matplotlib.use("Agg")


def test_docs_python_blocks_run(root, tmp_path, monkeypatch):
    text = (root / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 5
    (tmp_path / "examples").symlink_to(root / "examples")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    for i, block in enumerate(blocks):
        exec(compile(block, f"docs/python.md block {i}", "exec"), namespace)
    assert os.path.exists("material_sweep.png") and os.path.exists("bar.vtu")
    assert os.path.exists("out/python_stretch/summary.json") and os.path.exists("out/stretch_small/summary.json")

"""The example scripts in examples/python/ run and write their plots."""
import os
import subprocess
import sys

import pytest


@pytest.mark.parametrize("script", ["material_sweep.py", "stretch_frame_by_frame.py"])
def test_example_runs_and_writes_its_plot(script, examples, tmp_path):
    png = tmp_path / "plot.png"
    command = [sys.executable, str(examples / "python" / script), "--out", str(png)]
    if script == "stretch_frame_by_frame.py":
        command += ["--frames-dir", str(tmp_path / "frames")]
    r = subprocess.run(command, capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"), timeout=600)
    assert r.returncode == 0, r.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20000
    if script == "stretch_frame_by_frame.py":
        assert (tmp_path / "frames" / "frame_0006.vtu").exists()
        assert (tmp_path / "frames" / "summary.json").exists()

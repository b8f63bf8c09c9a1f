"""sinew.Scene, sinew.run and sinew.Simulation: scenes from files and dicts, errors as the CLI
prints them, runs to a folder, frame-by-frame stepping with boundary motions and loads changed
between frames, and results as arrays."""
import copy
import json
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import sinew


def stretch_scene(element="hex", cells=(4, 2, 2)):
    """A 2 x 1 x 1 bar: "left" pinned, "right" translated by 0.1 per frame."""
    return {
        "mesh": {"box": {"min": [0, 0, 0], "max": [2, 1, 1]}, "cells": list(cells), "element": element},
        "material": {"family": "stable_neo_hookean", "E": 100.0, "nu": 0.3},
        "boundary": [
            {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
            {"name": "right", "select": {"plane": {"point": [2, 0, 0], "normal": [1, 0, 0]}},
             "motion": {"type": "translate", "per_frame": [0.1, 0, 0]}},
        ],
        "solver": {"newton": {"convergence": "absolute", "tolerance": 1e-8}},
        "frames": 2,
    }


def test_scene_from_file_and_from_dict(examples):
    path = examples / "stretch_small.json"
    s = sinew.Scene.load(str(path))
    assert s.boundary_names == ["left", "right"] and s.frames == 4 and not s.dynamic
    assert s.data == json.loads(path.read_text())
    again = sinew.Scene.from_dict(copy.deepcopy(s.data), path=str(path))
    assert again.path == str(path) and again.boundary_names == s.boundary_names
    assert s.material().E == pytest.approx(1e5) and s.mesh().kind == "hex"


BROKEN = {
    "nu_out_of_range": lambda d: d["material"].update(nu=0.6),
    "misspelt_key": lambda d: d.update(frmaes=3),
    "missing_mesh_file": lambda d: d.update(mesh={"file": "no_such_mesh.mesh"}),
    "empty_selection": lambda d: d["boundary"][1]["select"]["plane"].update(point=[5, 0, 0]),
}


@pytest.mark.parametrize("case", sorted(BROKEN))
def test_errors_carry_the_cli_message(case, cli, tmp_path):
    data = stretch_scene()
    BROKEN[case](data)
    path = tmp_path / f"{case}.json"
    path.write_text(json.dumps(data))
    r = subprocess.run([cli, "run", str(path), "--out", str(tmp_path / "out"), "--quiet"], capture_output=True,
                       text=True)
    assert r.returncode == 2
    assert r.stderr.startswith("sinew: error: ")
    cli_message = r.stderr.strip()[len("sinew: error: "):]
    with pytest.raises(sinew.Error) as e:
        sinew.Simulation(sinew.Scene.load(str(path)))
    assert str(e.value) == cli_message
    with pytest.raises(sinew.Error) as e:  # the same scene from a dict, named by the same path
        sinew.run(sinew.Scene.from_dict(data, path=str(path)))
    assert str(e.value) == cli_message


def test_run_checkpoints_as_often_as_asked(tmp_path):
    scene = sinew.Scene.from_dict(stretch_scene())
    seen = []

    def progress(e):
        if e.frame_done:
            seen.append(json.loads((tmp_path / "checkpoint.json").read_text())["frame"])

    sinew.run(scene, out=str(tmp_path), frames=2, progress=progress, checkpoint_seconds=0)
    assert seen == [1, 2]
    with pytest.raises(sinew.Error, match="checkpoint-seconds"):
        sinew.run(scene, out=str(tmp_path / "bad"), frames=1, checkpoint_seconds=-1)


def test_run_writes_the_cli_outputs_and_returns_records(tmp_path):
    scene = sinew.Scene.from_dict(stretch_scene())
    events = []
    result = sinew.run(scene, out=str(tmp_path), frames=2, progress=events.append)
    assert result.all_converged and len(result.frames) == 2
    for name in ("frame_0000.vtu", "frame_0002.vtu", "simulation.pvd", "summary.json", "checkpoint.json"):
        assert (tmp_path / name).exists(), name
    assert json.loads((tmp_path / "checkpoint.json").read_text())["frame"] == 2  # the last frame, always
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert [f["frame"] for f in summary["frames"]] == [1, 2]
    assert summary["frames"][1] == result.frames[1].to_dict()
    assert result.positions.shape == (result.vertices, 3) and result.positions.flags.c_contiguous
    assert np.ptp(result.positions[:, 0]) == pytest.approx(2.2, rel=1e-6)
    done = [e for e in events if e.frame_done]
    assert [e.frame for e in done] == [1, 2] and done[1].record.frame == 2
    assert any(e.newton_iteration > 0 for e in events)
    m = sinew.metrics(result.frames)
    assert m["reactions"].shape == (2, 2, 3) and m["volume"].shape == (2,)
    assert m["reactions"][1, 1, 0] > m["reactions"][0, 1, 0] > 0  # pulling harder on the right
    with pytest.raises(sinew.Error, match="--frames"):
        sinew.run(scene, frames=0)


def test_stepping_reproduces_a_run():
    scene = sinew.Scene.from_dict(stretch_scene())
    result = sinew.run(scene)
    sim = sinew.Simulation(scene)
    records = [sim.step(), sim.step()]
    assert sim.frame == 2 and sim.time == 2.0
    np.testing.assert_allclose(sim.positions, result.positions, atol=1e-9)
    for a, b in zip(records, result.frames):
        assert a.newton_iterations == b.newton_iterations
        np.testing.assert_allclose(a.reactions, b.reactions, rtol=1e-6, atol=1e-9)


def test_a_stretch_test_driven_frame_by_frame():
    sim = sinew.Simulation(sinew.Scene.from_dict(stretch_scene()))
    right = sim.boundary_vertices("right")
    rest = sim.rest_positions
    forces = []
    for k in range(1, 4):
        sim.move_boundary("right", translation=[0.15 * k, 0, 0])
        record = sim.step()
        assert record.converged
        np.testing.assert_allclose(sim.positions[right], rest[right] + [0.15 * k, 0, 0], atol=1e-12)
        np.testing.assert_allclose(sim.displacements, sim.positions - rest)
        R, t = sim.boundary_transform("right")
        np.testing.assert_allclose(t, [0.15 * k, 0, 0]) and np.testing.assert_allclose(R, np.eye(3))
        # At equilibrium the supports balance each other (no loads).
        np.testing.assert_allclose(record.reactions[0], -record.reactions[1], atol=1e-6)
        forces.append(record.reactions[1, 0])
    assert 0 < forces[0] < forces[1] < forces[2]
    # A rotation of the right end about the bar's axis.
    sim.move_boundary("right", translation=[0.45, 1.0, 0], rotation=sinew.rotation([1, 0, 0], 90))
    assert sim.step().converged
    np.testing.assert_allclose(sim.positions[right, 1], 1.0 - rest[right, 2], atol=1e-12)


def test_motions_set_as_dicts_and_their_errors():
    sim = sinew.Simulation(sinew.Scene.from_dict(stretch_scene()))
    sim.set_boundary_motion("right", {"type": "translate", "per_frame": [0.05, 0, 0]})
    sim.step()
    right = sim.boundary_vertices(1)
    np.testing.assert_allclose(sim.displacements[right, 0], 0.05)
    # A displacement without an amplitude ramps to the scene's last frame (2).
    sim.set_boundary_motion("right", {"type": "displace", "displacement": [0.3, 0, 0]})
    sim.step()
    np.testing.assert_allclose(sim.displacements[right, 0], 0.3)
    with pytest.raises(sinew.Error) as e:
        sim.set_boundary_motion("right", {"type": "translate"})
    assert str(e.value) == "boundary 'right' motion: /per_frame: required field is missing"
    with pytest.raises(sinew.Error, match="no boundary condition named 'middle' \\(the scene has: left, right\\)"):
        sim.move_boundary("middle", [0, 0, 0])
    with pytest.raises(sinew.Error, match="rotation matrix"):
        sim.move_boundary("right", [0, 0, 0], rotation=2 * np.eye(3))


def test_loads_changed_between_frames_are_balanced_by_the_support():
    data = stretch_scene()
    data["boundary"] = data["boundary"][:1]
    sim = sinew.Simulation(sinew.Scene.from_dict(data))
    assert np.all(sim.external_forces == 0)
    tip = np.flatnonzero(np.isclose(sim.rest_positions[:, 0], 2.0))
    f = np.zeros_like(sim.rest_positions)
    f[tip] = [0.0, 0.0, -0.05]
    sim.external_forces = f
    np.testing.assert_array_equal(sim.external_forces, f)
    record = sim.step()
    assert record.converged
    np.testing.assert_allclose(record.reactions[0], -f.sum(axis=0), atol=1e-6)
    assert sim.displacements[tip, 2].max() < 0  # the tip went down
    with pytest.raises(ValueError, match="shape"):
        sim.external_forces = f[:3]


def test_element_J_and_stresses_match_the_material_on_tetrahedra():
    sim = sinew.Simulation(sinew.Scene.from_dict(stretch_scene("tet", (3, 2, 2))))
    sim.step()
    tets = np.asarray(sim.mesh.elements)
    X, x = sim.rest_positions[tets], sim.positions[tets]  # (elements, 4, 3)
    Dm = (X[:, 1:] - X[:, :1]).transpose(0, 2, 1)
    Ds = (x[:, 1:] - x[:, :1]).transpose(0, 2, 1)
    F = Ds @ np.linalg.inv(Dm)
    J = np.linalg.det(F)
    fields = sim.element_fields()
    np.testing.assert_allclose(fields["J"], J, rtol=1e-10)
    s = sim.stresses()
    P = sim.material.pk1(F)
    np.testing.assert_allclose(s["pk1"], P, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(s["cauchy"], P @ F.transpose(0, 2, 1) / J[:, None, None], rtol=1e-9, atol=1e-9)
    assert sinew.von_mises(s["cauchy"]).shape == (len(tets),)
    assert fields["energy"].sum() == pytest.approx(
        np.sum(sim.material.psi(F) * sim.mesh.rest_volumes()), rel=1e-10)


def test_progress_callbacks_and_their_exceptions():
    sim = sinew.Simulation(sinew.Scene.from_dict(stretch_scene()))
    seen = []
    sim.step(progress=lambda iteration, residual: seen.append((iteration, residual)))
    assert seen and max(i for i, _ in seen) >= 1 and all(r >= 0 for _, r in seen)

    def fail(iteration, residual):
        raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        sim.step(progress=fail)


def test_dynamics_expose_time_and_velocities():
    data = stretch_scene()
    data["boundary"] = data["boundary"][:1]
    data["loads"] = {"gravity": [0, 0, -9.81]}
    data["dynamics"] = {"time_step": 0.01}
    sim = sinew.Simulation(sinew.Scene.from_dict(data))
    assert sim.dynamic and sim.velocities.shape == sim.positions.shape
    sim.step()
    assert sim.time == pytest.approx(0.01) and sim.velocities[:, 2].min() < 0


def test_long_calls_release_the_gil():
    # A run long enough to see a stalled thread: more frames until it takes 50 ms alone (the
    # solver gets faster; the test's premise should not depend on how fast).
    data = stretch_scene(cells=(12, 6, 6))
    data["boundary"][1]["motion"]["per_frame"] = [0.02, 0, 0]
    while True:
        scene = sinew.Scene.from_dict(data)
        start = time.perf_counter()
        sinew.run(scene)
        alone = time.perf_counter() - start
        if alone > 0.05 or data["frames"] >= 256:
            break
        data["frames"] *= 2
    worker = threading.Thread(target=sinew.run, args=(scene,))
    ticks = [time.perf_counter()]
    worker.start()
    while worker.is_alive():
        time.sleep(0.001)
        ticks.append(time.perf_counter())
    worker.join()
    # Were the GIL held during the run, this thread would stand still for all of it.
    assert alone > 0.05
    assert np.max(np.diff(ticks)) < 0.5 * alone


def test_ctrl_c_stops_a_run():
    data = stretch_scene(cells=(12, 6, 6))
    data["boundary"][1]["motion"]["per_frame"] = [0.02, 0, 0]
    data["frames"] = 1
    start = time.perf_counter()
    sinew.run(sinew.Scene.from_dict(data))
    one_frame = time.perf_counter() - start
    data["frames"] = 100
    timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sinew.run(sinew.Scene.from_dict(data))
    timer.join()
    assert time.perf_counter() - start < 0.2 + 20 * one_frame  # not the 100 frames


def test_warnings_and_strict():
    data = stretch_scene()
    data["boundary"] = [{"name": "all", "select": {"box": {"min": [-1, -1, -1], "max": [3, 3, 3]}}}]
    with pytest.warns(sinew.SceneWarning, match="selects every vertex"):
        sim = sinew.Simulation(sinew.Scene.from_dict(data))
    assert any("selects every vertex" in w for w in sim.warnings)
    with pytest.warns(sinew.SceneWarning):
        result = sinew.run(sinew.Scene.from_dict(data))
    assert result.warnings == sim.warnings
    for make in (lambda s: sinew.run(s, strict=True), lambda s: sinew.Simulation(s, strict=True)):
        with pytest.raises(sinew.Error, match=r"\(a warning, an error with --strict\)$"):
            make(sinew.Scene.from_dict(data))

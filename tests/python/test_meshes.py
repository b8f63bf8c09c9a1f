"""sinew.Mesh and sinew.Surface: lattices, files, voxelisation, arrays without copies."""
import numpy as np
import pytest

import sinew


def test_box_lattice_views_its_arrays_without_copies():
    m = sinew.box([0, 0, 0], [1, 2, 3], cells=[2, 3, 4])
    assert (m.kind, m.num_vertices, m.num_elements) == ("hex", 3 * 4 * 5, 24)
    v, e = m.vertices, m.elements
    assert v.shape == (60, 3) and v.dtype == np.float64 and e.shape == (24, 8) and e.dtype == np.int32
    assert not v.flags.writeable and not e.flags.writeable
    assert v.base is not None and np.shares_memory(v, m.vertices)  # both views of the mesh's own array
    np.testing.assert_allclose(v.min(axis=0), [0, 0, 0])
    np.testing.assert_allclose(v.max(axis=0), [1, 2, 3])
    np.testing.assert_array_equal(m.lattice["cells"], [2, 3, 4])
    assert m.rest_volumes().sum() == pytest.approx(6.0)
    tets = m.to_tets()
    assert tets.kind == "tet" and tets.num_elements == 6 * 24 and tets.lattice is None
    assert tets.rest_volumes().sum() == pytest.approx(6.0)
    del m
    assert v.sum() > 0  # the view keeps the mesh alive


def test_shapes_follow_the_scene_mesh_form_and_its_errors():
    s = sinew.sphere([0, 0, 0], 1.0, resolution=12)
    assert s.rest_volumes().sum() == pytest.approx(4 / 3 * np.pi, rel=0.1)
    c = sinew.cylinder([0, 0, 0], 0.5, 2.0, "x", cell_size=0.25, element="tet")
    assert c.kind == "tet" and np.ptp(c.vertices[:, 0]) == pytest.approx(2.0)
    with pytest.raises(sinew.Error) as e:
        sinew.Mesh.from_spec({"box": {"min": [0, 0, 0], "max": [1, -1, 1]}, "cells": [1, 1, 1]})
    assert str(e.value) == "mesh: /mesh/box/max: must exceed min in every coordinate"


def test_mesh_from_arrays_is_validated():
    m = sinew.box([0, 0, 0], [1, 1, 1], cells=[1, 1, 1], element="tet")
    again = sinew.Mesh(np.asarray(m.vertices), np.asarray(m.elements))
    assert again.kind == "tet" and again.rest_volumes().sum() == pytest.approx(1.0)
    bad = np.asarray(m.elements).copy()
    bad[0, [0, 1]] = bad[0, [1, 0]]  # inverted
    with pytest.raises(sinew.Error, match="invert"):
        sinew.Mesh(m.vertices, bad)
    with pytest.raises(ValueError):
        sinew.Mesh(m.vertices, bad[:, :3])


def test_files_and_boundary(examples, tmp_path):
    m = sinew.read_mesh(examples / "meshes" / "sphere27.vtu")
    b = m.boundary()
    assert b["triangles"].shape[1] == 3 and len(b["faces"]) == len(b["face_element"])
    assert set(b["vertices"]) <= set(range(m.num_vertices))
    out = tmp_path / "moved.vtu"
    moved = np.asarray(m.vertices) * 2.0
    m.write_vtu(str(out), moved, cell_fields={"index": np.arange(m.num_elements, dtype=float)})
    back = sinew.read_mesh(out)
    np.testing.assert_allclose(back.vertices, moved)
    np.testing.assert_array_equal(back.elements, m.elements)
    with pytest.raises(sinew.Error, match="no_such_file"):
        sinew.read_mesh(tmp_path / "no_such_file.mesh")


def test_surfaces_voxelise_and_tetrahedralise(examples):
    s = sinew.read_surface(examples / "meshes" / "sphere.stl")
    assert s.volume > 0 and s.faces.shape[1] == 3
    lo, hi = s.bounds
    vox = sinew.voxelize(s, resolution=8)
    assert vox.kind == "hex" and vox.lattice is not None
    # The kept cells cover the solid.
    assert vox.rest_volumes().sum() >= s.volume
    np.testing.assert_array_less(vox.vertices.min(axis=0), lo + 1e-9)
    tet = sinew.tetrahedralize(s, max_edge=np.max(hi - lo) / 4)
    assert tet.kind == "tet" and tet.rest_volumes().sum() == pytest.approx(s.volume, rel=1e-6)
    with pytest.raises(sinew.Error):
        sinew.voxelize(s)  # neither cell_size nor resolution
    # A surface from arrays: an outward tetrahedron.
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    assert sinew.Surface(v, f).volume == pytest.approx(1 / 6)
    with pytest.raises(sinew.Error):
        sinew.Surface(v, f[:, ::-1])  # inside out

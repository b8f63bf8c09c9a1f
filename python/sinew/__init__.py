"""Sinew from Python: materials, meshes and scenes (docs/python.md).

The compiled part (sinew._sinew, pybind11) holds the classes and the long-running calls, which
release the GIL; this file adds conveniences that build the same JSON forms the scene files use,
so a dict, a scene file and these helpers reach the same checks and the same error messages.
"""

import numpy as np

from ._sinew import (
    Error,
    FrameRecord,
    Material,
    Mesh,
    Progress,
    RunSummary,
    Scene,
    SceneWarning,
    Simulation,
    Surface,
    __version__,
    lambda_part_parameters,
    lame_from_young_poisson,
    materials,
    mu_part_parameters,
    normalize,
    read_mesh,
    read_surface,
    run,
    set_threads,
    tetrahedralize,
    voxelize,
    young_poisson,
)

# Errors and reprs say sinew.Error, sinew.Material, ... (where users meet them), not sinew._sinew.
for _name in ("Error", "FrameRecord", "Material", "Mesh", "Progress", "RunSummary", "Scene", "Simulation", "Surface"):
    globals()[_name].__module__ = __name__
del _name

__all__ = [
    "Error", "FrameRecord", "Material", "Mesh", "Progress", "RunSummary", "Scene", "SceneWarning", "Simulation",
    "Surface", "__version__", "box", "cylinder", "lambda_part_parameters", "lame_from_young_poisson",
    "load_scene", "material", "materials", "metrics", "mix", "mu_part_parameters", "normalize",
    "read_mesh", "read_surface", "rotation", "run", "set_threads", "sphere", "tetrahedralize",
    "von_mises", "voxelize", "young_poisson",
]


def load_scene(path):
    """Reads a scene file (the same as Scene.load)."""
    return Scene.load(path)


def material(family, *, E=None, nu=None, alpha=None, functions=None, **parameters):
    """A catalog family with parameters, optionally set from (E, nu) and given a nonlinearity
    exponent: material("neo_hookean", E=1e5, nu=0.45, alpha=2), material("ogden", mu1=2.0)."""
    spec = {"family": family}
    if parameters:
        spec["parameters"] = parameters
    if functions:
        spec["functions"] = functions
    if E is not None or nu is not None:
        spec["E"], spec["nu"] = E, nu
    if alpha is not None:
        spec["alpha"] = alpha
    return Material({k: v for k, v in spec.items() if v is not None})


def mix(lambda_family, mu_family, *, E, nu, alpha_lambda=1.0, alpha_mu=1.0, lambda_parameters=None,
        mu_parameters=None):
    """The volume part of one family and the shear part of another, each with its own exponent
    (paper 002 §6), at Young's modulus E and Poisson's ratio nu."""
    m = {"lambda_family": lambda_family, "mu_family": mu_family, "alpha_lambda": alpha_lambda,
         "alpha_mu": alpha_mu}
    if lambda_parameters:
        m["lambda_parameters"] = lambda_parameters
    if mu_parameters:
        m["mu_parameters"] = mu_parameters
    return Material({"mix": m, "E": E, "nu": nu})


def _lattice(shape, spec, cells, cell_size, resolution, element):
    mesh = {shape: spec, "element": element}
    for key, value in (("cells", cells), ("cell_size", cell_size), ("resolution", resolution)):
        if value is not None:
            mesh[key] = value
    return Mesh.from_spec(mesh)


def box(lo, hi, cells=None, *, cell_size=None, resolution=None, element="hex"):
    """A box lattice between corners lo and hi: cells (nx, ny, nz), or a cell size, or the number of
    cells along the longest side; element "hex" or "tet" (each hexahedron split into six)."""
    return _lattice("box", {"min": lo, "max": hi}, cells, cell_size, resolution, element)


def sphere(center, radius, *, cell_size=None, resolution=None, element="hex"):
    """The lattice cells whose centres lie inside a sphere."""
    return _lattice("sphere", {"center": center, "radius": radius}, None, cell_size, resolution, element)


def cylinder(center, radius, length, axis="x", *, cell_size=None, resolution=None, element="hex"):
    """The lattice cells whose centres lie inside a cylinder along axis "x", "y" or "z"."""
    spec = {"center": center, "radius": radius, "length": length, "axis": axis}
    return _lattice("cylinder", spec, None, cell_size, resolution, element)


def rotation(axis, degrees):
    """The 3x3 rotation by `degrees` about `axis` (right-handed), e.g. for Simulation.move_boundary."""
    a = np.asarray(axis, dtype=float)
    n = np.linalg.norm(a)
    if not n > 0:
        raise ValueError("axis must be non-zero")
    x, y, z = a / n
    t = np.radians(degrees)
    c, s = np.cos(t), np.sin(t)
    K = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + s * K + (1 - c) * (K @ K)


def von_mises(stress):
    """The von Mises equivalent stress of (..., 3, 3) stress tensors (e.g. Simulation.stresses()["cauchy"])."""
    s = np.asarray(stress, dtype=float)
    dev = s - np.trace(s, axis1=-2, axis2=-1)[..., None, None] * np.eye(3) / 3.0
    return np.sqrt(1.5 * np.sum(dev * dev, axis=(-2, -1)))


_METRICS = ("frame", "time", "converged", "newton_iterations", "linear_iterations", "substeps", "residual",
            "energy", "seconds", "volume", "min_J", "kinetic_energy", "potential_energy", "contacts",
            "max_penetration", "self_contacts", "self_penetration")


def metrics(frames):
    """Per-frame metrics of FrameRecords (RunSummary.frames, Simulation.frames) as a dict of arrays,
    one entry per frame; "reactions" is (frames, boundary conditions, 3)."""
    frames = list(frames)
    out = {key: np.array([getattr(f, key) for f in frames]) for key in _METRICS}
    nb = len(frames[0].reactions) if frames else 0
    out["reactions"] = np.array([f.reactions for f in frames]).reshape(len(frames), nb, 3)
    out["external_force"] = np.array([f.external_force for f in frames]).reshape(len(frames), 3)
    return out

#!/usr/bin/env python3
"""Fails if a library folder includes a folder above it in the layer order, or if folders
include each other in a cycle (docs/architecture.md draws the layers).

usage: check_layers.py REPO_ROOT
"""
import pathlib
import re
import sys

# Lowest first. A folder may include its own headers and those of folders earlier in this list.
LAYERS = [
    "core",         # types, errors, SVD
    "material",     # energy densities: psi(F), P(F), dP/dF and its projection; families/
    "mesh",         # volume meshes, lattices, surfaces, selections, voxelisation
    "element",      # quadrature, per-element kinematics (dN/dX), mass, embedding, mesh validation
    "io",           # readers and writers of files (meshes, surfaces, VTK, OBJ, PLY)
    "motion",       # prescribed rigid motion, obstacles, rig bones and their keys
    "linalg",       # block-sparse Hessian storage, linear operators
    "forms",        # energy terms (elastic, inertia, loads, contact, bone springs, corotational)
    "constraints",  # unilateral constraint rows: energy limits, contact constraints
    "assembly",     # the total energy: sum of forms with Dirichlet DOFs
    "solver",       # linear solvers, preconditioners, line search, Newton, LCP (PGS)
    "integrator",   # quasistatic, backward Euler, semi-implicit, energy-limited stepping
    "model",        # scene files -> model (forms, conditions, integrator settings)
    "run",          # frame loop, output files, summary, checkpoint
]
RANK = {name: i for i, name in enumerate(LAYERS)}
INCLUDE = re.compile(r'^\s*#\s*include\s+"sinew/([a-z_0-9]+)/', re.M)


def folder_of(path, root):
    rel = path.relative_to(root)
    parts = rel.parts
    if parts[0] == "include":
        return parts[2]  # include/sinew/<folder>/...
    return parts[1]      # src/<folder>/...


def self_test():
    """The checker must catch an upward include and a cycle in a synthetic tree."""
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "include/sinew/core").mkdir(parents=True)
        (root / "src/mesh").mkdir(parents=True)
        (root / "include/sinew/core/a.hpp").write_text('#include "sinew/mesh/b.hpp"\n')
        (root / "src/mesh/b.cpp").write_text('#include "sinew/core/a.hpp"\n')
        errors = check(root)
        assert any("a layer above it" in e for e in errors), errors
        assert any("folder cycle" in e for e in errors), errors
        (root / "include/sinew/core/a.hpp").write_text("// fine\n")
        assert check(root) == [], check(root)
    print("check_layers: self-test passed")


def main():
    if sys.argv[1] == "--self-test":
        self_test()
        return 0
    root = pathlib.Path(sys.argv[1]).resolve()
    errors = check(root)
    if errors:
        print("\n".join(errors))
        print(f"check_layers: {len(errors)} violation(s)")
        return 1
    print(f"check_layers: no upward include, no cycle ({len(LAYERS)} layers)")
    return 0


def check(root):
    files = [p for base in (root / "include" / "sinew", root / "src") for p in base.rglob("*")
             if p.suffix in (".hpp", ".cpp", ".h", ".cu", ".cuh") and p.is_file()]
    errors = []
    edges = {}
    for path in files:
        src = folder_of(path, root)
        if src not in RANK:
            errors.append(f"{path.relative_to(root)}: folder '{src}' is not in the layer list "
                          "(add it to tests/architecture/check_layers.py and docs/architecture.md)")
            continue
        for m in INCLUDE.finditer(path.read_text(errors="replace")):
            dst = m.group(1)
            if dst == src:
                continue
            line = path.read_text(errors="replace")[:m.start()].count("\n") + 1
            if dst not in RANK:
                errors.append(f"{path.relative_to(root)}:{line}: includes unknown folder '{dst}'")
                continue
            edges.setdefault(src, set()).add(dst)
            if RANK[dst] > RANK[src]:
                errors.append(f"{path.relative_to(root)}:{line}: '{src}' includes '{dst}', "
                              f"a layer above it")
    # Cycles (cannot happen without an upward include, but checked on their own so that a
    # reordering of LAYERS cannot hide one).
    state = {}

    def visit(node, stack):
        state[node] = 1
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == 1:
                errors.append("folder cycle: " + " -> ".join(stack[stack.index(nxt):] + [nxt]))
            elif nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = 2

    for node in sorted(edges):
        if node not in state:
            visit(node, [node])
    return errors


if __name__ == "__main__":
    sys.exit(main())

"""A material sweep: the catalog's families normalised to one Young's modulus and Poisson's
ratio agree at small strain and part ways at large strain (uniaxial stress-stretch curves); the
nonlinearity exponent alpha stiffens or softens one family without changing E and nu; and a
batch of deformation gradients (simple shear) evaluated in one call. Writes a PNG.

    PYTHONPATH=build/python python3 examples/python/material_sweep.py --out material_sweep.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt
import numpy as np

import sinew

E, NU = 1e5, 0.45
FAMILIES = ["stable_neo_hookean", "neo_hookean", "stvk", "hencky", "linear_corotational"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default="material_sweep.png", help="the PNG to write")
    args = parser.parse_args()

    fig, (by_family, by_alpha, shear) = plt.subplots(1, 3, figsize=(15, 4.4))
    print(f"{'material':<26}{'lambda':>12}{'mu':>12}{'E':>12}{'nu':>8}")
    # StVK's Green-strain volume term grows so fast with the axial stretch that beyond about 1.7
    # (at nu = 0.45) no lateral contraction brings the lateral stress to zero (curve() raises
    # sinew.Error saying so), so its curve stops earlier. The mix takes
    # Neo-Hookean's volume term and ARAP's shear term (ARAP alone can only have nu = 0).
    materials = {family: sinew.material(family, E=E, nu=NU) for family in FAMILIES}
    materials["mix: neo_hookean + arap"] = sinew.mix("neo_hookean", "arap", E=E, nu=NU)
    for name, m in materials.items():
        lam, mu = m.lame
        print(f"{name:<26}{lam:>12.5g}{mu:>12.5g}{m.E:>12.5g}{m.nu:>8.3f}")
        c = m.curve("uniaxial", 0.7, 1.6 if name == "stvk" else 2.0, 52)
        by_family.plot(c["stretch"], c["stress"] / E, label=name)
    by_family.set(title=f"uniaxial, E = {E:g}, nu = {NU}", xlabel="stretch", ylabel="nominal stress / E")
    by_family.legend(fontsize=8)

    for alpha in [0.5, 1.0, 1.5, 2.0]:
        m = sinew.material("stable_neo_hookean", E=E, nu=NU, alpha=alpha)
        assert np.allclose(m.lame, sinew.lame_from_young_poisson(E, NU))  # alpha keeps E and nu
        c = m.curve("uniaxial", 0.7, 2.0, 52)
        by_alpha.plot(c["stretch"], c["stress"] / E, label=f"alpha = {alpha:g}")
    by_alpha.set(title="stable Neo-Hookean, nonlinearity exponent", xlabel="stretch")
    by_alpha.legend(fontsize=8)

    # One call evaluates a whole batch: F = I + g e0 e1^T for 200 shears g.
    g = np.linspace(-1.5, 1.5, 200)
    F = np.broadcast_to(np.eye(3), (len(g), 3, 3)).copy()
    F[:, 0, 1] = g
    for name, m in materials.items():
        shear.plot(g, m.psi(F) / E, label=name)
    mu = sinew.lame_from_young_poisson(E, NU)[1]
    shear.plot(g, 0.5 * mu * g**2 / E, "k:", label="mu g^2 / 2")
    shear.set(title="simple shear energy density", xlabel="shear g", ylabel="psi / E")
    shear.legend(fontsize=8)

    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()

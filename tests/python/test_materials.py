"""sinew.Material and the catalog: batches of F in and out, derivatives against finite
differences, Lamé / (E, nu) / alpha / mixing, and errors as sinew.Error."""
import numpy as np
import pytest

import sinew

RNG = np.random.default_rng(14)


def random_F(n, spread=0.3):
    """Deformation gradients near the identity with J > 0 (rotations included)."""
    F = np.eye(3) + spread * RNG.standard_normal((n, 3, 3))
    F[np.linalg.det(F) <= 0.1] = np.eye(3)
    return F


def test_catalog_lists_families_with_parameters():
    families = sinew.materials()
    names = [f["name"] for f in families]
    assert "stable_neo_hookean" in names and "neo_hookean" in names and "ogden" in names
    assert len(names) == len(set(names))
    snh = next(f for f in families if f["name"] == "stable_neo_hookean")
    assert {p["key"] for p in snh["parameters"]} >= set(snh["normalized"])
    assert snh["separable"] in (True, False) and snh["formula"]


@pytest.mark.parametrize("family", ["stable_neo_hookean", "neo_hookean", "stvk", "hencky", "linear_corotational"])
def test_pk1_and_hessian_match_finite_differences(family):
    m = sinew.material(family, E=2.0, nu=0.3)
    F = random_F(4)
    psi, P, H = m.psi(F), m.pk1(F), m.hessian(F)
    assert psi.shape == (4,) and P.shape == (4, 3, 3) and H.shape == (4, 3, 3, 3, 3)
    h = 1e-6
    for a in range(3):
        for b in range(3):
            dF = np.zeros((3, 3))
            dF[a, b] = h
            dpsi = (m.psi(F + dF) - m.psi(F - dF)) / (2 * h)
            np.testing.assert_allclose(P[:, a, b], dpsi, rtol=1e-5, atol=1e-6)
            dP = (m.pk1(F + dF) - m.pk1(F - dF)) / (2 * h)
            np.testing.assert_allclose(H[:, a, b], dP, rtol=1e-5, atol=1e-5)


def test_single_F_and_batches_agree_and_layouts_are_accepted():
    m = sinew.material("neo_hookean", E=3.0, nu=0.4)
    F = random_F(5)
    assert np.ndim(m.psi(F[2])) == 0 and m.pk1(F[2]).shape == (3, 3)
    np.testing.assert_array_equal(m.pk1(F)[2], m.pk1(F[2]))
    # Other dtypes and non-contiguous views are converted; the result is the same.
    np.testing.assert_allclose(m.psi(F.astype(np.float32)), m.psi(F.astype(np.float32).astype(float)))
    Ft = np.ascontiguousarray(F.transpose(0, 2, 1)).transpose(0, 2, 1)  # Fortran-ordered items
    np.testing.assert_array_equal(m.pk1(Ft), m.pk1(F))
    with pytest.raises(ValueError, match=r"shape \(3, 3\) or \(n, 3, 3\)"):
        m.psi(np.eye(4))


def test_projected_hessian_is_psd_and_eigensystem_reconstructs_the_hessian():
    m = sinew.material("stable_neo_hookean", E=1.0, nu=0.45)
    F = random_F(6, spread=0.8)
    H = m.hessian(F).reshape(-1, 9, 9)
    np.testing.assert_allclose(H, H.transpose(0, 2, 1), atol=1e-9)
    values, Q = m.eigensystem(F)
    q = Q.reshape(-1, 9, 9)  # rows: eigenvectors in F.reshape(9) order
    np.testing.assert_allclose(np.einsum("nk,nki,nkj->nij", values, q, q), H, atol=1e-8)
    np.testing.assert_allclose(np.einsum("nki,nli->nkl", q, q), np.broadcast_to(np.eye(9), q.shape), atol=1e-10)
    Hp = m.projected_hessian(F).reshape(-1, 9, 9)
    assert np.linalg.eigvalsh(Hp).min() > -1e-9
    np.testing.assert_allclose(np.einsum("nk,nki,nkj->nij", np.maximum(values, 0), q, q), Hp, atol=1e-8)
    psi, P, He = m.evaluate(F, "none")
    np.testing.assert_allclose(He.reshape(-1, 9, 9), H, atol=1e-10)
    np.testing.assert_allclose(P, m.pk1(F), atol=1e-12)


def test_lame_E_nu_alpha_and_mixing():
    E, nu = 1e5, 0.45
    lam, mu = sinew.lame_from_young_poisson(E, nu)
    assert lam == pytest.approx(E * nu / ((1 + nu) * (1 - 2 * nu))) and mu == pytest.approx(E / (2 * (1 + nu)))
    assert sinew.young_poisson(lam, mu) == pytest.approx((E, nu))
    for family in ("stable_neo_hookean", "neo_hookean", "hencky"):
        m = sinew.material(family, E=E, nu=nu)
        assert (m.E, m.nu) == pytest.approx((E, nu), rel=1e-8)
        assert m.lame == pytest.approx((lam, mu), rel=1e-8)
        params = sinew.normalize(family, E, nu)
        assert m.parameters == pytest.approx(params)
    # The exponent keeps the Lamé parameters and changes large-deformation behaviour.
    soft, stiff = sinew.material("neo_hookean", E=E, nu=nu), sinew.material("neo_hookean", E=E, nu=nu, alpha=2)
    assert stiff.lame == pytest.approx(soft.lame, rel=1e-8) and stiff.alpha == 2
    F = np.diag([2.0, 1.0, 1.0])
    assert stiff.psi(F) > 1.1 * soft.psi(F)
    mixed = sinew.mix("neo_hookean", "linear_corotational", E=E, nu=nu, alpha_mu=2)
    assert mixed.family == "mix" and mixed.lame == pytest.approx((lam, mu), rel=1e-8)
    assert sinew.lambda_part_parameters("neo_hookean") == pytest.approx(mixed.lambda_parameters)
    assert mixed.spec["mix"]["mu_family"] == "linear_corotational"


def test_uniaxial_curve_starts_with_slope_E():
    m = sinew.material("stable_neo_hookean", E=10.0, nu=0.3)
    c = m.curve("uniaxial", 0.99, 1.01, 2)
    assert c["stress"][1] == pytest.approx(0.0, abs=1e-9)
    assert (c["stress"][2] - c["stress"][0]) / 0.02 == pytest.approx(10.0, rel=1e-3)
    assert c["lateral"][2] == pytest.approx(1 - 0.3 * 0.01, rel=1e-3)


def test_errors_are_sinew_errors_with_their_context():
    with pytest.raises(sinew.Error) as e:
        sinew.Material({"family": "no_such_family"})
    assert "no_such_family" in str(e.value) and "stable_neo_hookean" in str(e.value)
    with pytest.raises(sinew.Error) as e:
        sinew.Material({"family": "neo_hookean", "E": 1.0, "nu": 0.6}, context="my material")
    assert str(e.value) == "my material/nu: must satisfy -1 < nu < 0.5, got 0.6"
    assert e.value.context == "my material/nu" and e.value.message == "must satisfy -1 < nu < 0.5, got 0.6"
    m = sinew.material("neo_hookean", E=1.0, nu=0.3)
    F = np.stack([np.eye(3), np.diag([1.0, 1.0, -1.0])])
    with pytest.raises(sinew.Error, match=r"^F\[1\]"):
        m.psi(F)
    assert isinstance(e.value, RuntimeError)

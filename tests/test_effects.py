"""Effects (docs/DESIGN.md "Effects: simulate only what the scene calls for").

1. A disabled effect never runs: its entry point is patched to raise, and the solve with
   the effect off still works (while the same patch breaks the solve with the effect on).
2. Each reduced model equals its physical limit: elastic Greenwood-Williamson (closed form
   through F_n), dry contact = zero speed, rigid film = undeformed gap + z, phi = 1,
   full Sommerfeld (independent 1D quadrature), alleviation's exact factor.
3. ``effects: auto`` (lubecontact.model.auto_effects): its estimates against Martin, Hamrock and the
   full model, and auto against full solves within the tolerance.
"""

import math

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid
from scipy.interpolate import CubicSpline

import lubecontact as lc
from lubecontact.model import auto_effects as effects
from lubecontact.model.auto_effects import (
    OPEN_CIRCUIT_RESISTANCE,
    auto_effects,
    resolve_auto_effects,
)
from lubecontact.physics import film_estimates
from lubecontact.physics.materials import effective_modulus
from lubecontact.physics.rough_surface import gaussian_moment

TABLE1 = "config/scenes/table1.yaml"
COARSE = {"mesh.nx": 21, "mesh.ny": 11}
SCALARS = ["contact_resistance", "friction_coefficient", "fluid_force", "contact_force", "min_film_thickness",
           "separation", "real_contact_area"]


def scene(**overrides):
    return lc.load_scene(TABLE1, {**COARSE, **overrides})


def boom(*args, **kwargs):
    raise AssertionError("code of a disabled effect ran")


def ran(ds) -> set:
    return set(ds.attrs["effects_run"].split(","))


# --- 1. a disabled effect costs nothing ---------------------------------------------------------

# (effect, patched attribute, a scene with the effect on that reaches that code)
ENTRY_POINTS = [
    ("asperity_contact", "lubecontact.model.model.contact_table",
     {"operating.speed": 10.0, "roughness.sigma": 0.25e-6}),
    ("elastic_deformation", "lubecontact.model.model.ElasticDeformation", {"operating.speed": 0.1}),
    ("hydrodynamics", "lubecontact.model.evaluation.solve_reynolds", {"operating.speed": 0.1}),
    ("flow_factors", "lubecontact.physics.flow_factors.pressure_flow_factor", {"operating.speed": 0.1}),
    ("cavitation", "lubecontact.numerics.reynolds._active_set", {"operating.speed": 0.1}),
    ("plasticity", "lubecontact.physics.asperity.hardness_ratio", {"operating.speed": 0.1}),
    ("alleviation", "lubecontact.physics.electrical.spots.alleviation_factor", {"operating.speed": 0.1}),
    ("macro_constriction", "lubecontact.physics.electrical.path.ClusterOperator", {"effects.macro_constriction": True}),
    ("film_conduction", "lubecontact.physics.electrical.path.film_log_conductance", {"effects.film_conduction": True}),
    ("tunnelling", "lubecontact.physics.electrical.film.simmons_log_specific_conductance", {"effects.tunnelling": True}),
]


@pytest.mark.parametrize("effect, target, setting", ENTRY_POINTS, ids=[e[0] for e in ENTRY_POINTS])
def test_a_disabled_effect_never_runs(monkeypatch, effect, target, setting):
    on = scene(**setting)
    off = on.replace({f"effects.{effect}": False})
    monkeypatch.setattr("lubecontact.model.contact_tables._MEMO", {})  # no table cached by an earlier test
    monkeypatch.setattr(target, boom)
    with pytest.raises(AssertionError, match="disabled effect ran"):  # the patch does reach the effect
        lc.solve(on)
    ds = lc.solve(off)
    assert ds["converged"].item() == 1
    assert effect not in ran(ds)


def test_zero_speed_never_solves_reynolds(monkeypatch):
    monkeypatch.setattr("lubecontact.model.evaluation.solve_reynolds", boom)
    ds = lc.solve(scene(**{"operating.speed": 0.0}))
    assert ds["converged"].item() == 1
    assert ran(ds) == {"asperity_contact", "plasticity", "elastic_deformation", "alleviation"}


# --- 2. each reduced model is its physical limit --------------------------------------------------


def test_plasticity_off_is_the_elastic_greenwood_williamson_law():
    # Rigid dry contact with Hertzian asperities: every node's nominal pressure and real area
    # are the GW closed forms p = (4/3) eta E* R^1/2 s^3/2 F_3/2(t), A_r/A_n = pi eta R s F_1(t),
    # t = (h - y_s)/s, y_s = 0.045944/(eta R) (McCool, Eq. 13), F_n by parabolic cylinder functions.
    s = scene(**{"effects.plasticity": False, "effects.hydrodynamics": False, "effects.elastic_deformation": False})
    ds = lc.solve(s, fields=True)
    assert ds["converged"].item() == 1
    eta, r_p, sigma = 1e9, 1e-4, 0.5e-6
    t = (ds["film_thickness"].values - 0.045944 / (eta * r_p)) / sigma
    pressure = 4.0 / 3.0 * eta * effective_modulus(s) * math.sqrt(r_p) * sigma**1.5 * gaussian_moment(1.5, t)
    computed = ds["contact_pressure"].values
    np.testing.assert_allclose(computed, pressure, rtol=1e-5, atol=1e-9 * pressure.max())
    x, y = ds["x"].values, ds["y"].values
    area = np.trapezoid(np.trapezoid(math.pi * eta * r_p * sigma * gaussian_moment(1.0, t), x, axis=1), y)
    assert ds["real_contact_area"].item() == pytest.approx(area, rel=1e-5)
    plastic = lc.solve(s.replace({"effects.plasticity": True}))
    assert plastic["real_contact_area"].item() > 2 * area  # JG flattened asperities: much more area


def test_hydrodynamics_off_is_the_dry_contact_and_equals_zero_speed():
    dry = lc.solve(scene(**{"effects.hydrodynamics": False, "operating.speed": 0.1}))
    still = lc.solve(scene(**{"operating.speed": 0.0}))
    for name in SCALARS:
        assert dry[name].item() == pytest.approx(still[name].item(), rel=1e-12, abs=1e-300)
    assert dry["fluid_force"].item() == 0.0
    assert dry["contact_force"].item() == pytest.approx(5.0, rel=1e-6)
    assert dry["friction_coefficient"].item() == pytest.approx(0.1, rel=1e-6)  # mu_b F_cont / F


def test_elastic_deformation_off_is_the_rigid_film():
    ds = lc.solve(scene(**{"effects.elastic_deformation": False, "operating.speed": 0.1}), fields=True)
    assert ds["converged"].item() == 1
    assert ds["iterations"].item() == 1
    radius, x = 0.01, ds["x"].values
    gap = radius - np.sqrt(radius**2 - x**2)  # Eq. (4)
    film = ds["film_thickness"].values
    np.testing.assert_allclose(film, np.broadcast_to(gap + ds["separation"].item(), film.shape), rtol=0, atol=1e-15)
    assert np.all(ds["deformation"].values == 0.0)


def test_flow_factors_off_is_phi_equal_one(monkeypatch):
    off = lc.solve(scene(**{"effects.flow_factors": False, "operating.speed": 0.1}))
    with_phi = lc.solve(scene(**{"operating.speed": 0.1}))
    assert with_phi["contact_resistance"].item() != pytest.approx(off["contact_resistance"].item(), rel=1e-3)
    monkeypatch.setattr("lubecontact.physics.flow_factors.pressure_flow_factor", lambda h: np.ones_like(np.asarray(h, float)))
    monkeypatch.setattr("lubecontact.physics.flow_factors.pressure_flow_factor_slope", lambda h: np.zeros_like(np.asarray(h, float)))
    unit_phi = lc.solve(scene(**{"operating.speed": 0.1}))
    for name in SCALARS:
        assert off[name].item() == pytest.approx(unit_phi[name].item(), rel=1e-9)


def test_cavitation_off_gives_the_full_sommerfeld_pressure():
    # Line contact, rigid, symmetric domain: the asperities carry the load and the fluid
    # pressure is the full-Sommerfeld solution of the film found, negative downstream.
    # Truth: 1D Reynolds integrated by quadrature, p = int (U h_T/2 - q)/k dx with p = 0 at
    # both ends (no cavitation), on the solve's film through the Patir-Cheng gap and k
    # (down to percolation: flow_factors.percolating_coefficient_and_slope).
    from lubecontact.model.fluid_film import FLUID_FILM_FLOOR_SIGMAS
    from lubecontact.physics.flow_factors import (
        expected_gap,
        percolating_coefficient_and_slope,
    )

    half = 3e-4
    s = scene(**{"effects.cavitation": False, "effects.elastic_deformation": False, "operating.speed": 0.1,
                 "mesh.ny": 1, "mesh.nx": 1601, "mesh.x_min": -half, "mesh.x_max": half})
    ds = lc.solve(s, fields=True)
    assert ds["converged"].item() == 1
    x, film, p = ds["x"].values, ds["film_thickness"].values[0], ds["fluid_pressure"].values[0]
    assert p.min() < -0.5 * p.max() < 0.0
    # k falls steeply to the sealed film's leak at the threshold (1/k ~ 1/h): integrate on a grid
    # 16x finer; the finite volumes converge to it slowly there (max error 1.4 / 0.9 / 0.2 % on
    # 401 / 801 / 1601 nodes), hence 1601 nodes
    # (the rigid film is a parabola: cubic interpolation of the nodal film is exact to round-off)
    fine = np.linspace(x[0], x[-1], 16 * (x.size - 1) + 1)
    film = CubicSpline(x, film)(fine)
    h_t = expected_gap(np.maximum(film, FLUID_FILM_FLOOR_SIGMAS * 0.5e-6), 0.5e-6)  # the content's floor
    k = percolating_coefficient_and_slope(film, 0.5e-6, 0.1)[0]
    a = cumulative_trapezoid(0.05 * h_t / k, fine, initial=0.0)
    b = cumulative_trapezoid(1.0 / k, fine, initial=0.0)
    sommerfeld = (a - a[-1] / b[-1] * b)[::16]
    np.testing.assert_allclose(p, sommerfeld, rtol=0, atol=5e-3 * np.abs(sommerfeld).max())
    np.testing.assert_allclose(p, -p[::-1], rtol=0, atol=1e-6 * np.abs(p).max())  # odd in x
    assert abs(ds["fluid_force"].item()) < 1e-6 * 5.0


def test_alleviation_off_raises_the_resistance_by_the_exact_factor():
    # Same mechanics either way; R_off / R_on = sum(g dA / Psi) / sum(g dA) (Eqs. 15-17) with
    # Psi = (1 - sqrt(min(A_r/A_n, 0.99)))^1.5 and trapezoidal nodal areas, built here.
    from lubecontact.physics.rough_surface import RoughContact

    s = scene(**{"operating.speed": 0.01})
    on = lc.solve(s, fields=True)
    off = lc.solve(s.replace({"effects.alleviation": False}), fields=True)
    np.testing.assert_array_equal(on["film_thickness"].values, off["film_thickness"].values)
    contact = RoughContact.from_scene(s)
    film = on["film_thickness"].values
    g, ratio = contact.conductance(film), contact.area_fraction(film)
    psi = (1.0 - np.sqrt(np.minimum(ratio, 0.99))) ** 1.5
    x, y = on["x"].values, on["y"].values
    wx, wy = np.gradient(x), np.gradient(y)  # trapezoid: half weights at the ends
    wx[[0, -1]] = 0.5 * (x[1] - x[0]), 0.5 * (x[-1] - x[-2])
    wy[[0, -1]] = 0.5 * (y[1] - y[0]), 0.5 * (y[-1] - y[-2])
    area = np.outer(wy, wx)
    factor = np.sum(g * area / psi) / np.sum(g * area)
    assert factor > 2.0
    assert off["contact_resistance"].item() / on["contact_resistance"].item() == pytest.approx(factor, rel=1e-10)
    assert 1.0 / on["contact_resistance"].item() == pytest.approx(np.sum(g * area / psi), rel=1e-10)


# --- 3. effects: auto -----------------------------------------------------------------------------


def test_reynolds_line_load_reproduces_martin():
    # docs/physics.md section 4: rigid cylinder, Reynolds exit condition: w' = 4.895 mu u_m R / h0.
    mu, speed, radius, h0 = 0.1, 1.0, 0.01, 1e-6
    inlet = math.sqrt(2 * radius * h0)
    x = inlet * np.tan(np.linspace(math.atan(-60.0), math.atan(5.0), 4001))
    h = h0 + x**2 / (2 * radius)
    w = film_estimates.reynolds_line_load(x, h, h**3 / (12 * mu), speed)
    assert w * h0 / (mu * 0.5 * speed * radius) == pytest.approx(4.895, rel=2e-3)


def test_film_estimates_follow_martin_and_hamrock():
    mu, speed, radius, length, force = 0.1, 10.0, 0.01, 1e-3, 5.0
    s = scene(**{"operating.speed": speed, "effects.asperity_contact": False, "mesh.ny": 1, "mesh.nx": 101,
                 "mesh.x_min": -9e-3, "mesh.x_max": 2e-3})
    assert film_estimates.martin_film(s) == pytest.approx(4.9 * mu * 0.5 * speed * radius * length / force, rel=1e-12)
    assert effects.film_estimate(s) == pytest.approx(film_estimates.martin_film(s) * 4.895 / 4.9, rel=0.01)
    # finite cylinder: 1/F = h/(4.895 mu u_m R L) + 4 h^2/(mu U L^3) (Martin and Ocvirk's short bearing)
    a, b = 4.0 * force / (mu * speed * length**3), force / (4.895 * mu * 0.5 * speed * radius * length)
    short = (-b + math.sqrt(b * b + 4.0 * a)) / (2.0 * a)
    assert effects.film_estimate(s.replace({"mesh.ny": 11})) == pytest.approx(short, rel=0.01)
    for g in (20.0, 50.0, 200.0):  # docs/physics.md section 5: H_min -> 3.10 g_E^0.8 (within 2 % for g_E >= 20)
        assert film_estimates.elastic_film_factor(g) * 4.9 == pytest.approx(3.10 * g**0.8, rel=0.02)
    assert film_estimates.elastic_film_factor(0.01) == pytest.approx(1.0, abs=0.015)
    point = effects.operating_point(s)  # docs/physics.md section 9: g_E = 0.324 at 10 m/s for Table 1
    assert point.elasticity == pytest.approx(0.324, rel=0.01)


def test_film_estimate_errs_thick_against_the_rigid_solve():
    s = scene(**{"operating.speed": 10.0, "roughness.sigma": 0.05e-6, "effects.asperity_contact": False,
                 "effects.elastic_deformation": False, "mesh.nx": 31, "mesh.ny": 21})
    solved = lc.solve(s)["min_film_thickness"].item()
    assert solved < effects.film_estimate(s) < 1.25 * solved


@pytest.mark.parametrize("overrides", [{"roughness.sigma": 0.25e-6}, {"roughness.sigma": 2e-6}, {"operating.force": 0.5}],
                         ids=["sigma=0.25um", "sigma=2um", "F=0.5N"])
def test_fluid_share_bound_lies_above_the_coupled_fluid_share(overrides):
    s = scene(**{"operating.speed": 1e-3, "mesh.nx": 31, "mesh.ny": 21, **overrides})
    contact = effects.contact_table(s)
    share, _ = effects.fluid_share_bound(s, effects.dry_contact(s, contact), contact.sigma)
    actual = lc.solve(s)["fluid_load_fraction"].item()
    assert actual < share < 30 * actual


def test_dry_contact_matches_the_rigid_dry_solve():
    s = scene(**{"operating.speed": 0.0, "effects.elastic_deformation": False, "mesh.ny": 1, "mesh.nx": 401})
    dry = effects.dry_contact(s, effects.contact_table(s))
    ds = lc.solve(s)
    assert dry.separation == pytest.approx(ds["min_film_thickness"].item(), abs=1e-3 * 0.5e-6)
    assert dry.resistance == pytest.approx(ds["contact_resistance"].item(), rel=2e-3)
    stiffer = lc.solve(s.replace({"operating.force": 5.05}))["contact_resistance"].item()
    assert dry.load_exponent == pytest.approx(-math.log(stiffer / ds["contact_resistance"].item()) / math.log(1.01), rel=0.02)


def test_auto_decisions_and_their_reasons():
    still, reasons = resolve_auto_effects(scene(**{"effects": "auto", "operating.speed": 0.0}))
    assert not still.effects.hydrodynamics and not still.effects.auto
    assert reasons["hydrodynamics"].startswith("off: speed 0")
    assert set(reasons) == set(effects.EFFECTS)

    mixed, reasons = resolve_auto_effects(scene(**{"effects": "auto", "operating.speed": 0.1}))
    assert all(getattr(mixed.effects, name) for name in effects.EFFECTS)
    assert all(r.startswith("on: ") for r in reasons.values())

    smooth = auto_effects(scene(**{"effects": "auto", "operating.speed": 10.0, "roughness.sigma": 0.05e-6}))
    assert not smooth.scene.effects.asperity_contact and smooth.contact is None
    assert smooth.scene.effects.hydrodynamics and smooth.scene.effects.cavitation
    assert "open circuit" in smooth.reasons["asperity_contact"]

    light = scene(**{"effects": "auto", "operating.speed": 0.0, "operating.force": 0.05, "roughness.sigma": 2e-6})
    assert not resolve_auto_effects(light)[0].effects.elastic_deformation  # Hertz approach 0.004 sigma


def test_auto_matches_the_full_model_within_its_tolerance():
    # A compact Fig. 4 grid: auto drops the fluid at the lowest speeds and the asperities of
    # a smooth film; resistance within 2 % (or open in both), friction within 2 %.
    tol = effects.DEFAULT_TOLERANCE
    dropped = set()
    cases = [(sigma, speed) for sigma in (0.5e-6, 2e-6) for speed in (1e-4, 0.1, 10.0)] + [(0.05e-6, 10.0)]
    for sigma, speed in cases:
        full = scene(**{"roughness.sigma": sigma, "operating.speed": speed})
        auto = lc.solve(full.replace({"effects": "auto"}))
        reference = lc.solve(full)
        assert auto["converged"].item() == 1
        assert auto.attrs["notes"].startswith("effects: auto -> hydrodynamics: ")
        dropped |= ran(reference) - ran(auto)
        r_auto, r_full = auto["contact_resistance"].item(), reference["contact_resistance"].item()
        if not (r_auto >= OPEN_CIRCUIT_RESISTANCE and r_full >= OPEN_CIRCUIT_RESISTANCE):
            assert r_auto == pytest.approx(r_full, rel=tol)
        assert auto["friction_coefficient"].item() == pytest.approx(reference["friction_coefficient"].item(), rel=tol)
    assert {"hydrodynamics", "asperity_contact"} <= dropped

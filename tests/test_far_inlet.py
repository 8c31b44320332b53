"""The far inlet as an exact boundary condition (numerics/far_inlet.py, docs/physics.md
section 17) against independent truths: adaptive quadrature of its integrals and of
Martin's exterior film, finite differences of its slopes, and Martin's closed-form film
carried by a line contact on a domain five times shorter than the long inlet's."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

import lubecontact as lc
from lubecontact.cli.main import main
from lubecontact.model.validity import far_inlet_advice
from lubecontact.numerics.far_inlet import FarInlet, parabola_integrals
from lubecontact.numerics.mesh import Mesh, build_mesh, domain_x, nodes_x
from lubecontact.physics.percolation import face_film

TABLE1 = "config/scenes/table1.yaml"
RADIUS, VISCOSITY, SPEED = 0.01, 0.1, 10.0


def exterior_quadrature(power, offset, end, moment=False):
    """int_{-inf}^{end} (end - x)^moment (c + x^2/2R)^-power dx by adaptive quadrature, split
    at decades of the film's two lengths (scipy's quad over (0, inf) alone misses a narrow
    peak, and one split left roundoff warnings and errors of 3e-9)."""
    film = offset + end * end / (2 * RADIUS)
    scales = (film / (abs(end) / RADIUS), np.sqrt(2 * RADIUS * film))  # where the slope, the curvature governs

    def integrand(u):  # u = end - x >= 0
        return u**moment * (offset + (end - u) ** 2 / (2 * RADIUS)) ** -power

    bounds = [0.0, *sorted({scale * 10.0**k for scale in scales for k in range(-1, 4)}), np.inf]
    return sum(quad(integrand, a, b, epsrel=1e-14, limit=1000)[0] for a, b in zip(bounds[:-1], bounds[1:]))


# the reference's own roundoff notices on the extreme films (its values agree to 1e-8 all the same)
@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("end", [-3e-4, -1.1e-3, -6e-3])
@pytest.mark.parametrize("offset_fraction", [-0.8, -0.01, 0.0, 0.05, 1.0, 100.0])
def test_the_parabola_integrals_match_adaptive_quadrature(end, offset_fraction):
    """To 1e-8: the rule's largest error, 1.4e-9 on K_2, is for a film 100 times the gap's rise at
    the domain's end; where the far inlet works (a film below the rise) it is below 1e-11."""
    offset = offset_fraction * end * end / (2 * RADIUS)  # c, from a cylinder sunk deep to a film far above the gap
    n = parabola_integrals(np.array([offset]), end, RADIUS)
    for power in (1, 2, 3, 4):
        assert n.i[power][0] == pytest.approx(exterior_quadrature(power, offset, end), rel=1e-8)
    for power in (2, 3, 4):
        assert n.k[power][0] == pytest.approx(exterior_quadrature(power, offset, end, moment=True), rel=1e-8)


def line_mesh(nodes=51, start=-1.1e-3, stop=4.7e-4):
    return Mesh(x=np.linspace(start, stop, nodes), y=np.zeros(1), length=1e-3, far_inlet=True)


def exterior(mesh):
    return FarInlet.on(mesh, RADIUS, VISCOSITY, SPEED)


def a_film(mesh, central=3e-6):
    return central + mesh.x[None, :] ** 2 / (2 * RADIUS)


def test_martins_exterior_film_gives_the_flux_load_shear_and_boundary_pressure():
    """Truth: Martin's exterior solved by quadrature from its ODE, h^3/(12 mu) p' = (U/2)(h - h*)
    with p(-inf) = 0, for the h* that gives the first Reynolds node's pressure p_1."""
    mesh = line_mesh()
    inlet, film = exterior(mesh), a_film(mesh)
    x0, x1, dx, width = mesh.x[0], mesh.x[1], mesh.dx, mesh.length
    offset = 0.5 * (film[0, 0] + film[0, 1]) - (x0**2 + x1**2) / (4 * RADIUS)
    h = lambda x: offset + x * x / (2 * RADIUS)
    p1 = 2.0e4
    gradient = lambda x, h_star: 6 * VISCOSITY * SPEED * (h(x) - h_star) / h(x) ** 3
    pressure = lambda x, h_star: quad(lambda s: gradient(s, h_star), -np.inf, x, epsrel=1e-12, limit=400)[0]
    h_star = brentq(lambda hs: pressure(x1, hs) - p1, 0.0, 10 * h(x1), xtol=1e-20, rtol=1e-14)
    field = np.zeros(mesh.shape)
    field[0, 1] = p1

    values, _ = inlet.faces(film, *smooth_faces(mesh, film))
    flux = 0.5 * SPEED * values.gap_x[0, 0] - values.coefficient_x[0, 0] / dx * p1  # the face's, per width
    assert flux == pytest.approx(0.5 * SPEED * h_star, rel=1e-9)

    load = quad(lambda x: pressure(x, h_star), -np.inf, x1, epsrel=1e-11, limit=400)[0]
    value, weights, _ = inlet.load(field, film)
    assert value == pytest.approx(width * (load - 0.5 * dx * p1), rel=1e-8)
    assert value == pytest.approx(float(np.sum(weights * field)) + inlet.load(np.zeros(mesh.shape), film)[0], rel=1e-12)

    boundary, shear = inlet.upstream(field, film)
    assert boundary[0] == pytest.approx(pressure(x0, h_star), rel=1e-8)
    tau = lambda x: VISCOSITY * SPEED / h(x) + 0.5 * h(x) * gradient(x, h_star)  # on the block (friction.py)
    assert shear == pytest.approx(width * quad(tau, -np.inf, x0, epsrel=1e-12, limit=400)[0], rel=1e-8)


def smooth_faces(mesh, film):
    """The faces of a smooth Newtonian film (k = h^3/(12 mu), content h), as percolation.py
    lays them out, for the far inlet to overwrite."""
    return face_film(film, lambda h: (h**3 / (12 * VISCOSITY), h**2 / (4 * VISCOSITY)), lambda h: (h, np.ones_like(h)))


def test_the_slopes_are_the_derivatives_in_the_first_faces_film():
    mesh = line_mesh()
    inlet, film = exterior(mesh), a_film(mesh)
    field = np.zeros(mesh.shape)
    field[0, 1] = 3.0e4
    step = 1e-12  # m, on a film of 60 um at the face

    def faces(f):
        return inlet.faces(f, *smooth_faces(mesh, f))[0]

    up, down = film.copy(), film.copy()
    up[0, :2] += step
    down[0, :2] -= step  # the face's film h_f moves by the step
    _, slopes = inlet.faces(film, *smooth_faces(mesh, film))
    for name in ("coefficient_x", "gap_x"):
        numeric = (getattr(faces(up), name)[0, 0] - getattr(faces(down), name)[0, 0]) / (2 * step)
        assert getattr(slopes, name)[0, 0] == pytest.approx(numeric, rel=1e-5)
    _, _, film_slope = inlet.load(field, film)
    for node in (0, 1):  # each of the face's nodes moves h_f by half its own change
        up, down = film.copy(), film.copy()
        up[0, node] += step
        down[0, node] -= step
        numeric = (inlet.load(field, up)[0] - inlet.load(field, down)[0]) / (2 * step)
        assert film_slope[0, node] == pytest.approx(numeric, rel=1e-5)


# Martin's film of a rigid cylinder at 10 m/s, with roughness ten times below the film's
# hundredth so that the flow factors are 1: h_min = 4.895 mu (U/2) R L / F (Martin 1916 with
# the Reynolds condition, as tests/test_lubricated.py)
MARTIN = {"mesh.ny": 1, "mesh.nx": 201, "operating.speed": SPEED, "effects.elastic_deformation": False,
          "roughness.sigma": 0.05e-6, "mesh.far_inlet": True}
MARTIN_FILM = 4.895 * VISCOSITY * 0.5 * SPEED * RADIUS * 1e-3 / 5.0


@pytest.mark.parametrize("method", ["nested", "newton"])
def test_a_line_contact_carries_martins_film_on_a_domain_without_inlet_cells(method):
    scene = lc.load_scene(TABLE1, {**MARTIN, "solver.method": method})
    mesh = build_mesh(scene)
    assert mesh.far_inlet and mesh.nx == 201  # the automatic domain's nodes, none added upstream
    ds = lc.solve(scene)
    assert ds["converged"].item() == 1
    assert ds["min_film_thickness"].item() == pytest.approx(MARTIN_FILM, rel=1e-3)
    assert "inlet" not in ds.attrs["validity"]


def test_the_long_inlet_it_replaces_is_short_of_martins_film():
    """What the far inlet fixes: the same line on the long inlet (20 film lengths, p = 0 at its
    end, the default), at the same spacing, carries a film more than half a per cent thinner."""
    scene = lc.load_scene(TABLE1, {**MARTIN, "mesh.far_inlet": False})
    mesh = build_mesh(scene)
    assert not mesh.far_inlet and mesh.nx > 5 * 201
    ds = lc.solve(scene)
    assert ds["min_film_thickness"].item() < 0.995 * MARTIN_FILM
    assert mesh.nx == nodes_x(scene) and mesh.x[0] == domain_x(scene)[0]


@pytest.mark.parametrize("overrides, need", [
    ({"mesh.ny": 21, "geometry.crown_radius": 0.1}, "a straight cylinder"),
    ({"mesh.ny": 21, "effects.cavitation": "jfo"}, "on a 2-D mesh, effects.cavitation reynolds or none"),
    ({"mesh.x_min": -1e-3, "mesh.x_max": 5e-4}, "the automatic domain"),
    ({"lubricant.rheology": "bingham", "lubricant.yield_stress": 100.0}, "a Newtonian lubricant"),
    ({"effects.asperity_contact": False}, "asperity contact"),
    ({"motion.kind": "stop"}, "a steady solve"),
])
def test_a_far_inlet_where_it_does_not_hold_is_refused_naming_what_it_needs(overrides, need):
    with pytest.raises(lc.SceneError, match=f"mesh.far_inlet: true needs {need}"):
        lc.load_scene(TABLE1, {**MARTIN, **overrides})


def test_a_motions_mesh_keeps_the_long_inlet_and_the_key_is_auto_by_default():
    """mesh.far_inlet: auto (the default, left out of the canonical form, so old scenes keep
    their hash) takes the far inlet where the long inlet adds columns and it fits; true asks
    for it anywhere it fits; false keeps the long inlet; a motion's mesh keeps it."""
    line = lc.load_scene(TABLE1, {**MARTIN, "mesh.nx": 51})
    motion = build_mesh(line, far_inlet=False)  # as unsteady/integrator.py builds a motion's mesh
    assert not motion.far_inlet and motion.nx > build_mesh(line).nx == 51
    default = lc.load_scene(TABLE1, {"mesh.ny": 1})
    assert lc.load_scene(TABLE1, {"mesh.ny": 1, "mesh.far_inlet": "auto"}).hash == default.hash
    assert "far_inlet" not in default.canonical_yaml() and default.mesh.far_inlet is None
    for key in (True, False):
        assert lc.load_scene(TABLE1, {"mesh.ny": 1, "mesh.far_inlet": key}).hash != default.hash
    fast, slow = (lc.load_scene(TABLE1, {"mesh.ny": 1, "mesh.nx": 51, "operating.speed": u}) for u in (10.0, 0.001))
    assert build_mesh(fast).far_inlet and build_mesh(fast).nx == 51 < nodes_x(fast.replace({"mesh.far_inlet": False}))
    assert not build_mesh(slow).far_inlet and build_mesh(slow.replace({"mesh.far_inlet": True})).far_inlet
    # auto where it does not fit: the long inlet, no refusal
    crowned = fast.replace({"mesh.ny": 11, "geometry.crown_radius": 0.1})
    assert not build_mesh(crowned).far_inlet and build_mesh(crowned).nx > 51


def test_a_starved_steady_line_is_told_of_the_far_inlet_which_floods_it():
    """A 10 Pa s oil at 1 m/s on a line: its long inlet stops at 0.9 R, where a rigid film is
    3 % short of the flooded one (the flag ``inlet``), and the flag says the far inlet would
    flood it; with it the film is thicker, and the flag says instead that the flooded film
    rests on Martin's parabola beyond 0.9 R, a gap the cylinder does not have. Table 1's own
    oil needs no lubricant from there: no flag."""
    viscous = {"mesh.ny": 1, "lubricant.viscosity": 10.0, "operating.speed": 1.0}
    starved = lc.solve(lc.load_scene(TABLE1, {**viscous, "mesh.far_inlet": False}))
    assert "inlet" in starved.attrs["validity"] and "leave mesh.far_inlet at auto" in starved.attrs["notes"]
    flooded = lc.solve(lc.load_scene(TABLE1, {**viscous, "mesh.far_inlet": True}))
    default = lc.solve(lc.load_scene(TABLE1, viscous))  # auto: the far inlet here
    assert default["min_film_thickness"].item() == flooded["min_film_thickness"].item()
    assert flooded["converged"].item() == 1 and "inlet" in flooded.attrs["validity"]
    assert "beyond 0.9 R" in flooded.attrs["notes"] and "parabola" in flooded.attrs["notes"]
    assert "leave mesh.far_inlet" not in flooded.attrs["notes"]
    assert flooded["min_film_thickness"].item() > starved["min_film_thickness"].item()
    table1 = lc.solve(lc.load_scene(TABLE1, {"mesh.ny": 1, "operating.speed": 1.0, "mesh.far_inlet": True}))
    assert "inlet" not in table1.attrs["validity"]
    for where_it_would_not_hold in ({"mesh.ny": 21, "geometry.crown_radius": 0.1}, {"mesh.x_min": -5e-3, "mesh.x_max": 5e-4},
                                    {"motion.kind": "stop"}):
        assert far_inlet_advice(lc.load_scene(TABLE1, {**viscous, "mesh.far_inlet": False,
                                                       **where_it_would_not_hold})) == ""
    assert far_inlet_advice(lc.load_scene(TABLE1, viscous)) == ""  # auto: it has the far inlet already


def test_a_case_and_the_cli_say_which_inlet_the_mesh_has(capsys, tmp_path):
    """A case's attribute ``mesh`` and `lubecontact solve` name the mesh solved and what lies
    upstream of it: the far inlet (the default at 10 m/s), the long inlet's added columns
    (mesh.far_inlet: false), or nothing (0.001 m/s, where the long inlet adds none)."""
    coarse = {"mesh.nx": 21, "mesh.ny": 11}
    for speed, key, said in ((10.0, "auto", "open upstream to the far inlet"), (10.0, "false", "the long inlet: "),
                             (0.001, "auto", "p = 0 at x_min")):
        scene = lc.load_scene(TABLE1, {**coarse, "operating.speed": speed, "mesh.far_inlet": key})
        mesh = build_mesh(scene)
        ds = lc.solve(scene)
        expected = f"11 x {mesh.nx} nodes (y x x), x from {mesh.x[0] * 1e3:.4g} to {mesh.x[-1] * 1e3:.4g} mm"
        assert ds.attrs["mesh"].startswith(expected) and said in ds.attrs["mesh"]
        if key == "false":
            assert f"the long inlet: {mesh.nx - 21} columns added" in ds.attrs["mesh"] and mesh.nx > 21
        assert main(["solve", TABLE1, "--set", f"operating.speed={speed}", "--set", f"mesh.far_inlet={key}",
                     "--set", "mesh.nx=21", "--set", "mesh.ny=11", "--out", str(tmp_path / "case.nc")]) == 0
        assert f"mesh: {ds.attrs['mesh']}" in capsys.readouterr().out

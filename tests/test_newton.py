"""The coupled Newton step (newton.py) against independent truths: its linearised fluid
pressure against central finite differences of the Reynolds solve, and the steady solve it
drives against the same solve by the contact-only step with Anderson mixing (another path
to the same discrete solution)."""

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.model import coupling
from lubecontact.model.evaluation import evaluate
from lubecontact.model.model import Model
from lubecontact.model.newton import contact_newton_step, fluid_pressure_response

TABLE1 = "config/scenes/table1.yaml"


def scene(**overrides):
    return lc.load_scene(TABLE1, {"mesh.nx": 31, "mesh.ny": 21, **overrides})


@pytest.mark.parametrize("speed", [0.1, 1.0])
def test_fluid_response_equals_finite_differences_of_the_reynolds_solve(speed):
    """dp = response(v) against (p(h + eps v) - p(h - eps v)) / 2 eps at the converged state
    (same cavitated set: v vanishes near the cavitation boundary), film change v smooth and
    of both signs. The response runs on the faces' slopes (percolating flow factors)."""
    s = scene(**{"operating.speed": speed})
    _, state = lc.solve(s, return_state=True)
    model = Model.assemble(s)
    mesh = model.mesh
    X, Y = np.meshgrid(mesh.x, mesh.y)
    pressurised = state.fluid_pressure > 0.05 * state.fluid_pressure.max()
    v = np.where(pressurised, np.cos(X / (mesh.x.max() - mesh.x.min()) * 7.0) * (1.0 + Y / mesh.length), 0.0)
    eps = 1e-3 * model.contact.sigma
    plus = evaluate(model, state.z, state.delta + eps * v, state.reynolds.cavitated)
    minus = evaluate(model, state.z, state.delta - eps * v, state.reynolds.cavitated)
    assert np.array_equal(plus.reynolds.cavitated, state.reynolds.cavitated)
    assert np.array_equal(minus.reynolds.cavitated, state.reynolds.cavitated)
    finite = (plus.fluid_pressure - minus.fluid_pressure) / (2 * eps)
    exact_state = evaluate(model, state.z, state.delta, state.reynolds.cavitated)
    linear = fluid_pressure_response(model, exact_state)(v)
    scale = np.abs(finite).max()
    assert scale > 0.0
    np.testing.assert_allclose(linear, finite, rtol=0.0, atol=1e-5 * scale)


def test_coupled_newton_and_mixed_contact_steps_reach_the_same_solution(monkeypatch):
    """The steady solve with the coupled Newton step, and with the contact-only step + Anderson
    mixing (the coupled step switched off), end within the solver tolerance of each other;
    the coupled one in fewer outer iterations."""
    s = scene(**{"operating.speed": 0.1})
    coupled = lc.solve(s)
    from lubecontact.numerics.anderson import AndersonMixer

    monkeypatch.setattr(coupling, "deformation_stepper", lambda model: (contact_newton_step, AndersonMixer(beta=1.0)))
    mixed = lc.solve(s)
    assert coupled["converged"].item() == 1 and mixed["converged"].item() == 1
    for name in ("contact_resistance", "friction_coefficient", "separation", "fluid_force"):
        assert coupled[name].item() == pytest.approx(mixed[name].item(), rel=1e-5)
    assert coupled["iterations"].item() <= mixed["iterations"].item()


def test_backtracking_makes_newton_converge_where_full_steps_diverge():
    """Kelley's example (1995, section 8.1): Newton's method on arctan(x) = 0 from x = 10
    overshoots further each step; with Armijo backtracking it reaches the root 0."""
    from lubecontact.model.newton import Backtracking

    def newton(x, search=None, iterations=30):
        for _ in range(iterations):
            if search is not None:
                fraction = search.retry(abs(np.arctan(x)))
                if fraction is not None:
                    anchor, _, step, _ = search.anchor
                    x = anchor + fraction * step
                    continue
            step = -np.arctan(x) * (1.0 + x * x)
            if search is not None:
                search.accept(x, abs(np.arctan(x)), step)
            x = x + step
            if not np.isfinite(x) or abs(x) > 1e100:
                break
        return x

    assert not abs(newton(10.0)) < 1.0  # full steps diverge
    assert abs(newton(10.0, Backtracking())) < 1e-12


def test_backtracking_stops_halving_at_the_smallest_fraction():
    from lubecontact.model.newton import SMALLEST_STEP_FRACTION, Backtracking

    search = Backtracking()
    search.accept(0.0, 1.0, 1.0)
    fractions = []
    while (fraction := search.retry(2.0)) is not None:  # never any decrease
        fractions.append(fraction)
    assert fractions == [0.5, 0.25, 0.125, 0.0625] and fractions[-1] == SMALLEST_STEP_FRACTION
    assert search.exhausted
    search.accept(0.0, 1.0, 1.0)
    assert search.retry(0.5) is None and not search.exhausted  # enough decrease: kept


def test_stalled_newton_steps_backtrack_to_the_mixed_steps_solution(monkeypatch):
    """Table 1 on 51^2 at 0.0158 m/s: near the fold the full Newton steps cycle between
    cavitated sets (650 <-> 654 nodes) and stall; the backtracked steps converge, to the
    solution the contact-only step with Anderson mixing (another path) reaches, in fewer
    outer iterations (16 against 65 for the restart with mixed steps it replaced)."""
    from lubecontact.model.newton import Backtracking
    from lubecontact.numerics.anderson import AndersonMixer

    fractions = []

    class Recorded(Backtracking):
        def retry(self, norm):
            fractions.append(super().retry(norm))
            return fractions[-1]

    monkeypatch.setattr(coupling, "Backtracking", Recorded)
    s = lc.load_scene(TABLE1, {"mesh.nx": 51, "mesh.ny": 51, "operating.speed": 0.0158})
    backtracked = lc.solve(s)
    assert any(fractions)  # it engaged and shortened a step

    def mixed_steps(model):  # a fresh mixer for each level, as deformation_stepper gives
        return contact_newton_step, AndersonMixer(beta=1.0)

    monkeypatch.setattr(coupling, "deformation_stepper", mixed_steps)
    mixed = lc.solve(s)
    assert backtracked["converged"].item() == 1 and mixed["converged"].item() == 1
    for name in ("contact_resistance", "friction_coefficient", "separation", "fluid_force"):
        assert backtracked[name].item() == pytest.approx(mixed[name].item(), rel=1e-5)
    assert backtracked["iterations"].item() < mixed["iterations"].item()

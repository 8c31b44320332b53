"""The coupled Newton step (newton.py) against independent truths: its linearised fluid
pressure against central finite differences of the Reynolds solve, and the steady solve it
drives against the same solve by the contact-only step with Anderson mixing (another path
to the same discrete solution)."""

import numpy as np
import pytest

import lubecontact as lc
from lubecontact import solver
from lubecontact.newton import fluid_pressure_response

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
    model = solver.Model.assemble(s)
    mesh = model.mesh
    X, Y = np.meshgrid(mesh.x, mesh.y)
    pressurised = state.fluid_pressure > 0.05 * state.fluid_pressure.max()
    v = np.where(pressurised, np.cos(X / (mesh.x.max() - mesh.x.min()) * 7.0) * (1.0 + Y / mesh.length), 0.0)
    eps = 1e-3 * model.contact.sigma
    plus = solver.evaluate(model, state.z, state.delta + eps * v, state.reynolds.cavitated)
    minus = solver.evaluate(model, state.z, state.delta - eps * v, state.reynolds.cavitated)
    assert np.array_equal(plus.reynolds.cavitated, state.reynolds.cavitated)
    assert np.array_equal(minus.reynolds.cavitated, state.reynolds.cavitated)
    finite = (plus.fluid_pressure - minus.fluid_pressure) / (2 * eps)
    exact_state = solver.evaluate(model, state.z, state.delta, state.reynolds.cavitated)
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
    from lubecontact.anderson import AndersonMixer

    monkeypatch.setattr(solver, "deformation_stepper", lambda model: (solver.contact_newton_step, AndersonMixer(beta=1.0)))
    mixed = lc.solve(s)
    assert coupled["converged"].item() == 1 and mixed["converged"].item() == 1
    for name in ("contact_resistance", "friction_coefficient", "separation", "fluid_force"):
        assert coupled[name].item() == pytest.approx(mixed[name].item(), rel=1e-5)
    assert coupled["iterations"].item() <= mixed["iterations"].item()

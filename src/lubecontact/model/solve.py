"""Coupled solve of one operating point (paper section 2.5 and Fig. 1; Eqs. 1-18).

The cylinder sits at height z above the block; the film is h = h_o + z + delta (Eq. 3) with
the undeformed gap h_o of Eq. (4) and the macro deformation delta. Asperities carry the
nominal contact pressure p_c(h) (Eq. 11), the fluid the Reynolds pressure p(h) (Eq. 1),
and both deform the surfaces: delta = K (p + p_c). The cylinder's position balances the
applied force: F = F_cont + F_fluid (Eq. 18).

Algorithm (only the enabled effects are assembled and run):
0. Nested iteration: with asperity contact, the same problem is first solved on the mesh
   with every other node (recursively, loosely), and the fine mesh starts from its
   position, deformation and cavitated zone (``nested_start``).
1. For the current deformation, find z with the force balance satisfied to
   ``tolerance * F``: safeguarded Newton on the total force, whose slope dF/dz comes with
   each evaluation (contact law slope + Reynolds adjoint, ``force_gradient``); bisection
   once bracketed when a step misbehaves (the contact law has a jump at 1.9 omega_c).
2. Recompute the deformation from the pressures at that z and take a Newton step of the
   fixed point delta -> K(p + p_c): with Reynolds fluid pressure between rough surfaces the
   coupled step of newton.py ((I - K P') step = K(p + p_c) - delta, P' the linearised
   contact and fluid pressure with the force balance kept, by GMRES with the Reynolds
   factors and the FFT operator; 3-6 iterations on Table 1 where the contact-only step took
   4-11; near a fold, where full steps cycle between cavitated sets, they are shortened by
   backtracking, newton.Backtracking). Without fluid (or with JFO or no cavitation) the
   step is preconditioned by the contact part of the Jacobian only,
   (I + K D) step = K(p + p_c) - delta with D = -dp_c/dh >= 0 (a Newton step for the dry
   contact), and accelerated by Anderson mixing (also for smooth steady films, where full
   coupled Newton steps overshoot to h <= 0). The next z is predicted to first order from
   the load gradient, so a balance near convergence takes one evaluation. Stop when the
   change is below ``tolerance`` times the deformation's range.
Consecutive Reynolds solves reuse the previous LU factors as a CG preconditioner while the
pressurised set stays (reynolds.BlockInverse). The solve runs with one BLAS thread.
Every solve reports its residuals and a ``converged`` flag; nothing is silently accepted.
The discrete coupled problem can have more than one converged solution at some hard points
(very smooth surfaces on coarse meshes, where the fluid load jumps as the contact edge
crosses nodes; 500 N at 10 m/s, a fluid-lifted and a contact-carried branch): which one a
solve finds then depends on its start (bench/RESULTS.md, "Several solutions").
"""

from __future__ import annotations

import time

from lubecontact.io.case_result import CaseResult
from lubecontact.model.coupling import WarmStart, coupled_solve
from lubecontact.model.model import Model
from lubecontact.model.outputs import point_outputs
from lubecontact.model.prepare import prepare
from lubecontact.model.validity import assess
from lubecontact.numerics.blas_threads import one_blas_thread


def solve(scene, fields: bool = False, initial: WarmStart | None = None, return_state: bool = False):
    """Solve one operating point; returns the case ``xarray.Dataset`` (docs/DESIGN.md outputs),
    with ``return_state`` also the solver's final state (``solve_case``)."""
    result, state = solve_case(scene, fields, initial)
    ds = result.to_dataset()
    return (ds, state) if return_state else ds


def solve_case(scene, fields: bool = False, initial: WarmStart | None = None):
    """Solve one operating point; returns (case_result.CaseResult, the solver's final state).

    ``initial`` (a WarmStart from a previous solution on this mesh) warm-starts the coupling loop (a sweep's continuation);
    a cold start must give the same answer within tolerance.
    """

    start = time.perf_counter()
    requested = scene
    prepared = prepare(scene)
    scene, notes = prepared.scene, list(prepared.notes)
    with one_blas_thread():
        model = Model.assemble(scene, contact=prepared.contact)
        state, diag = coupled_solve(model, initial)
    if diag.failure:
        notes.append("NOT CONVERGED: " + diag.failure)
    outputs, output_notes = point_outputs(model, state)
    notes.extend(output_notes)
    mesh = model.mesh
    validity = assess(scene, mesh, model.contact, state, model.hydrodynamic)
    notes.extend(f"validity {flag}: {note}" for flag, note in validity.items())
    scalars = {
        **outputs,
        "converged": int(diag.converged),
        "iterations": diag.iterations,
        "force_residual": diag.force_residual,
        "deformation_residual": diag.deformation_residual,
        "reynolds_residual": diag.reynolds_residual,
        "solve_time": time.perf_counter() - start,
        "speed": scene.operating.speed,
        "valid": int(not validity),
    }
    field_data = None
    if fields:
        field_data = {
            "fluid_pressure": state.fluid_pressure,
            "contact_pressure": state.contact_pressure,
            "film_thickness": state.film,
            "deformation": state.delta,
        }
        if getattr(state.reynolds, "content", None) is not None:  # effects.cavitation: jfo
            field_data["film_content"] = state.reynolds.content
    result = CaseResult.build(requested, scalars, field_data, mesh, model.effects_run, "; ".join(notes), ",".join(validity) or "ok")
    return result, state

"""Coupled solve of one operating point (paper section 2.5 and Fig. 1; Eqs. 1-18): the
public entry ``solve`` and ``solve_case``.

The cylinder sits at height z above the block; the film is h = h_o + z + delta (Eq. 3) with
the undeformed gap h_o of Eq. (4) and the macro deformation delta. Asperities carry the
nominal contact pressure p_c(h) (Eq. 11), the fluid the Reynolds pressure p(h) (Eq. 1),
and both deform the surfaces: delta = K (p + p_c). The cylinder's position balances the
applied force: F = F_cont + F_fluid (Eq. 18).

A solve prepares the scene (model/prepare.py: ``effects: auto`` decided), assembles only
the sub-models it enables (model/model.py), runs the coupling loop (model/coupling.py)
with one BLAS thread, and reports the outputs (model/outputs.py), the validity flags
(model/validity.py) and whether every stopping test was met: nothing is silently accepted.
"""

from __future__ import annotations

import time

from lubecontact.io.case_result import CaseResult
from lubecontact.model.coupling import WarmStart
from lubecontact.model.grease_start import entrained_film_note
from lubecontact.model.model import Model
from lubecontact.model.monolithic_newton import steady_solve
from lubecontact.model.outputs import point_outputs
from lubecontact.model.prepare import prepare
from lubecontact.model.validity import assess, flag_bits, resolution_note
from lubecontact.numerics.blas_threads import one_blas_thread
from lubecontact.numerics.mesh import describe_mesh

# Why a smooth film on a 2-D mesh most likely failed, said with the failure: the fluid pressure
# is ambient at the cylinder's ends (y = +-L/2), so the ends of an uncrowned cylinder sink less
# than its middle and a film without asperity contact closes there first. Measured on Table 1
# without asperity contact, 51 x 51 (tests/test_hard_cases.py, smooth_default_mesh): the film
# at the ends is 306 / 105 / 20 nm at 1 / 0.5 / 0.3 m/s against 508 / 279 / 171 nm on the line
# contact, and the solve fails from 0.1 m/s down.
SMOOTH_CLOSED = "without asperity contact a film that closes at any node ends the solve"
SMOOTH_ENDS = (f"{SMOOTH_CLOSED}, and on a 2-D mesh an uncrowned cylinder's film is thinnest at its ends "
               "(y = +-L/2, where the fluid pressure is ambient), so it closes there first as the speed falls: turn on "
               "effects.asperity_contact to let the asperities carry the ends, or solve a line contact (mesh.ny: 1)")
# A crowned cylinder (geometry.crown_radius) lifts its ends: where its smooth film still fails
# the cause is elsewhere. Measured on Table 1 crowned at 0.1 m on the automatic 51 x 51 domain
# (sized by the Hertz ellipse, cells of 15 um): cold solves converge down to 0.02 m/s (13 s at
# 0.03, 103 s at 0.02), and at 0.01 m/s the nested force balance closes the film and one Newton
# from a cold start stalls at 0.4 of the load in its continuation, 11 s (tests/test_hard_cases.py,
# smooth_crowned_default_mesh; docs/DESIGN.md "Hard cases"). Refined along the sliding, 81 x 51
# and 101 x 31 converge there (44 and 29 s), central films within 2.5 % of 101 x 51's 20.18 nm.
SMOOTH_CROWNED = (f"{SMOOTH_CLOSED}; this cylinder is crowned, its ends lifted, so the film failed within its "
                  "contact: thinner than the mesh's cells resolve, or beyond the solver at this speed "
                  "(docs/DESIGN.md, \"Hard cases\"): refine the mesh along the sliding (mesh.nx), turn on "
                  "effects.asperity_contact, or solve a line contact (mesh.ny: 1, without the crown)")


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
        state, diag, solver_notes = steady_solve(model, initial)
        notes.extend(solver_notes)
    if diag.failure or not diag.converged:  # never silent: a solve that stopped says why
        notes.append("NOT CONVERGED: " + (diag.failure or f"{diag.iterations} iteration(s) without meeting the "
                                                          f"tolerances (force residual {diag.force_residual:.3g} N, "
                                                          f"deformation change {diag.deformation_residual:.3g} m)"))
        if model.contact is None and model.hydrodynamic and not model.mesh.line:
            notes.append(SMOOTH_ENDS if scene.geometry.crown_radius is None else SMOOTH_CROWNED)
        grease = entrained_film_note(model)
        if grease:
            notes.append(grease)
    outputs, output_notes = point_outputs(model, state)
    notes.extend(output_notes)
    resolution = resolution_note(model, state)
    if resolution:
        notes.append(resolution)
    mesh = model.mesh
    validity = assess(scene, mesh, model.contact, state, model.hydrodynamic)
    # a state that is no solution has its flags too, but they describe where the iteration stopped
    last = "" if diag.converged and not diag.failure else " (of the last iterate, not a solution)"
    notes.extend(f"validity {flag}{last}: {note}" for flag, note in validity.items())
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
        "validity_flags": flag_bits(validity),
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
    # one line per flag, for the CLI and a sweep (notes join everything with "; ")
    return result.with_attrs(validity_notes="\n".join(f"{flag}: {note}" for flag, note in validity.items()),
                             mesh=describe_mesh(mesh, scene.mesh.nx)), state

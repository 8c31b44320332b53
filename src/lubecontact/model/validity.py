"""Where a case leaves the ground its sub-models stand on (docs/DESIGN.md "Validity").

A solved case is checked against the range of each sub-model it used; every breach is a
flag (its name in the case's ``validity`` attribute, ``valid`` = 0) and a note with the
numbers. Nothing is silent, nothing is refused: the paper's own figures leave several of
these grounds at low speed (docs/physics.md sections 9 and 11.6).

Flags:

- ``gw_area``: A_r/A_n above GW_MAX_AREA_FRACTION somewhere. Greenwood-Williamson's
  statistics (and Jackson-Green's asperities in them) treat the asperities as independent;
  their interaction grows with the contact fraction, and the light-contact regime the
  model was built for is usually bounded at about a tenth of the nominal area.
- ``area_capped``: A_r/A_n > 1 at some node (the statistical integral passes the nominal
  area at deep interference); ``real_contact_area`` counts such nodes as fully in contact.
- ``bulk_yield``: peak nominal pressure (fluid + asperities) above the onset of yield
  under a Hertzian line load, p0 = 1.67 S_y (von Mises, Johnson 1985 section 4.2), with
  S_y of the softer body: the bodies are modelled elastic on the macro scale.
- ``bandwidth``: Nayak's bandwidth alpha < 2. For a Gaussian isotropic surface
  eta R_peak sigma = 0.020358 sqrt(alpha) (McCool 1986; docs/physics.md section 18), so the
  scene's eta, R_peak, sigma imply alpha; below 2 the summit statistics of GW have no
  surface behind them (the CLI warns on loading such a scene: ``scene_warnings``).
- ``flow_factor_range``: h/sigma < 0.5 where the fluid is pressurised: Patir-Cheng's flow
  factors (Eq. 2) are fitted for h/sigma > 0.5.
- ``inlet``: the inlet is too short for the film: a rigid cylinder's film with the inlet at
  X = x_min / sqrt(2 R h) is INLET_FILM_DEFICIT or more below the fully flooded one
  (:func:`lubecontact.physics.inlet.inlet_film_fraction`, h the thinnest fluid gap). The
  inlet is upstream of the sliding: at x_max where U < 0 (the return stroke of an
  oscillation, on an explicit domain; on the automatic one its steps go on the mirrored mesh,
  whose inlet is there). On a mesh open to the far inlet (numerics/far_inlet.py,
  numerics/modal_far_inlet.py) the same test at X = 0.9 R / sqrt(2 R h): a film that needs
  lubricant from beyond 0.9 R rests on the exterior's gap there (a line's parabola to -inf, a
  2-D mesh's exterior stops at 0.9 R), where the cylinder and the lubrication approximation
  part ways.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from lubecontact.io.case_schema import VALIDITY_FLAGS
from lubecontact.numerics.mesh import MAX_DOMAIN_RADII, far_inlet_problems
from lubecontact.physics.inlet import inlet_film_fraction
from lubecontact.physics.viscosity_temperature import DATASHEET_TEMPERATURES
from lubecontact.scene.unread_keys import unread_motion_keys_note

GW_MAX_AREA_FRACTION = 0.1
LINE_YIELD_ONSET = 1.67  # p0/S_y at first yield under a Hertzian line load (von Mises, nu = 0.3)
BANDWIDTH_CONSTANT = 0.020358  # eta R_peak sigma / sqrt(alpha), Gaussian isotropic surface
MIN_BANDWIDTH = 2.0
MIN_FLOW_FACTOR_FILM = 0.5  # h/sigma where Patir-Cheng's fits begin
INLET_FILM_DEFICIT = 0.01
# resolution_note: about 1 % of a smooth rigid film (Martin's line: 0.8 % at 16.1 cells)
PRESSURE_WIDTH_CELLS = 16.0


def bandwidth(roughness) -> float:
    """Nayak's alpha implied by eta R_peak sigma = 0.020358 sqrt(alpha)."""
    return (roughness.asperity_density * roughness.asperity_radius * roughness.sigma / BANDWIDTH_CONSTANT) ** 2


def bandwidth_note(roughness) -> str | None:
    """The statement about alpha < 2, naming the keys, or None."""
    alpha = bandwidth(roughness)
    if alpha >= MIN_BANDWIDTH:
        return None
    return (f"roughness.sigma = {roughness.sigma:g} m with roughness.asperity_density = "
            f"{roughness.asperity_density:g} 1/m^2 and roughness.asperity_radius = {roughness.asperity_radius:g} m: "
            f"eta R sigma = {roughness.asperity_density * roughness.asperity_radius * roughness.sigma:.3g} implies "
            f"bandwidth alpha = {alpha:.3g} < {MIN_BANDWIDTH:g} (eta R sigma = 0.020358 sqrt(alpha)): no Gaussian "
            f"surface has these summits; GW statistics are outside their ground")


def summit_radius_note(scene) -> str | None:
    """The statement that the asperities' summit radius is not smaller than the cylinder
    they sit on, or None: no rough surface has such summits (a measured surface whose height
    unit is wrong by a factor 10^6 gave R_peak = 115 m on a 10 mm cylinder, without a word)."""
    radius, summit = scene.geometry.radius, scene.roughness.asperity_radius
    if summit < radius:
        return None
    return (f"roughness.asperity_radius = {summit:g} m is not smaller than the cylinder's radius geometry.radius = "
            f"{radius:g} m: summits larger than the body they sit on (check the units of the surface or of the key)")


def flag_bits(flags) -> int:
    """The ``validity_flags`` bit field of the flags raised (io/case_schema.VALIDITY_FLAGS)."""
    unknown = set(flags) - set(VALIDITY_FLAGS)
    if unknown:
        raise ValueError(f"validity flags {sorted(unknown)} have no bit in io/case_schema.VALIDITY_FLAGS")
    return sum(1 << VALIDITY_FLAGS.index(flag) for flag in flags)


def cold_extrapolation_note(scene) -> str | None:
    """The statement that a datasheet oil's viscosity is extrapolated below its first
    datasheet temperature with no pour point given, or None: ASTM D341's line holds only
    above the pour point, below which the oil is no Newtonian fluid (a VG 32 datasheet oil at
    -60 C solved as a contact floating on 25 um of oil, without a word)."""
    lubricant, temperature = scene.lubricant, scene.operating.temperature
    if temperature is None or lubricant.kinematic_viscosity_40 is None or lubricant.pour_point is not None:
        return None
    if temperature >= DATASHEET_TEMPERATURES[0]:
        return None
    return (f"operating.temperature = {temperature:g} C is below the datasheet's {DATASHEET_TEMPERATURES[0]:g} C and "
            f"lubricant.pour_point is not given: the viscosity ({lubricant.viscosity:.3g} Pa s) is ASTM D341's "
            "extrapolation, which holds only above the oil's pour point; give lubricant.pour_point to have it checked")


def scene_warnings(scene) -> list[str]:
    """What is wrong with a valid scene without making it unusable (printed by the CLI)."""
    return [note for note in (bandwidth_note(scene.roughness), summit_radius_note(scene),
                              cold_extrapolation_note(scene), unread_motion_keys_note(scene)) if note]


def share(weight: np.ndarray, where: np.ndarray) -> float:
    """Fraction of sum(weight) at the nodes ``where`` (0 when the total is 0)."""
    total = float(np.sum(weight))
    return float(np.sum(weight[where])) / total if total > 0.0 else 0.0


def conductance_share(log_conductance: np.ndarray, nodal_area: np.ndarray, where: np.ndarray) -> float:
    """Fraction of the spots' conductance sum(g dA) at the nodes ``where``, from log g (the
    nodes conduct in parallel, docs/physics.md section 8; g itself may underflow)."""
    log_weight = log_conductance + np.log(nodal_area)
    if not np.isfinite(log_weight).any():
        return 0.0
    return share(np.exp(log_weight - np.max(log_weight)), where)


def resolution_note(model, state) -> str | None:
    """Where a smooth rigid film's pressure spans fewer than PRESSURE_WIDTH_CELLS cells along
    x: a note with the width and the mesh.nx that would resolve it, else None (a film held up
    by asperities or by the bodies' deformation spreads its pressure over their contact).

    The width is the pressure's load over its peak along the row that carries most,
    int p dx / max p (Martin's cylinder: 1.609 sqrt(2 R h0), docs/physics.md section 4). The
    film is that zone's: on the rigid smooth line at 0.1 m/s (Martin's 4.9 nm), the film came
    out 63 % thin at 2.2 cells, 9.9 % at 3.9, 2.9 % at 8.0 and 0.8 % at 16.1
    (tests/test_validity.py); a Herschel-Bulkley grease's 19 nm line likewise."""
    scene, mesh = model.scene, model.mesh
    if not model.hydrodynamic or model.contact is not None or model.deformation is not None:
        return None
    pressure = np.asarray(state.fluid_pressure).reshape(mesh.shape)
    loads = np.trapezoid(pressure, mesh.x, axis=1)
    row = int(np.argmax(loads))
    peak = float(np.max(pressure[row]))
    if not peak > 0.0:
        return None
    width = float(loads[row]) / peak
    cells = width / mesh.dx
    if cells >= PRESSURE_WIDTH_CELLS:
        return None
    needed = int(np.ceil((scene.mesh.nx - 1) * PRESSURE_WIDTH_CELLS / cells)) + 1
    return (f"the fluid pressure's width (its load over its peak, {width:.3g} m) spans only {cells:.3g} cells of "
            f"{mesh.dx:.3g} m: a smooth rigid film is as thin as that zone, and a rigid line's came out 10 % thin "
            f"at 4 cells, 3 % at 8 and 1 % at 16 (docs/physics.md section 4); use mesh.nx of at least {needed}, or a "
            f"shorter domain (mesh.x_min, mesh.x_max)")


def assess(scene, mesh, contact, state, hydrodynamic: bool) -> dict[str, str]:
    """flag -> note for every ground the solved ``state`` leaves (empty when none). Each note
    says by how much and what rests on the nodes beyond the bound (their share of the load
    or of the conductance), so a breach at a few edge nodes reads differently from one
    under the whole contact (docs/DESIGN.md "Validity")."""
    flags = {}
    area = mesh.nodal_area
    note = bandwidth_note(scene.roughness) if contact is not None else None
    if note:
        flags["bandwidth"] = note
    if contact is not None:
        fraction = contact.area_fraction(state.film)
        peak = float(fraction.max())
        if peak > GW_MAX_AREA_FRACTION:
            beyond = fraction > GW_MAX_AREA_FRACTION
            flags["gw_area"] = (
                f"A_r/A_n up to {peak:.3g} > {GW_MAX_AREA_FRACTION:g}: beyond the light contact of independent "
                f"asperities (GW), and those nodes carry {100 * share(state.contact_pressure * area, beyond):.3g} % of "
                f"the asperity load and {100 * conductance_share(contact.log_conductance(state.film), area, beyond):.3g} "
                f"% of the spots' conductance")
        if peak > 1.0:
            flags["area_capped"] = (f"A_r/A_n > 1 at {int((fraction > 1.0).sum())} nodes (up to {peak:.3g}): "
                                    f"counted as full contact in real_contact_area")
    yield_strength = min(scene.cylinder.yield_strength, scene.block.yield_strength)
    nominal = state.contact_pressure + state.fluid_pressure
    pressure = float(np.max(nominal))
    onset = LINE_YIELD_ONSET * yield_strength
    if pressure > onset:
        flags["bulk_yield"] = (
            f"peak nominal pressure {pressure:.3g} Pa = {pressure / onset:.3g} x the onset of bulk yield "
            f"{LINE_YIELD_ONSET:g} S_y = {onset:.3g} Pa, over nodes carrying {100 * share(nominal * area, nominal > onset):.3g} "
            f"% of the load: the bodies are modelled elastic")
    if hydrodynamic and contact is not None and scene.effects.flow_factors:
        wet = state.fluid_pressure > 0.0
        if wet.any():
            lowest = float(np.min(state.film[wet])) / contact.sigma
            if lowest < MIN_FLOW_FACTOR_FILM:
                thin = wet & (state.film < MIN_FLOW_FACTOR_FILM * contact.sigma)
                flags["flow_factor_range"] = (
                    f"h/sigma down to {lowest:.3g} < {MIN_FLOW_FACTOR_FILM:g} where the fluid is pressurised: below "
                    f"Patir-Cheng's fitted range the pressure flow is the percolation interpolation to zero at "
                    f"h = 0 (docs/physics.md section 15), and those nodes carry "
                    f"{100 * share(state.fluid_pressure * area, thin):.3g} % of the fluid load")
    # at rest nothing is entrained: no inlet to starve
    if hydrodynamic and scene.operating.speed != 0.0:
        gap = state.expected_gap if state.expected_gap is not None else state.film
        thinnest = float(np.min(gap))
        end, key, node = (("x_max", "mesh.x_max: the sliding reverses", -1) if scene.operating.speed < 0.0
                          else ("x_min", "mesh.x_min", 0))
        scale = math.sqrt(2.0 * scene.geometry.radius * thinnest)
        # on an open mesh, the film upstream up to where the exterior's gap leaves the cylinder's ground
        inlet = (MAX_DOMAIN_RADII * scene.geometry.radius if mesh.far_inlet else abs(float(mesh.x[node]))) / scale
        fraction = inlet_film_fraction(inlet)
        if 1.0 - fraction >= INLET_FILM_DEFICIT:
            if mesh.far_inlet:
                flags["inlet"] = (
                    f"the flooded film needs lubricant from beyond {MAX_DOMAIN_RADII:g} R (X = {MAX_DOMAIN_RADII:g} "
                    f"R/sqrt(2 R h) = {inlet:.3g}, h = {thinnest:.3g} m: a rigid film with p = 0 there would be "
                    f"{fraction:.3g} of the flooded one), where "
                    + ("the far inlet takes Martin's parabola to -inf, a gap the cylinder does not have" if mesh.line
                       else "the far inlet stops, at p = 0 (beyond it Eq. 4 leaves the lubrication approximation)")
                    + ": the film is uncertain by about that much; a larger radius, or a thinner film, is within "
                      "the model")
            else:
                flags["inlet"] = (f"inlet at X = {end}/sqrt(2 R h) = {inlet:.3g} (h = {thinnest:.3g} m): a rigid film "
                                  f"would be {fraction:.3g} of the fully flooded one; lengthen the domain ({key})"
                                  + far_inlet_advice(scene))
    return flags


def far_inlet_advice(scene) -> str:
    """What the flag ``inlet`` adds where the scene turned off the far inlet that would fit it
    (mesh.far_inlet: false on a steady contact on the automatic domain:
    numerics/mesh.far_inlet_problems), else "": by default (auto) a scene whose long inlet
    falls short already has it."""
    if scene.mesh.far_inlet is not False or far_inlet_problems(replace(scene, mesh=replace(scene.mesh, far_inlet=True))):
        return ""
    return (", or leave mesh.far_inlet at auto (the rigid film upstream as the boundary condition, docs/physics.md "
            "section 17)")

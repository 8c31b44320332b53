"""A rigid smooth cylinder stopped on a Bingham film (docs/physics.md section 21) against the
closed form of where a squeeze stops: the yield stress alone carries the load at
h_stop = a^2/(2R(exp(F/(4 L R tau_y)) - 1)) (physics/yield_stress_flow.bingham_squeeze_stop_film,
itself tested against a quadrature), and the creep of the bi-viscous regularisation that
the run's notes report; the grease figure's grease that never touches (config/transient.yaml)."""

import math
import re

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.physics.yield_stress_flow import bingham_squeeze_stop_film
from lubecontact.plotting.transient import FULL_FILM_RATIO, closed_form_stop_film, film_at_stop
from lubecontact.studies import transient_cases as study

TABLE1 = "config/scenes/table1.yaml"
FORCE, YIELD_STRESS, HALF_DOMAIN = 0.2, 1000.0, 1e-3  # N, Pa, m: F/(4 L R tau_y) = 5, h_stop = 0.34 um
# Table 1's cylinder (R = 10 mm, L = 1 mm) rigid and smooth, sliding at 1 m/s on a Bingham
# film (plastic viscosity 0.1 Pa s), stopped over 0.1 ms and left at rest for 10 s; a line
# of 101 nodes (more, and the steady start at 1 m/s stalls: docs/physics.md section 21)
STOP = {"operating.speed": 1.0, "operating.force": FORCE, "motion.kind": "stop", "motion.ramp": 1e-4,
        "motion.duration": 10.0, "effects.asperity_contact": False, "effects.elastic_deformation": False,
        "mesh.ny": 1, "mesh.nx": 101, "mesh.x_min": -HALF_DOMAIN, "mesh.x_max": HALF_DOMAIN,
        "lubricant.rheology": "bingham", "lubricant.yield_stress": YIELD_STRESS}


def stopped(creep_viscosity):
    scene = lc.load_scene(TABLE1, {**STOP, "lubricant.creep_viscosity": creep_viscosity})
    series = lc.transient(scene, progress=False)
    assert series["converged"].item() == 1, series.attrs["notes"]
    h_stop = bingham_squeeze_stop_film(FORCE, scene.geometry.length, scene.geometry.radius, HALF_DOMAIN, YIELD_STRESS)
    return series, series["min_film_thickness"].values / h_stop


def creep_share(notes: str) -> float:
    return float(re.search(r"over the \S+ s simulated, (\S+) of the smallest film", notes).group(1))


def test_a_bingham_squeeze_stops_where_the_yield_stress_carries_the_load():
    series, ratio = stopped(1e8)  # creep viscosity high enough for creep to be negligible over 10 s
    t = series["time"].values
    assert ratio[np.searchsorted(t, 0.5)] > 1.1  # still squeezing out half a second after the stop
    assert ratio[-1] == pytest.approx(1.0, abs=0.01)  # 10 s later: stopped at h_stop (0.997 measured)
    assert creep_share(series.attrs["notes"]) < 0.01 and "not negligible" not in series.attrs["notes"]
    # each step's face-flux volume balance, the faces' fluxes from the law (series.volume_balance):
    # 2.0e-6 measured; 1.4e4 with the Newtonian face fluxes (until the thirty-ninth session)
    assert np.max(np.abs(series["volume_balance"].values)) < 1e-3


def test_the_default_creep_is_reported_where_it_drains_the_film():
    # at the default creep viscosity the plug creeps through the thick film at the domain's
    # ends: the film sinks far below h_stop (0.65 of it after 10 s, measured), and the notes say so
    series, ratio = stopped(lc.load_scene(TABLE1).lubricant.creep_viscosity)
    assert ratio[-1] < 0.8
    assert creep_share(series.attrs["notes"]) > 1.0 - ratio[-1] and "not negligible" in series.attrs["notes"]


# The grease figure of the transient study (config/transient.yaml figures.grease): Table 1's
# rough elastic contact as a 101-node line at 0.5 N, stopped from 1 m/s. Its grease whose
# closed-form stop film lies in the full film (above FULL_FILM_RATIO sigma) and below the film
# the stop leaves must settle there, its asperities apart and its contact open throughout.
def grease_figure_cases():
    spec = study.study_spec("config/transient.yaml")
    cases = study.figure_cases(spec)["grease"]
    overrides = study.case_overrides(spec, {"grease": cases})
    return [lc.load_scene(spec["base"], overrides[case["id"]]) for case in cases]


def full_film_stop(scene):
    """The closed-form stop film of ``scene`` if it lies in the full film, else None."""
    if scene.lubricant.rheology != "bingham":
        return None
    h_stop = bingham_squeeze_stop_film(scene.operating.force, scene.geometry.length, scene.geometry.radius,
                                       scene.mesh.x_max, scene.lubricant.yield_stress)
    return h_stop if h_stop >= FULL_FILM_RATIO * scene.roughness.sigma else None


def test_the_stiffest_grease_of_the_figure_never_touches_and_stops_at_the_closed_form_film():
    never, = [s for s in grease_figure_cases() if full_film_stop(s) is not None]  # the 5 kPa grease
    h_stop = full_film_stop(never)
    series = lc.transient(never, progress=False)
    assert series["converged"].item() == 1, series.attrs["notes"]
    t, film = series["time"].values, series["min_film_thickness"].values
    rest = never.motion.stop_time + never.motion.ramp
    assert closed_form_stop_film(never, film_at_stop(series)) == h_stop  # the figure draws it
    assert film_at_stop(series) > 1.2 * h_stop  # it squeezes down to it ...
    error = abs(film[-1] / h_stop - 1)
    assert error < 0.005  # ... and settles there 30 s after the stop (0.9995 measured, creep < 0.02 %)
    resistance = series["contact_resistance"].values[t >= rest]
    assert np.all(resistance > series["open_resistance"].item())  # open throughout (1e11 ohm at the end)
    assert math.isinf(series["reconnect_time"].item()) and series["contact_force"].values[-1] < 1e-9 * never.operating.force
    assert "not negligible" not in series.attrs["notes"]
    # the stop film is the discrete one's limit: on 21 nodes (100 um apart) the film settles
    # 1.6 % below it, 33 times the 101 nodes' error (second order: 25)
    coarse = lc.transient(lc.load_scene(never, {"mesh.nx": 21, "motion.duration": 10.0}), progress=False)
    assert coarse["converged"].item() == 1
    assert abs(coarse["min_film_thickness"].values[-1] / h_stop - 1) > 10 * error

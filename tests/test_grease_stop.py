"""A rigid smooth cylinder stopped on a Bingham film (docs/physics.md section 21) against the
closed form of where a squeeze stops: the yield stress alone carries the load at
h_stop = a^2/(2R(exp(F/(4 L R tau_y)) - 1)) (physics/yield_stress_flow.bingham_squeeze_stop_film,
itself tested against a quadrature), and the creep of the bi-viscous regularisation that
the run's notes report."""

import re

import numpy as np
import pytest

import lubecontact as lc
from lubecontact.physics.yield_stress_flow import bingham_squeeze_stop_film

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


def test_the_default_creep_is_reported_where_it_drains_the_film():
    # at the default creep viscosity the plug creeps through the thick film at the domain's
    # ends: the film sinks far below h_stop (0.65 of it after 10 s, measured), and the notes say so
    series, ratio = stopped(lc.load_scene(TABLE1).lubricant.creep_viscosity)
    assert ratio[-1] < 0.8
    assert creep_share(series.attrs["notes"]) > 1.0 - ratio[-1] and "not negligible" in series.attrs["notes"]

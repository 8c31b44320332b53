"""Where a smooth grease film's Newton starts from (docs/physics.md section 21, "Its cold start").

A cold start of a smooth film takes the rigid (or isoviscous-elastic) film estimate of its
lubricant and that film's Reynolds pressure (monolithic_newton.cold_start). A grease has no
single viscosity: taken at its consistency K, a shear-thinning grease's start was a hundred
times too thick (a Herschel-Bulkley line, n = 0.7, K = 0.5 Pa s^n, tau_y = 300 Pa at 1 m/s:
2.4 um against the 19 nm a shooting solution of the line gives), and its pressure, the
Newtonian one of that film at K, about 250 times the load: the Newton found no descent, even
started from the right film.

The start is instead that of a Newtonian stand-in at the grease's flowing viscosity, the
apparent viscosity at the Couette shear rate of the film it predicts
(physics/yield_stress_flow.flowing_viscosity, with the cold start's own film estimate). It is
a start, not an answer: on the line above it gives a 9.6 nm film, from which the Newton
converges to the shooting film (tests/test_yield_stress_reynolds.py).
"""

from __future__ import annotations

import dataclasses

from lubecontact.model.auto_effects import operating_point
from lubecontact.model.fluid_film import yield_stress_law
from lubecontact.model.model import Model
from lubecontact.physics.film_estimates import entrained_film, martin_film
from lubecontact.physics.yield_stress_flow import flowing_viscosity


def start_film(scene, elastic: bool) -> float:
    """The film (m) a smooth cold start takes: the isoviscous-elastic estimate on deforming
    bodies, else the rigid cylinder's on the scene's domain (auto_effects.operating_point)."""
    estimate = operating_point(scene)
    return estimate.elastic_film if elastic else estimate.film


def with_viscosity(scene, viscosity: float):
    """The scene with a Newtonian lubricant of ``viscosity`` (Pa s) in place of its own (the
    grease's keys left as they are: a Newtonian rheology reads none of them)."""
    lubricant = dataclasses.replace(scene.lubricant, rheology="newtonian", viscosity=float(viscosity))
    return dataclasses.replace(scene, lubricant=lubricant)


def newtonian_stand_in(model: Model) -> Model:
    """The model with its grease replaced by the Newtonian lubricant of its flowing viscosity
    (module docstring); a Newtonian model, one at rest (no shear rate to take) or one with no
    flowing viscosity as it is."""
    law = yield_stress_law(model)
    speed = model.scene.operating.speed
    if law is None or speed == 0.0:
        return model
    elastic = model.deformation is not None
    viscosity = flowing_viscosity(lambda mu: start_film(with_viscosity(model.scene, mu), elastic), speed, law)
    if viscosity is None:
        return model
    return dataclasses.replace(model, scene=with_viscosity(model.scene, viscosity))


def entrained_film_note(model: Model) -> str | None:
    """For a smooth grease film, the film its own law entrains (film_estimates.entrained_film,
    Martin's at the flowing viscosity) in words, said where its solve failed: a strongly
    shear-thinning law can put it far below any film a continuum carries (Herschel-Bulkley,
    n = 0.3, K = 0.5 Pa s^n on Table 1's rigid line at 1 m/s: about 1e-19 m), which no mesh
    or path reaches; None for a Newtonian or rough film, or at rest."""
    scene = model.scene
    if yield_stress_law(model) is None or model.contact is not None or scene.operating.speed == 0.0:
        return None
    film = entrained_film(scene)
    viscosity = film / martin_film(scene) * scene.lubricant.viscosity
    return (f"the grease's own rigid film estimate is {film:.3g} m (Martin's film at its flowing viscosity, "
            f"{viscosity:.3g} Pa s at the shear rate {abs(scene.operating.speed) / film:.3g} 1/s, docs/physics.md "
            f"section 21): a film or a shear rate far from those its law was measured at says the law, not the "
            f"solver, has left its ground")

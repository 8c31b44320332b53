"""A figure grid's curves as continuation cases: each curve (the speeds of one parameter
combination) solved speeding up and slowing down (``lubecontact.sweep``, direction "both"),
where a contact can have two steady states (docs/physics.md section 23).

The figure build solves every point of a grid cold and on its own (figure_grids): one
branch wherever two coexist. These cases follow each branch instead, a whole curve a case,
one file each, identified by the curve's scene and speeds.
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping

from lubecontact.scene import load_scene
from lubecontact.studies.figure_grids import SPEED_KEY, FigureGrid, value_text
from lubecontact.studies.transient_cases import key_units, key_words

ID_DIGITS = 16  # hex digits of a curve's id, as a scene hash


def curve_cases(grid: FigureGrid, root=".") -> list[dict]:
    """One case per curve of ``grid``: {"id", "scene", "set", "speeds", "label"}, ``set`` the
    curve's overrides of its scene file without the speed, ``speeds`` ascending (m/s),
    ``label`` its swept values in words and ``id`` a digest of its scene's hash and speeds:
    an edit of one curve's scene or speeds renames that curve's case only."""
    cases = []
    for index, members in grid.curves():
        overrides = {k: v for k, v in members[0].set.items() if k != SPEED_KEY}
        speeds = sorted(float(c.set[SPEED_KEY]) for c in members)
        scene = load_scene(f"{root}/{members[0].scene}", overrides)
        digest = hashlib.sha256(f"{scene.hash} {speeds!r}".encode()).hexdigest()[:ID_DIGITS]
        cases.append({"id": digest, "scene": members[0].scene, "set": overrides, "speeds": speeds,
                      "label": curve_label(grid, index)})
    return cases


def curve_label(grid: FigureGrid, index: tuple[int, ...]) -> str:
    """The swept values of the curve at ``index`` in words with units, e.g. 'normal force on the cylinder F = 20 N'."""
    parts = []
    for dim, i in zip(grid.dims[:-1], index):
        for key, value in zip(dim.keys, dim.values[i]):
            unit = key_units(key)
            parts.append(f"{key_words(key)} = {value_text(value)}{'' if unit == '1' else f' {unit}'}")
    return ", ".join(parts) or "the base scene"


def study_problems(names, grids: Mapping[str, FigureGrid]) -> list[str]:
    """One message per name of config ``hysteresis`` that is not a figure grid of the run."""
    return [f"hysteresis: {name} is not among the figures of this config ({', '.join(grids)})"
            for name in names if name not in grids]

"""Smooth joins of two laws (docs/physics.md section 20).

A law whose slope jumps (a floor) is a corner that Newton's method crosses badly: its
linear model is wrong on one side, and an iteration that sits at the corner stalls. A join
here replaces the corner by a smooth piece over a stated width; how far the width moves an
answer is measured where it is used.
"""

from __future__ import annotations

import numpy as np


def smooth_floor(value, floor: float):
    """(v, dv/dvalue): max(value, floor) joined smoothly over a width ``floor`` (> 0),
    v = (value + floor + sqrt((value - floor)^2 + floor^2)) / 2: v > floor everywhere,
    v - max(value, floor) in (0, floor/2], largest where value = floor and falling as
    floor^2 / (4 |value - floor|) away from it."""
    value = np.asarray(value, dtype=float)
    root = np.sqrt((value - floor) ** 2 + floor**2)
    return 0.5 * (value + floor + root), 0.5 * (1.0 + (value - floor) / root)

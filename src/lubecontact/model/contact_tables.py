"""The rough-contact law of a scene (physics/rough_surface.RoughContact), built once per
roughness, materials and plasticity and kept for the next solve: a speed sweep or a
transient reuses the tables instead of rebuilding them (10-20 ms each). The same small
memo keeps the speed-independent estimates of model/auto_effects.py.
"""

from __future__ import annotations

from lubecontact.physics.rough_surface import RoughContact

_MEMO: dict = {}  # speed-independent results by what they depend on: a speed sweep reuses them


_MEMO_SIZE = 16


def memoised(key, build):
    if key not in _MEMO:
        if len(_MEMO) >= _MEMO_SIZE:
            _MEMO.pop(next(iter(_MEMO)))  # the oldest
        _MEMO[key] = build()
    return _MEMO[key]


def contact_table(scene):
    """RoughContact.from_scene(scene), cached on the sections it is built from."""
    key = ("table", scene.roughness, scene.cylinder, scene.block, scene.effects.plasticity)
    return memoised(key, lambda: RoughContact.from_scene(scene))

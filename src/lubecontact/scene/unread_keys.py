"""Motion keys a scene sets that its motion does not read (docs/DESIGN.md "Scene schema").

A scene may carry keys of another motion kind (an oscillation's frequency on a stop) or of
another excitation: they are valid, enter the case's hash, and change nothing. The CLI says
so on loading (model/validity.scene_warnings), rather than leave a user to wonder why a key
did not move the result.
"""

from __future__ import annotations

from lubecontact.scene.scene import Motion

# motion key -> the motion kinds that read it
KIND_KEYS = {
    "speed": ("stop", "start"),
    "stop_time": ("stop",),
    "ramp": ("stop", "start"),
    "amplitude": ("oscillation",),
    "frequency": ("oscillation",),
    "cycles": ("oscillation",),
}
# motion key -> the base excitations (motion.vibration) that read it
VIBRATION_KEYS = {
    "vibration_frequency": ("sine", "sine_sweep", "random"),
    "vibration_frequency_end": ("sine_sweep", "random"),
    "vibration_seed": ("random",),
    "shock_duration": ("half_sine_shock",),
}


def unread_motion_keys(scene) -> list[str]:
    """The motion keys set away from their defaults that this scene's motion does not read,
    each with what would read it."""
    motion = scene.motion

    def changed(key: str) -> bool:
        return getattr(motion, key) != getattr(Motion, key)

    unread = [f"motion.{key} (read by motion.kind {' or '.join(kinds)})"
              for key, kinds in KIND_KEYS.items() if motion.kind not in kinds and changed(key)]
    unread += [f"motion.{key} (read by motion.vibration {' or '.join(kinds)})"
               for key, kinds in VIBRATION_KEYS.items() if motion.vibration not in kinds and changed(key)]
    if scene.mesh.x_min is not None and changed("rest_refinement"):
        unread.append("motion.rest_refinement (read on the automatic domain only: with mesh.x_min and mesh.x_max "
                      "the steps keep the scene's mesh at rest)")
    return unread


def unread_motion_keys_note(scene) -> str | None:
    """The warning that names unread_motion_keys, or None where there are none."""
    unread = unread_motion_keys(scene)
    if not unread:
        return None
    return (f"motion.kind = {scene.motion.kind} with motion.vibration = {scene.motion.vibration} does not read "
            f"{'; '.join(unread)}: set there, a key changes the case's hash, not its result")

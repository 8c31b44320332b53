"""Reconnect times of the Table 1 contact after a stop from 1 m/s (ramp 1 ms), 51^2 nodes:
the oil and grease scenes of config/scenes and the conditions that make the wait long.

    PYTHONPATH=src python bench/reconnect_times.py
"""

import time

import lubecontact as lc

CASES = [
    ("Table 1, 0.1 Pa s oil", "config/scenes/table1.yaml", {"motion.kind": "stop", "motion.speed": 1.0}),
    ("ISO VG 100 mineral oil, 0.087 Pa s", "config/scenes/stop_hydrocarbon_oil.yaml", {}),
    ("grease-like, 10 Pa s", "config/scenes/stop_grease.yaml", {}),
    ("grease-like, 10 Pa s, F = 1 N", "config/scenes/stop_grease.yaml", {"operating.force": 1.0}),
    ("grease-like, 10 Pa s, R = 50 mm", "config/scenes/stop_grease.yaml", {"geometry.radius": 0.05}),
    # at 51^2 this one takes minutes (ms steps at ~0.5 s each near contact): line mode
    ("grease-like, 10 Pa s, sigma = 0.1 um, line", "config/scenes/stop_grease.yaml", {"roughness.sigma": 0.1e-6, "mesh.ny": 1}),
    ("100 Pa s (grease near rest)", "config/scenes/stop_grease.yaml", {"lubricant.viscosity": 100.0}),
]

if __name__ == "__main__":
    for label, path, overrides in CASES:
        scene = lc.load_scene(path, {"motion.duration": 1000.0, **overrides})
        cpu = time.process_time()
        ds = lc.transient(scene, progress=False)
        print(f"{label:40s} reconnect_time {ds['reconnect_time'].item():10.4g} s   film at 1 m/s "
              f"{ds['min_film_thickness'].values[0] * 1e6:6.3f} um   R sliding {ds['contact_resistance'].values[0]:.3g} ohm, "
              f"at rest {ds['rest_resistance'].item():.3g} ohm   {ds['steps'].item()} steps, "
              f"{time.process_time() - cpu:.1f} s CPU, converged {ds['converged'].item()}", flush=True)

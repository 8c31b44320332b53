"""Time (unsteady model): the lubricated contact after its motion changes (docs/DESIGN.md
"Time"; docs/physics.md sections 14-16).

motion.py (U(t) of the scene's ``motion:`` and the checks a motion makes of its scene),
integrator.py (adaptive BDF2 with the squeeze term in the Reynolds equation, a coupled
solve per step), series.py (the Dataset along ``time``, reconnect_time, oscillation
metrics), events.py (discontinuity events, edges on the integrator's dense output),
transient.py (``transient(scene)``, the public entry).
"""

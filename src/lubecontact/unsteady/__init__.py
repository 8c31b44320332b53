"""Time (unsteady model): the lubricated contact after its motion changes (DESIGN.md Part II; physics.md 14-16).

motion.py (U(t) of the scene's ``motion:``), integrator.py (adaptive BDF2 with the squeeze
term in the Reynolds equation, a coupled solve per step), series.py (the Dataset along
``time``, reconnect_time, oscillation metrics), api.py (``transient(scene)``).
"""

from .api import transient

__all__ = ["transient"]

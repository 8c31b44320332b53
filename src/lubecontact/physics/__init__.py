"""The sub-models, one law a module, each a function of the film or the scene and free
of any mesh solver: the asperity and rough-surface contact laws, the flow and shear
factors, percolation, friction, elastic deformation, closed-form film estimates, the
inlet law and the electrical path (docs/physics.md)."""

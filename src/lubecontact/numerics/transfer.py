"""Transfer between meshes: the mesh with every other node, bilinear interpolation of a
nodal field from one mesh to another over the same domain (nested iteration of the Reynolds
solve and of the coupled solve, warm starts of a sweep), and cubic-spline interpolation
along x onto a mesh within the domain (a transient's levels onto its mesh at rest).
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import CubicSpline

from lubecontact.numerics.mesh import Mesh


def coarser_mesh(mesh, coarsest: int):
    """The mesh with every other node (same domain) in each direction longer than
    ``coarsest`` nodes, or None when no direction is."""
    def halve(nodes):
        if nodes.size <= coarsest:
            return nodes
        return np.linspace(nodes[0], nodes[-1], (nodes.size + 1) // 2)

    if mesh.nx <= coarsest and (mesh.line or mesh.ny <= coarsest):
        return None
    return Mesh(x=halve(mesh.x), y=mesh.y if mesh.line else halve(mesh.y), length=mesh.length, far_inlet=mesh.far_inlet)


def interpolate_field(field, source, target):
    """Bilinear interpolation of a (ny, nx) field between meshes over the same domain."""
    def along(values, nodes_from, nodes_to, axis):
        if nodes_from.size == 1:
            return values
        i = np.clip(np.searchsorted(nodes_from, nodes_to, side="right") - 1, 0, nodes_from.size - 2)
        t = np.clip((nodes_to - nodes_from[i]) / (nodes_from[i + 1] - nodes_from[i]), 0.0, 1.0)
        shape = (-1, 1) if axis == 0 else (1, -1)
        lower, upper = np.take(values, i, axis=axis), np.take(values, i + 1, axis=axis)
        return lower + t.reshape(shape) * (upper - lower)

    return along(along(field, source.x, target.x, 1), source.y, target.y, 0)


def spline_along_x(field, source, target):
    """A (ny, nx) field on ``source`` at the nodes of ``target``, whose rows are those of
    ``source``: the not-a-knot cubic spline through each row (exact for cubics; error O(dx^4)
    for a smooth field, where bilinear interpolation's is O(dx^2)). For the elastic
    deformation, whose curvature reaches ~1/R over the contact, where linear interpolation
    would leave film errors of up to dx^2/8R (12 nm on the Table 1 contact's 51-node mesh,
    dx = 32 um, R = 10 mm), beyond a time step's error weight. Beyond ``source``'s domain
    (the inlet of a mirrored mesh, numerics/mesh.mirrored_mesh) the value at its edge, as
    bilinear interpolation holds it: a cubic carried that far diverges, and there the
    deformation varies as slowly as ln|x| (a line load's) under a gap of tens of um."""
    if source.nx < 4:
        return interpolate_field(field, source, target)
    return CubicSpline(source.x, field, axis=-1)(np.clip(target.x, source.x[0], source.x[-1]))

"""Transfer between nested meshes over the same domain: the mesh with every other node, and
bilinear interpolation of a nodal field from one mesh to another (nested iteration of the
Reynolds solve and of the coupled solve, warm starts of a sweep).
"""

from __future__ import annotations

import numpy as np

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
    return Mesh(x=halve(mesh.x), y=mesh.y if mesh.line else halve(mesh.y), length=mesh.length)


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

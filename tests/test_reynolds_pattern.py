"""The Reynolds matrix assembled on a kept sparsity pattern (numerics/reynolds_pattern.py).

Truth: the finite-volume matrix of Eq. (1) assembled here node by node in a dense array,
with loops and no shared code (each interior cell's faces: T_f on its diagonal, -T_f towards
an unknown neighbour; the far inlet's dense block on the first column's interior cells), and
the pressurised block against scipy's general slicing of the same matrix.
"""

from types import SimpleNamespace

import numpy as np
import pytest

from lubecontact.numerics.mesh import Mesh
from lubecontact.numerics.reynolds import reynolds_system

SPEED = 1.0


def field(shape, seed, sealed=()):
    """A positive Poiseuille coefficient, 0 at each node of ``sealed`` and its neighbours
    along x and y: all its faces then carry no flow (faces take the mean of their nodes)."""
    k = np.random.default_rng(seed).uniform(0.5, 2.0, shape) * 1e-12
    for j, i in sealed:
        for dj, di in ((0, 0), (0, -1), (0, 1), (-1, 0), (1, 0)):
            if 0 <= j + dj < shape[0] and 0 <= i + di < shape[1]:
                k[j + dj, i + di] = 0.0
    return k


def dense_truth(mesh, k, block=None):
    """(A dense, unknown mask) by loops over the cells: faces' T = mean k * (side / spacing)."""
    ny, nx = k.shape
    interior = np.zeros(k.shape, dtype=bool)
    if ny == 1:
        interior[0, 1:-1] = True
    else:
        interior[1:-1, 1:-1] = True
    faces = {}
    for j in range(ny):
        for i in range(nx):
            for dj, di, ratio in ((0, 1, mesh.dy / mesh.dx), (1, 0, mesh.dx / mesh.dy)):
                if j + dj < ny and i + di < nx:
                    t = 0.5 * (k[j, i] + k[j + dj, i + di]) * ratio
                    faces.setdefault((j, i), []).append(((j + dj, i + di), t))
                    faces.setdefault((j + dj, i + di), []).append(((j, i), t))
    diagonal = {node: sum(t for _, t in faces.get(node, [])) for node in np.ndindex(k.shape)}
    unknown = np.array([[interior[j, i] and diagonal[(j, i)] > 0 for i in range(nx)] for j in range(ny)])
    number = {node: n for n, node in enumerate(node for node in np.ndindex(k.shape) if unknown[node])}
    a = np.zeros((len(number), len(number)))
    for node, row in number.items():
        for neighbour, t in faces[node]:
            a[row, row] += t
            if neighbour in number:
                a[row, number[neighbour]] -= t
    if block is not None:
        first = [number[(j, 1)] for j in range(1, ny - 1)]
        for r, row in enumerate(first):
            for c, column in enumerate(first):
                a[row, column] += block[r, c]
    return a, unknown


def exterior_of(ny, seed):
    """A stand-in far inlet: a symmetric dense block (as modal_far_inlet.Exterior's) and an inflow."""
    m = np.random.default_rng(seed).uniform(-1.0, 1.0, (ny - 2, ny - 2)) * 1e-13
    return SimpleNamespace(block=m + m.T, inflow=np.zeros(ny - 2))


CASES = {
    "2-D": (7, 9, [(3, 5), (4, 6)], None),  # two sealed nodes: no unknowns
    "2-D with the far inlet": (7, 9, [(2, 6)], 11),
    "line": (1, 12, [(0, 7)], None),
}


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_the_matrix_on_the_kept_pattern_is_the_finite_volume_matrix(case):
    ny, nx, sealed, exterior_seed = case
    mesh = Mesh(x=np.linspace(-1e-3, 5e-4, nx), y=np.linspace(-2e-3, 2e-3, ny) if ny > 1 else np.zeros(1), length=4e-3)
    k = field((ny, nx), 5, sealed)
    exterior = None if exterior_seed is None else exterior_of(ny, exterior_seed)
    block = None if exterior is None else exterior.block
    for film in (1.0, 1.7):  # the second assembly reuses the first's pattern with new values
        truth, unknown = dense_truth(mesh, film * k, block)
        assert unknown.sum() == (ny - 2 if ny > 1 else 1) * (nx - 2) - len(sealed)
        system = reynolds_system(mesh, np.ones((ny, nx)) * 1e-6, film * k, SPEED, exterior=exterior)
        np.testing.assert_array_equal(system.unknown, unknown)
        np.testing.assert_allclose(system.matrix.toarray(), truth, rtol=1e-13, atol=1e-13 * np.abs(truth).max())
        assert system.matrix.has_canonical_format
    free = np.random.default_rng(2).random(system.rhs.size) > 0.35
    pressurised = system.pattern.block(system.matrix, free)
    np.testing.assert_array_equal(pressurised.toarray(), system.matrix[free][:, free].toarray())
    np.testing.assert_allclose(pressurised.toarray(), truth[np.ix_(free, free)], rtol=1e-13,
                               atol=1e-13 * np.abs(truth).max())


def test_a_pattern_is_built_once_per_set_of_unknowns():
    mesh = Mesh(x=np.linspace(-1e-3, 5e-4, 9), y=np.linspace(-2e-3, 2e-3, 7), length=4e-3)
    gap = np.ones((7, 9)) * 1e-6
    first = reynolds_system(mesh, gap, field((7, 9), 1), SPEED).pattern
    assert reynolds_system(mesh, 2 * gap, field((7, 9), 2), SPEED).pattern is first
    sealed = reynolds_system(mesh, gap, field((7, 9), 1, [(3, 4)]), SPEED)
    assert sealed.pattern is not first and sealed.pattern.size == first.size - 1
    assert reynolds_system(mesh, gap, field((7, 9), 3, [(3, 4)]), SPEED).pattern is sealed.pattern

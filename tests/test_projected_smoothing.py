"""Projected Gauss-Seidel smoothing of a pressure guess (projected_smoothing.py).

Truths: projected Gauss-Seidel converges to the solution of an M-matrix complementarity
problem (Cryer 1971), so run long enough it must reproduce the active-set solution of
reynolds.py (a different algorithm) and the independent projected SOR of test_reynolds; the
red-black colouring is exact Gauss-Seidel only if the stencil never couples two nodes of one
colour; and the smoothed guess of an interpolated coarse solution must lie closer to the fine
free boundary than the interpolated one (Brandt & Cryer 1983's nested iteration).
"""

import numpy as np
import pytest
from test_reynolds import U, independent_lcp, line_problem, rough_cylinder_2d, small_lcp

from lubecontact.numerics.projected_smoothing import (
    projected_gauss_seidel,
    red_black_colour,
    smoothed_cavitated_set,
)
from lubecontact.numerics.reynolds import COARSEST_NODES, reynolds_system, solve_reynolds
from lubecontact.numerics.transfer import coarser_mesh, interpolate_field

pytestmark = pytest.mark.filterwarnings("error")


@pytest.mark.parametrize("case", ["line", "2d"])
def test_projected_gauss_seidel_converges_to_the_complementarity_solution(case):
    mesh, hT, k, speed = small_lcp(case)
    system = reynolds_system(mesh, hT, k, speed)
    colour = red_black_colour(system.unknown)
    start = np.zeros(system.rhs.size)
    p = projected_gauss_seidel(system.matrix.tocsr(), system.rhs, colour, start, 4000)
    pressure = np.zeros(mesh.shape)
    pressure[system.unknown] = p
    active_set = solve_reynolds(mesh, hT, k, speed).pressure
    reference, *_ = independent_lcp(mesh, hT, k, speed)
    for truth in (active_set, reference):
        np.testing.assert_allclose(pressure, truth, rtol=0, atol=1e-8 * truth.max())
    # a few sweeps are not the solution: the test above is not met by construction
    early = projected_gauss_seidel(system.matrix.tocsr(), system.rhs, colour, start, 3)
    assert np.max(np.abs(early - active_set[system.unknown])) > 1e-3 * active_set.max()


@pytest.mark.parametrize("shape", [(1, 41), (11, 17)])
def test_red_black_colouring_never_couples_a_colour_with_itself(shape):
    ny, nx = shape
    if ny == 1:
        mesh, hT, k = line_problem(-4.0, 2.0, nx)
    else:
        mesh, hT, k = rough_cylinder_2d(nx=nx, ny=ny)
    system = reynolds_system(mesh, hT, k, U)
    colour = red_black_colour(system.unknown)
    coupling = system.matrix.tocoo()
    off = coupling.row != coupling.col
    assert off.any()
    assert np.all(colour[coupling.row[off]] != colour[coupling.col[off]])
    assert 0 < colour.sum() < colour.size


@pytest.mark.parametrize("nx, ny, tilt", [(121, 81, 0.0), (241, 161, 0.0), (161, 81, 5e-4)])
def test_smoothing_moves_an_interpolated_free_boundary_towards_the_fine_one(nx, ny, tilt):
    mesh, hT, k = rough_cylinder_2d(nx=nx, ny=ny, tilt=tilt)
    speed = 0.1
    fine = solve_reynolds(mesh, hT, k, speed)
    coarse = coarser_mesh(mesh, COARSEST_NODES)
    coarse_solution = solve_reynolds(coarse, interpolate_field(hT, mesh, coarse), interpolate_field(k, mesh, coarse), speed)
    interpolated = interpolate_field(coarse_solution.pressure, coarse, mesh)
    system = reynolds_system(mesh, hT, k, speed)
    truth = fine.cavitated[system.unknown]
    raw = np.count_nonzero((interpolated <= 0.0)[system.unknown] != truth)
    smoothed = np.count_nonzero(smoothed_cavitated_set(system, interpolated) != truth)
    assert raw > 0 and smoothed < raw
    from_set = solve_reynolds(mesh, hT, k, speed, cavitated_guess=interpolated <= 0.0)
    from_pressure = solve_reynolds(mesh, hT, k, speed, pressure_guess=interpolated)
    assert from_pressure.converged and from_pressure.iterations < from_set.iterations
    np.testing.assert_allclose(from_pressure.pressure, fine.pressure, rtol=0, atol=1e-10 * fine.pressure.max())

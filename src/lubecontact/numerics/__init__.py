"""Discretisation and solvers: the mesh and its domain, the Reynolds equation with its
cavitation laws (Swift-Stieber, JFO), mesh transfer, sparse linear algebra, Anderson
mixing and the BLAS thread limit."""

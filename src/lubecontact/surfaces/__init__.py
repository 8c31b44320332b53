"""Roughness from a measured surface (docs/physics.md section 18; McCool 1986, Wear 107:37).

From a height map or profile to the three numbers the statistical contact model needs
(sigma, eta, R_peak) and the bandwidth alpha that says whether the Greenwood-Williamson
picture holds:

- ``reading``: instrument files through SurfaceTopography, or a plain-text matrix / ``.npy``
  with the size and unit given; refuses NaN gaps and non-uniform grids.
- ``moments``: detrending and the spectral moments m0, m2, m4 along x and y, with the
  short-wavelength cut-off stated.
- ``mccool``: sigma, eta, R_peak, alpha, sigma_s from the moments; the composite of two
  surfaces and the sigma split of the shear flow factor.
- ``synthetic``: seeded isotropic random surfaces with a known spectrum (tests, samples).
- ``figure``: the profile spectra with the moments' cut-off marked (workflow surfaces_psd).
- ``report``: what ``lubecontact roughness`` prints and writes; ``measured``: a scene's
  ``roughness.surface`` (parameters cached on the file's content).
"""

from lubecontact.surfaces.mccool import McCool, composite, parameters
from lubecontact.surfaces.moments import Moments, spectral_moments
from lubecontact.surfaces.reading import Surface, SurfaceError, read_surface

__all__ = ["McCool", "Moments", "Surface", "SurfaceError", "composite", "parameters", "read_surface", "spectral_moments"]

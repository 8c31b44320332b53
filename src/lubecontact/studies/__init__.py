"""Studies built from solves: speed sweeps, the figures' parameter grids and their
collection, the accuracy study, the transient figures' cases."""

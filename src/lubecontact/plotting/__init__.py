"""Figures drawn from collected Datasets and case files (matplotlib's object API)."""

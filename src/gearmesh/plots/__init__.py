"""Figures, each drawn from a stage's netCDF Dataset (never from in-memory model state).

One module per stage; every function takes Datasets and an output path and writes a PNG.
"""

"""Stage results as xarray Datasets: one public function per workflow stage.

One module per stage. Each function takes a :class:`~gearmesh.gear.GearPair` (or several)
and the stage's settings, calls the physics modules and returns a Dataset in SI units whose
every variable carries ``units`` and ``long_name``; the workflow only adds provenance and
writes it (:mod:`gearmesh.pipeline`).
"""

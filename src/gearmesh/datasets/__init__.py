"""Stage results as xarray Datasets: one public function per workflow stage.

One module per stage. Each function takes a :class:`~gearmesh.gear.GearPair` (or several)
and the stage's settings, calls the physics modules and returns a Dataset in SI units whose
every variable carries ``units`` and ``long_name``; the workflow only adds provenance and
writes it (:mod:`gearmesh.pipeline`).
"""


def variant_name(ds, k: int) -> str:
    """The micro-geometry variant a stage's dataset belongs to: its ``variant`` attribute, else the
    job's wildcards (:data:`gearmesh.upstream.WILDCARDS_ATTR`), else ``variant{k}``."""
    import json

    from ..upstream import WILDCARDS_ATTR

    if "variant" in ds.attrs:
        return str(ds.attrs["variant"])
    return str(json.loads(ds.attrs.get(WILDCARDS_ATTR, "{}")).get("variant", f"variant{k}"))

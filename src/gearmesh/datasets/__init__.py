"""Stage results as xarray Datasets: one public function per workflow stage.

One module per stage. Each function takes a :class:`~gearmesh.gear.GearPair` (or several)
and the stage's settings, calls the physics modules and returns a Dataset in SI units whose
every variable carries ``units`` and ``long_name``; the workflow only adds provenance and
writes it (:mod:`gearmesh.pipeline`).
"""

from __future__ import annotations

from typing import Any, Mapping, Sequence


def named_pairs(gear_pairs: Mapping[str, Any], names: Sequence[str]) -> dict[str, Any]:
    """The pairs a study table's section names (its ``pairs``), in its order, from ``gear_pairs``
    (loaded pairs by name; more may be given); GearmeshInputError naming ``pairs`` for a name
    that is not given."""
    from ..errors import GearmeshInputError

    if not isinstance(gear_pairs, Mapping):
        raise GearmeshInputError("gear_pairs", type(gear_pairs).__name__, "must map each pair's name to its pair")
    missing = [n for n in names if n not in gear_pairs]
    if missing:
        raise GearmeshInputError("pairs", missing[0], f"must be one of the pairs given {sorted(gear_pairs)}")
    return {n: gear_pairs[n] for n in names}


def variant_name(ds, k: int) -> str:
    """The micro-geometry variant a stage's dataset belongs to: its ``variant`` attribute, else the
    job's wildcards (:data:`gearmesh.upstream.WILDCARDS_ATTR`), else ``variant{k}``."""
    import json

    from ..upstream import WILDCARDS_ATTR

    if "variant" in ds.attrs:
        return str(ds.attrs["variant"])
    return str(json.loads(ds.attrs.get(WILDCARDS_ATTR, "{}")).get("variant", f"variant{k}"))


def variant_names(argument: str, datasets: Any, empty_ok: bool = False) -> list[str]:
    """The variant of each of a table's per-variant ``datasets`` (:func:`variant_name`), after
    refusing (GearmeshInputError naming ``argument``) what is not a list of datasets, an empty one
    (unless ``empty_ok``), a variant given twice (the same file twice) and datasets of different
    pairs (:func:`one_pair`)."""
    import xarray as xr

    from ..errors import GearmeshInputError

    if isinstance(datasets, (xr.Dataset, str, bytes)) or not isinstance(datasets, Sequence):
        raise GearmeshInputError(argument, type(datasets).__name__, "must be a list of datasets, one per variant")
    if not datasets and not empty_ok:
        raise GearmeshInputError(argument, [], "must hold the dataset of at least one variant")
    for k, ds in enumerate(datasets):
        if not isinstance(ds, xr.Dataset):
            raise GearmeshInputError(f"{argument}[{k}]", type(ds).__name__, "must be a dataset")
    names = [variant_name(ds, k) for k, ds in enumerate(datasets)]
    twice = next((n for k, n in enumerate(names) if n in names[:k]), None)
    if twice is not None:
        raise GearmeshInputError(argument, names, f"has variant {twice!r} twice: one dataset per variant")
    one_pair(**{argument: datasets})
    return names


def shared_torques(field: str, names: Sequence[str], datasets: Sequence[Any], dim: str = "torque"):
    """The torques (coordinate ``dim``) every variant's dataset shares, refused naming ``field``
    (the config key that sets them) and the first variant that has others: a table of the
    variants sets them side by side at the same operating points."""
    import numpy as np

    from ..errors import GearmeshInputError

    first = np.asarray(datasets[0][dim].values, dtype=float)
    for name, ds in zip(names, datasets):
        other = np.asarray(ds[dim].values, dtype=float)
        if other.shape != first.shape or not np.allclose(other, first, rtol=1e-12, atol=0.0):
            raise GearmeshInputError(field, other.tolist(), f"must be the same for every variant ({name})")
    return first


def one_pair(**lists: Sequence[Any]) -> None:
    """Refuse (GearmeshInputError naming the list and the first differing pair key) datasets that
    were not all computed for one pair: the variants of a pair differ in their micro-geometry
    alone (the pair data each records, :data:`gearmesh.upstream.PAIR_ATTR`, without the
    modification; or its ``pair_name``). Datasets that record neither (made by hand) pass."""
    from ..errors import GearmeshInputError
    from ..upstream import first_difference

    first: tuple[str, dict[str, Any]] | None = None
    for argument, datasets in lists.items():
        for k, ds in enumerate(datasets):
            pair = _pair_of(ds)
            if pair is None:
                continue
            if first is None:
                first = (f"{argument}[{k}]", pair)
                continue
            key = first_difference(first[1], pair)
            if key is not None:
                raise GearmeshInputError(f"{argument}[{k}]", f"a dataset of pair {pair.get('name')!r}",
                                         f"is not of the pair of {first[0]} ({first[1].get('name')!r}; "
                                         f"{key or 'name'} differs): a table sets one pair's variants side by side")


def _pair_of(ds) -> dict[str, Any] | None:
    """The pair data a stage's dataset records, without the modification (its variant's); the pair
    name alone where only that is recorded; None where neither is."""
    import json

    from ..upstream import PAIR_ATTR

    text = ds.attrs.get(PAIR_ATTR)
    if isinstance(text, str):
        pair = dict(json.loads(text).get("pair") or {})
        pair.pop("modification", None)
        return pair
    name = ds.attrs.get("pair_name")
    return {"name": str(name)} if name else None

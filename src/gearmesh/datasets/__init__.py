"""Stage results as xarray Datasets: one public function per workflow stage.

One module per stage. Each function takes a :class:`~gearmesh.gear.GearPair` (or several)
and the stage's settings, calls the physics modules and returns a Dataset in SI units whose
every variable carries ``units`` and ``long_name``; the workflow only adds provenance and
writes it (:mod:`gearmesh.pipeline`).
"""

from __future__ import annotations

from typing import Any, Mapping, Sequence


def named_pairs(gear_pairs: Mapping[str, Any], names: Sequence[str]) -> dict[str, Any]:
    """The pairs a study table's section names (its ``pairs``), in its order, from ``gear_pairs``.

    Parameters
    ----------
    gear_pairs : Mapping[str, GearPair]
        Loaded pairs by name; more may be given than ``names`` asks for.
    names : Sequence[str]
        The section's ``pairs``, in the table's order.

    Returns
    -------
    dict[str, GearPair]
        The named pairs, in the order of ``names``.

    Raises
    ------
    GearmeshInputError
        Naming ``gear_pairs`` when it is not a mapping, ``pairs`` for a name not given.
    """
    from ..errors import GearmeshInputError

    if not isinstance(gear_pairs, Mapping):
        raise GearmeshInputError("gear_pairs", type(gear_pairs).__name__, "must map each pair's name to its pair")
    missing = [n for n in names if n not in gear_pairs]
    if missing:
        raise GearmeshInputError("pairs", missing[0], f"must be one of the pairs given {sorted(gear_pairs)}")
    return {n: gear_pairs[n] for n in names}


def variant_name(ds, k: int) -> str:
    """The micro-geometry variant a stage's dataset belongs to: its ``variant`` attribute, else the
    job's wildcards (:data:`gearmesh.upstream.WILDCARDS_ATTR`), else ``variant{k}``.

    Parameters
    ----------
    ds : xarray.Dataset
        A stage's dataset.
    k : int
        Its index in the table's list: the fallback name ``variant{k}``.

    Returns
    -------
    str
        The variant's name.
    """
    import json

    from ..upstream import WILDCARDS_ATTR

    if "variant" in ds.attrs:
        return str(ds.attrs["variant"])
    return str(json.loads(ds.attrs.get(WILDCARDS_ATTR, "{}")).get("variant", f"variant{k}"))


def variant_names(argument: str, datasets: Any, empty_ok: bool = False) -> list[str]:
    """The variant of each of a table's per-variant ``datasets`` (:func:`variant_name`), after
    refusing what is not a list of datasets, an empty one (unless ``empty_ok``), a variant given
    twice (the same file twice) and datasets of different pairs (:func:`one_pair`).

    Parameters
    ----------
    argument : str
        The table function's argument that holds ``datasets``: the field an error names.
    datasets : Sequence[xarray.Dataset]
        One stage dataset per variant.
    empty_ok : bool, default False
        Accept an empty list.

    Returns
    -------
    list[str]
        The variant of each dataset, in their order.

    Raises
    ------
    GearmeshInputError
        Naming ``argument`` (or ``argument[k]`` for an item that is not a dataset).
    """
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
    """The torques (coordinate ``dim``) every variant's dataset shares: a table of the variants
    sets them side by side at the same operating points.

    Parameters
    ----------
    field : str
        The config key that sets the torques: the field an error names.
    names : Sequence[str]
        The variant of each dataset (:func:`variant_names`).
    datasets : Sequence[xarray.Dataset]
        One stage dataset per variant, at least one.
    dim : str, default "torque"
        The torque coordinate's name.

    Returns
    -------
    numpy.ndarray
        The shared torques, shape (T,), in the datasets' unit (N·m for the stages').

    Raises
    ------
    GearmeshInputError
        Naming ``field`` and the first variant whose torques differ (relative tolerance 1e-12).
    """
    import numpy as np

    from ..errors import GearmeshInputError

    first = np.asarray(datasets[0][dim].values, dtype=float)
    for name, ds in zip(names, datasets):
        other = np.asarray(ds[dim].values, dtype=float)
        if other.shape != first.shape or not np.allclose(other, first, rtol=1e-12, atol=0.0):
            raise GearmeshInputError(field, other.tolist(), f"must be the same for every variant ({name})")
    return first


def one_pair(**lists: Sequence[Any]) -> None:
    """Refuse datasets that were not all computed for one pair: the variants of a pair differ in
    their micro-geometry alone (the pair data each records, :data:`gearmesh.upstream.PAIR_ATTR`,
    without the modification; or its ``pair_name``). Datasets that record neither (made by hand)
    pass.

    Parameters
    ----------
    **lists : Sequence[xarray.Dataset]
        The table function's per-variant dataset lists, by argument name.

    Returns
    -------
    None
        Returns only when the datasets are of one pair.

    Raises
    ------
    GearmeshInputError
        Naming ``argument[k]`` of the first dataset of another pair and the first differing pair key.
    """
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

"""gearmesh: helical gear geometry, contact, mesh stiffness, impact and dynamics.

The names below are loaded on first use (PEP 562), so ``import gearmesh`` and the light
modules (``gearmesh.errors``, ``gearmesh.jobserver``) import neither numpy nor YAML; the version
too (reading the installed metadata costs 30 ms, which every job's script would pay).
"""

from importlib import import_module

_LAZY = {
    "GearmeshInputError": "errors",
    "GearPair": "gear",
    "Material": "gear",
    "Modification": "gear",
    "PairGeometry": "gear",
    "load_pair": "pairfile",
    "example_pair": "pairfile",
    "pair_geometry": "gear",
}

__all__ = [*_LAZY, "__version__"]


def __getattr__(name: str):
    if name in _LAZY:
        return getattr(import_module(f".{_LAZY[name]}", __name__), name)
    if name == "__version__":
        from importlib.metadata import PackageNotFoundError, version

        try:
            value = version("gearmesh")
        except PackageNotFoundError:  # running from a source tree without installation
            value = "0.0.0+unknown"
        globals()["__version__"] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)

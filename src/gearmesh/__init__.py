"""gearmesh: helical gear geometry, contact, mesh stiffness, impact and dynamics."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("gearmesh")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.0.0+unknown"

from .errors import GearmeshInputError
from .gear import GearPair, Material, Modification, PairGeometry, load_pair, pair_geometry

__all__ = [
    "GearmeshInputError",
    "GearPair",
    "Material",
    "Modification",
    "PairGeometry",
    "load_pair",
    "pair_geometry",
    "__version__",
]

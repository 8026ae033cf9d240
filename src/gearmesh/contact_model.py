"""The contact model of a loaded contact, one group for every physics function that solves one.

The loaded tooth contact (:func:`gearmesh.ltca.ltca`, :func:`gearmesh.ltca_model.ltca_model`), the
mesh-in impact (:func:`gearmesh.impact.impact_model`) and the mesh force tables of the dynamics
(:func:`gearmesh.meshforce.table_layout`, :func:`gearmesh.meshforce.mesh_force_table`,
:func:`gearmesh.dynamics.population.population_dynamics`) all discretise the contact lines into
candidate points, load each by a local contact law on a slice compliance of one tooth model, and
reach a fraction of the base pitch beyond the active zone for tip-edge contacts. They take that
choice as one :class:`ContactModel`, checked once where it is made; the study sections that carry
it (:class:`gearmesh.settings.Ltca`, :class:`~gearmesh.settings.Impact`,
:class:`~gearmesh.settings.Dynamics`, :class:`~gearmesh.settings.Optimise`) give it whole.

Each use's defaults are declared here once: :data:`LTCA_CONTACT` (the LTCA and the impact) and
:data:`TABLE_CONTACT` (the dynamics' mesh force table). Light: it imports no physics (only
:mod:`~gearmesh.choices`, :mod:`~gearmesh.errors` and :mod:`~gearmesh.limits`), so :mod:`gearmesh.settings` can
build the group: its sections inherit how from the mixins below (:class:`LoadedContactSection`,
:class:`TableContactSection`, :class:`OverridingContactSection`).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, replace

from .choices import CONTACT_LAWS, DEFAULT_CONTACT_LAW, DEFAULT_CORNER_EXTENSION, DEFAULT_TOOTH_METHOD, TOOTH_METHODS
from .errors import GearmeshInputError
from .limits import MAX_LINE_POINTS

__all__ = ["ContactModel", "LTCA_CONTACT", "TABLE_CONTACT", "DEFAULT_LTCA_POINTS", "DEFAULT_TABLE_POINTS",
           "DEFAULT_TABLE_EXTENSION", "LoadedContactSection", "TableContactSection", "OverridingContactSection"]

#: Candidate points (slices) per contact line of the LTCA and the impact model (the study's default
#: of ``ltca.points`` and ``impact.points``, :mod:`gearmesh.settings`).
DEFAULT_LTCA_POINTS = 50
#: Points (slices) per contact line of a mesh force table. More than the LTCA's 50: a helical pair
#: enters at the corner at the face end, and slice centres put the first point half a slice inside it,
#: delaying the entering pair's first touch by (b/2N)·tan βb of roll — 0.2 mm at 50 points on the
#: default pair, 0.05 mm at 200, converging as 1/N to the exact corner of
#: :func:`gearmesh.impact.impact_static` (tests/test_dynamics_contact.py); the table costs about 1 s at 200.
DEFAULT_TABLE_POINTS = 200
#: Reach of a mesh force table's tip-edge candidates beyond the active zone (fraction of p_bt): half a
#: base pitch, the whole half-window before A in which the entering pair is followed.
DEFAULT_TABLE_EXTENSION = 0.5


@dataclass(frozen=True)
class ContactModel:
    """How a loaded contact is modelled: ``points`` candidate points (slices) per contact line, the
    local ``contact_law`` of a slice (:data:`gearmesh.choices.CONTACT_LAWS`,
    :func:`gearmesh.ltca_model.contact_law`), the tooth model ``method`` of the slice compliance
    (:data:`gearmesh.choices.TOOTH_METHODS`) and the ``extension`` of the tip-edge candidates beyond
    the active zone (fraction of the transverse base pitch p_bt, in [0, 1];
    :func:`gearmesh.tca.candidate_grid`). The field defaults are the LTCA's (:data:`LTCA_CONTACT`).

    Raises
    ------
    GearmeshInputError
        A field out of its range, named as the study names it (``points``, ``contact_law``,
        ``method``, ``corner_extension``).
    """

    points: int = DEFAULT_LTCA_POINTS
    contact_law: str = DEFAULT_CONTACT_LAW
    method: str = DEFAULT_TOOTH_METHOD
    extension: float = DEFAULT_CORNER_EXTENSION

    def __post_init__(self) -> None:
        points, extension = self.points, self.extension
        if isinstance(points, bool) or not isinstance(points, numbers.Integral) or not 1 <= points <= MAX_LINE_POINTS:
            raise GearmeshInputError("points", points, f"must be an integer in [1, {MAX_LINE_POINTS}]")
        if self.contact_law not in CONTACT_LAWS:
            raise GearmeshInputError("contact_law", self.contact_law, f"must be one of {list(CONTACT_LAWS)}")
        if self.method not in TOOTH_METHODS:
            raise GearmeshInputError("method", self.method, f"must be one of {list(TOOTH_METHODS)}")
        if isinstance(extension, bool) or not isinstance(extension, numbers.Real) or not math.isfinite(extension) \
                or not 0 <= extension <= 1:
            raise GearmeshInputError("corner_extension", extension, "must lie in [0, 1] (fraction of the base pitch)")
        object.__setattr__(self, "points", int(points))
        object.__setattr__(self, "extension", float(extension))

    def with_(self, **changes) -> ContactModel:
        """This model with ``changes`` (field names), checked again."""
        return replace(self, **changes)


#: The LTCA's and the impact model's contact model: the declared defaults of :mod:`gearmesh.choices`.
LTCA_CONTACT = ContactModel()
#: A mesh force table's (:mod:`gearmesh.meshforce`): more points, half a base pitch of reach.
TABLE_CONTACT = ContactModel(points=DEFAULT_TABLE_POINTS, extension=DEFAULT_TABLE_EXTENSION)


class LoadedContactSection:
    """A study section that sets a loaded contact (:class:`gearmesh.settings.Ltca`,
    :class:`~gearmesh.settings.Impact`): its ``points``, ``contact_law``, ``method`` and ``corner_extension``."""

    def contact_model(self) -> ContactModel:
        """The section's contact model, passed whole to the physics."""
        return ContactModel(self.points, self.contact_law, self.method, self.corner_extension)


class TableContactSection:
    """A study section that sets a mesh force table (:class:`gearmesh.settings.Dynamics`,
    :class:`~gearmesh.settings.TrainDynamics`): its ``points``, ``contact_law`` and ``method`` on a table's reach."""

    def contact_model(self) -> ContactModel:
        """The contact table's contact model, passed whole to the physics."""
        return TABLE_CONTACT.with_(points=self.points, contact_law=self.contact_law, method=self.method)


class OverridingContactSection:
    """A study section (:class:`gearmesh.settings.Optimise`) whose ``points``, ``contact_law`` and
    ``corner_extension`` override the study's impact section's when given (None: the impact's)."""

    def contact_model(self, impact: LoadedContactSection) -> ContactModel:
        """The run's contact model: the impact section's with this section's own keys; its tooth model always."""
        own = {"points": self.points, "contact_law": self.contact_law, "extension": self.corner_extension}
        return impact.contact_model().with_(**{k: v for k, v in own.items() if v is not None})

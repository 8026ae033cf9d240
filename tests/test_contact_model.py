"""gearmesh.contact_model: the one contact-model group of the LTCA, the impact and the mesh force
tables — checked once when made, its defaults the declared ones, given whole by the study sections."""

from __future__ import annotations

import numpy as np
import pytest

from gearmesh.choices import CONTACT_LAWS, DEFAULT_CONTACT_LAW, DEFAULT_CORNER_EXTENSION, DEFAULT_TOOTH_METHOD
from gearmesh.contact_model import (DEFAULT_TABLE_EXTENSION, DEFAULT_TABLE_POINTS, LTCA_CONTACT,
                                    TABLE_CONTACT, ContactModel)
from gearmesh.errors import GearmeshInputError
from gearmesh.limits import MAX_LINE_POINTS
from gearmesh.schema import settings_object
from gearmesh.settings import Dynamics, Impact, Ltca, Optimise


def test_the_defaults_are_the_declared_choices():
    assert LTCA_CONTACT == ContactModel(50, DEFAULT_CONTACT_LAW, DEFAULT_TOOTH_METHOD, DEFAULT_CORNER_EXTENSION)
    assert TABLE_CONTACT == LTCA_CONTACT.with_(points=DEFAULT_TABLE_POINTS, extension=DEFAULT_TABLE_EXTENSION)
    assert settings_object(Ltca, {}).contact_model() == LTCA_CONTACT
    assert settings_object(Impact, {}).contact_model() == LTCA_CONTACT
    assert settings_object(Dynamics, {}).contact_model() == TABLE_CONTACT


@pytest.mark.parametrize("field, value", [
    ("points", 0), ("points", MAX_LINE_POINTS + 1), ("points", 2.0), ("points", True),
    ("contact_law", "hertz"), ("method", "beam"),
    ("extension", -0.1), ("extension", 1.5), ("extension", float("nan")), ("extension", "0.25"), ("extension", True),
])
def test_a_bad_field_is_refused_when_the_group_is_made(field, value):
    with pytest.raises(GearmeshInputError) as err:
        ContactModel(**{field: value})
    assert err.value.field == ("corner_extension" if field == "extension" else field)
    with pytest.raises(GearmeshInputError):
        LTCA_CONTACT.with_(**{field: value})  # a changed copy is checked again


def test_numpy_numbers_are_taken_as_python_numbers():
    c = ContactModel(points=np.int64(30), extension=np.float64(0.5))
    assert type(c.points) is int and type(c.extension) is float and c == ContactModel(30, extension=0.5)
    assert {ContactModel(method=m, contact_law=law).method for m in ("fe", "transition") for law in CONTACT_LAWS} \
        == {"fe", "transition"}


def test_each_section_gives_its_own_keys_whole():
    imp = settings_object(Impact, {"points": 30, "contact_law": "linear", "method": "transition",
                                   "corner_extension": 0.5})
    assert imp.contact_model() == ContactModel(30, "linear", "transition", 0.5)
    dyn = settings_object(Dynamics, {"points": 80, "contact_law": "linear", "method": "improved"})
    assert dyn.contact_model() == ContactModel(80, "linear", "improved", DEFAULT_TABLE_EXTENSION)
    # an optimisation overrides the impact section's points, law and reach, never its tooth model
    none = settings_object(Optimise, {})
    assert none.contact_model(imp) == imp.contact_model()
    own = settings_object(Optimise, {"points": 20, "corner_extension": 0.1})
    assert own.contact_model(imp) == ContactModel(20, "linear", "transition", 0.1)

"""The one error type for bad input: it names the field, the value and the rule."""

from __future__ import annotations


class GearmeshInputError(ValueError):
    """A config or gear pair that is malformed, out of range or physically impossible.

    The CLI turns it into one line on stderr and exit code 2; the workflow's scripts let
    it propagate before any output file is written.
    """

    def __init__(self, field: str, value: object, rule: str):
        self.field = field
        self.value = value
        self.rule = rule
        super().__init__(f"{field} = {value!r}: {rule}")

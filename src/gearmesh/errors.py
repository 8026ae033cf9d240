"""The one error type for bad input: it names the field, the value and the rule."""

from __future__ import annotations

import reprlib

#: Longest excerpt of a value, a field name or a rule in the one-line message (characters):
#: a terminal line, so that a hostile value of megabytes never reaches stderr in full.
MAX_EXCERPT = 120

_repr = reprlib.Repr()
_repr.maxlevel, _repr.maxlist, _repr.maxtuple, _repr.maxdict = 3, 8, 8, 4
_repr.maxstring = _repr.maxother = _repr.maxlong = MAX_EXCERPT


def excerpt(text: str, limit: int = MAX_EXCERPT) -> str:
    """``text`` cut to ``limit`` characters, the cut marked with an ellipsis.

    Parameters
    ----------
    text : str
        The text to cut.
    limit : int, default MAX_EXCERPT
        Longest result (characters), the ellipsis included.

    Returns
    -------
    str
        ``text`` unchanged when it fits, else its first ``limit - 1`` characters and "…".
    """
    return text if len(text) <= limit else text[:limit - 1] + "…"


def unknown_key_rule(key: object, allowed, reference: str) -> str:
    """The rule an unknown ``key`` breaks, whole words only within the message's excerpt: every
    allowed key where they fit in a terminal line, else the closest ones and the command that
    lists them all (``reference``, e.g. "gearmesh schema pair --format markdown").

    Parameters
    ----------
    key : object
        The key the user gave.
    allowed : iterable
        Every key allowed where ``key`` stands.
    reference : str
        The command that lists every allowed key.

    Returns
    -------
    str
        The rule of a :class:`GearmeshInputError`: "unknown key; allowed keys are ..." or
        "unknown key; did you mean ...? every allowed key: ``reference``".
    """
    import difflib

    names = sorted(map(str, allowed))
    listed = ", ".join(names)
    if len(listed) <= 3 * MAX_EXCERPT:
        return f"unknown key; allowed keys are {listed}"
    close = difflib.get_close_matches(str(key), names, n=3, cutoff=0.5)
    guess = f"did you mean {' or '.join(close)}? " if close else ""
    return f"unknown key; {guess}every allowed key: {reference}"


def short_repr(value: object) -> str:
    """repr of ``value`` in bounded time and length (reprlib: nested levels, items and long
    strings are elided), so that the error path never formats a huge input in full.

    Parameters
    ----------
    value : object
        Any value, however large or deeply nested.

    Returns
    -------
    str
        Its repr, at most :data:`MAX_EXCERPT` characters.
    """
    return excerpt(_repr.repr(value))


class GearmeshInputError(ValueError):
    """A config or gear pair that is malformed, out of range or physically impossible.

    The CLI turns it into one line on stderr and exit code 2; the workflow's scripts let
    it propagate before any output file is written. The message shows an excerpt of the
    value (:func:`short_repr`) and of the field and rule, never a whole huge input.
    """

    def __init__(self, field: str, value: object, rule: str):
        self.field = field
        self.value = value
        self.rule = rule
        text = f"{excerpt(str(field))} = {short_repr(value)}: {excerpt(' '.join(str(rule).split()), 4 * MAX_EXCERPT)}"
        super().__init__(text)

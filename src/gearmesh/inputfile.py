"""Bounded reading of small YAML input files: pair files, study configs, profiles, the CLI's files.

A document that cannot be a gearmesh input is refused as one :class:`GearmeshInputError` before
it is walked: anything but a regular file, more than :data:`gearmesh.limits.MAX_INPUT_BYTES`,
non-UTF-8 bytes, a key given twice in one mapping, a YAML alias, more than
:data:`gearmesh.limits.MAX_INPUT_NODES` nodes or nesting deeper than
:data:`gearmesh.limits.MAX_INPUT_DEPTH`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from .errors import GearmeshInputError
from .limits import MAX_INPUT_BYTES, MAX_INPUT_DEPTH, MAX_INPUT_NODES


class _InputRefused(yaml.YAMLError):
    """Raised by the loader for a document that cannot be a gearmesh input (reason as text)."""


class _UniqueKeyLoader(yaml.SafeLoader):
    """A safe YAML loader for small input documents: refuses a mapping with the same key twice
    (PyYAML keeps the last), aliases (``*name``: a "billion laughs" document expands
    exponentially when walked), more than :data:`MAX_INPUT_NODES` nodes and nesting deeper
    than :data:`MAX_INPUT_DEPTH`."""

    _nodes = 0
    _depth = 0

    def compose_node(self, parent, index):
        if self.check_event(yaml.AliasEvent):
            mark = self.peek_event().start_mark
            raise _InputRefused(f"uses a YAML alias (line {mark.line + 1}); write the value out")
        self._nodes += 1
        if self._nodes > MAX_INPUT_NODES:
            raise _InputRefused(f"has more than {MAX_INPUT_NODES} YAML nodes")
        self._depth += 1
        try:
            if self._depth > MAX_INPUT_DEPTH:
                raise _InputRefused(f"nests deeper than {MAX_INPUT_DEPTH} levels")
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


def _unique_mapping(loader: _UniqueKeyLoader, node: yaml.MappingNode, deep: bool = False):
    keys = [loader.construct_object(k, deep=deep) for k, _ in node.value]
    seen, duplicates = set(), set()
    for key in keys:
        try:
            (duplicates if key in seen else seen).add(key)
        except TypeError:  # an unhashable key: construct_mapping refuses it below
            pass
    if duplicates:
        raise GearmeshInputError(min(map(str, duplicates)), None,
                                 f"is given twice in one mapping (line {node.start_mark.line + 1})")
    return loader.construct_mapping(node, deep=deep)


_UniqueKeyLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _unique_mapping)


def read_input_text(path: str | Path, what: str) -> str:
    """The text of a small input file, read bounded: refuses anything but a regular file (a
    directory, FIFO or device such as /dev/zero, checked before opening), more than
    :data:`MAX_INPUT_BYTES` and non-UTF-8 bytes, each as one :class:`GearmeshInputError`.

    Parameters
    ----------
    path : str or pathlib.Path
        The input file.
    what : str
        What the file is ("pair file", "config file", "profile"), the field an error names.

    Returns
    -------
    str
        The file's text.

    Raises
    ------
    GearmeshInputError
        Naming ``what`` and ``path``: not a regular file, unreadable, larger than
        :data:`MAX_INPUT_BYTES`, or not UTF-8.
    """
    import stat

    path = Path(path)
    try:
        mode = path.stat().st_mode
        if not stat.S_ISREG(mode):
            raise GearmeshInputError(what, str(path), "is not a regular file")
        with path.open("rb") as f:
            data = f.read(MAX_INPUT_BYTES + 1)
    except OSError as exc:
        raise GearmeshInputError(what, str(path), f"cannot be read ({exc.strerror})") from None
    if len(data) > MAX_INPUT_BYTES:
        raise GearmeshInputError(what, str(path), f"is larger than {MAX_INPUT_BYTES // 1024} kB: not a gearmesh input")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise GearmeshInputError(what, str(path), "is not UTF-8 text") from None


def read_yaml(path: str | Path, what: str) -> Any:
    """Parse a small YAML input file (:func:`read_input_text`); a malformed file, a key given
    twice, an alias or an oversized document is a one-line :class:`GearmeshInputError`.

    Parameters
    ----------
    path : str or pathlib.Path
        The input file.
    what : str
        What the file is, the field an error names.

    Returns
    -------
    object
        The parsed document (a mapping for every gearmesh input; the caller checks).

    Raises
    ------
    GearmeshInputError
        Naming ``what`` and ``path`` (or the duplicated key): everything :func:`read_input_text`
        refuses, malformed YAML, a key given twice, an alias, more than :data:`MAX_INPUT_NODES`
        nodes or deeper than :data:`MAX_INPUT_DEPTH` levels.
    """
    text = read_input_text(path, what)
    try:
        return yaml.load(text, Loader=_UniqueKeyLoader)
    except _InputRefused as exc:
        raise GearmeshInputError(what, str(path), str(exc)) from None
    except yaml.YAMLError as exc:
        raise GearmeshInputError(what, str(path), "is not valid YAML: " + " ".join(str(exc).split())) from None
    except RecursionError:  # pragma: no cover - MAX_INPUT_DEPTH refuses first
        raise GearmeshInputError(what, str(path), "nests too deep") from None

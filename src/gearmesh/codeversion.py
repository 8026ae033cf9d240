"""Results follow the code: the digest of the package modules a rule's function can run.

A rule names the package function it runs in ``params.function``. The workflow writes it as
:func:`versioned` ``("gearmesh.datasets.ltca:ltca_dataset")``, which appends the sha256 of the
source of every gearmesh module that function's module imports, directly or through other
gearmesh modules (imports inside functions included), plus :mod:`gearmesh.pipeline` (the glue
that writes every file). Snakemake reruns a job when its params change (its ``params`` rerun
trigger, on by default), so editing a module reruns exactly the jobs whose functions can
execute it, and nothing else. :func:`gearmesh.pipeline.resolve` drops the ``@…`` suffix.

The import graph is read from the source (``ast``), not by importing, so the digest of a
module that fails to import is still defined and the check costs a few milliseconds.
"""

from __future__ import annotations

import hashlib
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import ast

PACKAGE = "gearmesh"
#: Every job goes through these (provenance, logging, writing).
GLUE = ("gearmesh.pipeline",)
PACKAGE_ROOT = Path(__file__).resolve().parent


@lru_cache(maxsize=None)
def module_file(module: str, root: Path = PACKAGE_ROOT) -> Path | None:
    """The source file of a gearmesh module under ``root`` (the package directory), or None.

    Remembered for the process (the workflow's digests ask for each module about 15 times per
    rule: 15 000 lookups, 0.4 s of Snakemake's start-up otherwise): a module file created or
    removed during one process is not seen; an edited one is (its digest reads the file).

    Parameters
    ----------
    module : str
        Dotted module name, e.g. ``"gearmesh.datasets.ltca"``; a name outside the package gives None.
    root : Path
        The package directory (default: this installed package's).

    Returns
    -------
    Path or None
        ``<root>/<sub/path>.py`` or ``<root>/<sub/path>/__init__.py``, whichever exists; None when
        neither does (a name imported from a module rather than a module).
    """
    parts = module.split(".")
    if parts[0] != PACKAGE:
        return None
    base = root.joinpath(*parts[1:])
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


#: The fields of a node that hold statements (an import is a statement, so these lead to every one).
_STATEMENT_FIELDS = ("body", "orelse", "finalbody", "handlers", "cases")


def _statements(nodes):
    """Every statement in and under ``nodes`` (exception handlers and match cases passed through),
    without visiting expressions: what :func:`ast.walk` would find of them, in a tenth of the time."""
    stack = list(nodes)
    while stack:
        node = stack.pop()
        yield node
        for name in _STATEMENT_FIELDS:
            stack.extend(getattr(node, name, None) or ())


def _import_nodes(tree: ast.Module, nested: bool):
    """Import statements of a module: all of them, or only those run at import time."""
    import ast  # here: every job's script unpickles a Versioned and so imports this module
    if nested:
        return _statements(tree.body)
    return _statements(stmt for stmt in tree.body
                       if not isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)))


@lru_cache(maxsize=None)
def _parsed_imports(module: str, path: Path, stamp: tuple[int, int], nested: bool) -> frozenset[str]:
    """gearmesh modules named by the import statements of one file (cached per file version)."""
    import ast

    is_package = path.name == "__init__.py"
    package = module if is_package else module.rpartition(".")[0]
    out: set[str] = set()
    for node in _import_nodes(ast.parse(path.read_text(encoding="utf-8")), nested):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names if a.name.split(".")[0] == PACKAGE)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                anchor = package.split(".")
                anchor = anchor[: len(anchor) - (node.level - 1)]
                base = ".".join(anchor + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            if base.split(".")[0] != PACKAGE:
                continue
            out.add(base)
            out.update(f"{base}.{a.name}" for a in node.names)  # "from . import io" names a module
    return frozenset(out)


def _imports(module: str, path: Path, nested: bool = True) -> frozenset[str]:
    st = path.stat()
    return _parsed_imports(module, path, (st.st_mtime_ns, st.st_size), nested)


def module_closure(module: str, root: Path = PACKAGE_ROOT, shallow: tuple[str, ...] = ()) -> dict[str, Path]:
    """``module`` and every gearmesh module it imports, transitively, with their parent
    packages' ``__init__`` files: {module name: source file}. Modules in ``shallow``
    contribute only the imports they run at import time (not those inside functions).

    Parameters
    ----------
    module : str
        Dotted name of the module to start from, e.g. ``"gearmesh.datasets.ltca"``.
    root : Path
        The package directory (default: this installed package's).
    shallow : tuple of str
        Modules whose imports inside functions are not followed (default: none).

    Returns
    -------
    dict of str to Path
        Every module reached, by dotted name, with its source file.
    """
    found: dict[str, Path] = {}
    todo = [module]
    while todo:
        name = todo.pop()
        if name in found:
            continue
        path = module_file(name, root)
        if path is None:  # a name imported from a module, not a module
            continue
        found[name] = path
        todo.extend(_imports(name, path, nested=name not in shallow))
        parts = name.split(".")
        todo.extend(".".join(parts[:i]) for i in range(1, len(parts)))
    return found


def _digest(module: str, root: Path) -> str:
    # the glue's own helpers (e.g. pipeline.run_variant_pair) import more inside functions:
    # those count for the rule that names them, not for every job
    files = module_closure(module, root)
    for glue in GLUE:
        files.update(module_closure(glue, root, shallow=(glue,)))
    h = hashlib.sha256()
    for name in sorted(files):
        h.update(name.encode())
        h.update(files[name].read_bytes())
    return h.hexdigest()


def function_digest(spec: str, root: Path = PACKAGE_ROOT) -> str:
    """sha256 of the sources that the function ``spec`` ("gearmesh.module:function") can run.

    The module's :func:`module_closure` and that of the glue (:data:`GLUE`, its imports inside
    functions not followed), each file's name and bytes hashed in name order.

    Parameters
    ----------
    spec : str
        ``"gearmesh.module:function"``; an ``"@digest"`` suffix is ignored.
    root : Path
        The package directory (default: this installed package's).

    Returns
    -------
    str
        The 64 hex digits of the sha256.

    Raises
    ------
    ValueError
        ``spec``'s module is not a module of the package under ``root``.

    References
    ----------
    .. [1] NIST, Secure Hash Standard (SHS), FIPS PUB 180-4 (2015), §6.2 (SHA-256).
    """
    module = spec.partition("@")[0].partition(":")[0]
    if module_file(module, root) is None:
        raise ValueError(f"{spec!r} does not name a module of the {PACKAGE} package under {root}")
    return _digest(module, Path(root))


class Versioned(str):
    """A function spec with its digest ("module:function@digest") that shows without it.

    Snakemake compares a job's params by ``repr`` (its params rerun trigger: the digest is what
    reruns a job whose code changed) and writes them into the report's job panel by ``format``
    (where a reader wants the function's name, not a hash). The workflow hands it to Snakemake
    from a param function (:func:`gearmesh.plan.versioned_param`): a plain string
    param is formatted with the wildcards, which would make it a plain ``str``. The end-to-end test
    checks both: a changed module reruns its jobs, and the report shows no digest."""

    __slots__ = ()

    def __str__(self) -> str:
        return self.partition("@")[0]

    def __format__(self, spec: str) -> str:
        return format(str(self), spec)


def versioned(spec: str, root: Path = PACKAGE_ROOT) -> Versioned:
    """``spec`` with the first 16 hex digits of :func:`function_digest` appended after '@'.

    What a rule's ``params.function`` holds: Snakemake reruns a job when its params change (the
    ``params`` rerun trigger, on by default since Snakemake 7.8), so a job reruns exactly when a
    module its function can run changed.

    Parameters
    ----------
    spec : str
        ``"gearmesh.module:function"``.
    root : Path
        The package directory (default: this installed package's).

    Returns
    -------
    Versioned
        ``"gearmesh.module:function@<16 hex digits>"``, shown without the digest.

    Raises
    ------
    ValueError
        As :func:`function_digest`.

    References
    ----------
    .. [1] Snakemake documentation, "Snakefiles and Rules": non-file parameters for rules
       (``params``); command line interface: ``--rerun-triggers``.
    """
    return Versioned(f"{spec}@{function_digest(spec, root)[:16]}")

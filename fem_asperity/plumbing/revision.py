"""Which code computed a result: a hash of the package modules it runs, docstrings left out.

`solver_revision()` keys the stored curves (`studies.store`) and is recorded in every result.json:
editing the solver or the kernel changes it, editing help text, a plot, a comment or a docstring
does not (tests/test_layering.py).
"""

import ast
import hashlib
import importlib.util
from functools import cache
from pathlib import Path

#: The roots of the code that computes a stored curve: the solve and the store's format, with
#: all they import (methods.md §13); test_layering.py checks the set.
REVISION_ROOTS = ("fem_asperity.solver.solve", "fem_asperity.studies.store")


@cache
def _source(module):
    """The source bytes of `module` (read once per process)."""
    return Path(importlib.util.find_spec(module).origin).read_bytes()


def _package_imports(module):
    """Absolute names of the modules of fem_asperity and of `module`'s own package (gw's, for a
    root in gw) that `module` imports from (the packages import from modules only: `from
    ..curves.curve import Curve`, never `from .. import path`)."""
    tree = ast.parse(_source(module))
    # a package's __init__ imports relative to the package itself, a module relative to its own
    package = (module if importlib.util.find_spec(module).submodule_search_locations is not None
               else module.rsplit(".", 1)[0])
    found = {importlib.util.resolve_name("." * node.level + (node.module or ""), package)
             for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
    return {name for name in found if name.split(".")[0] in ("fem_asperity", module.split(".")[0])}


def revision_modules(roots=REVISION_ROOTS):
    """The modules reachable by imports from `roots` (`_package_imports`), sorted."""
    seen, todo = set(), list(roots)
    while todo:
        module = todo.pop()
        if module not in seen:
            seen.add(module)
            todo.extend(_package_imports(module))
    return sorted(seen)


def _code_digest(module):
    """The module's syntax tree without docstrings: comments, docstrings and layout do not count."""
    tree = ast.parse(_source(module))
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (isinstance(body, list) and body and isinstance(body[0], ast.Expr)
                and isinstance(body[0].value, ast.Constant)
                and isinstance(body[0].value.value, str)):
            node.body = body[1:] or [ast.Pass()]
    return ast.dump(tree).encode()


@cache
def code_revision(*roots):
    """First 10 hex digits of the SHA-256 of the code of `revision_modules(roots)` (syntax trees
    without docstrings, so editing a comment or a docstring keeps what was stored)."""
    digest = hashlib.sha256()
    for module in revision_modules(roots):
        digest.update(module.encode() + b"\0" + _code_digest(module))
    return digest.hexdigest()[:10]


def solver_revision():
    """The revision of the code that computes a stored curve (REVISION_ROOTS)."""
    return code_revision(*REVISION_ROOTS)



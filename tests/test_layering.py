"""The floor plan holds: each subpackage of fem_asperity imports only from those below it,
scikit-fem only in the FE solid, and the store's revision key covers exactly the code that computes
a curve."""

import ast
import importlib
from pathlib import Path

import pytest

import fem_asperity.plumbing.revision as revision

PACKAGE = Path(importlib.import_module("fem_asperity").__file__).parent
#: Bottom up; a module may import from its own subpackage and from those before it.
LAYERS = ("plumbing", "closed_forms", "curves", "solids", "path", "solver", "studies")
#: The only modules that import scikit-fem: the FE half-space and its mesh.
SKFEM_MODULES = {"solids/fe.py", "solids/mesh.py"}


def _modules():
    return sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)


def _imports(path):
    """(absolute fem_asperity subpackage names, top-level third-party names) imported by `path`."""
    tree = ast.parse(path.read_text())
    package = ".".join(("fem_asperity", *path.relative_to(PACKAGE).parent.parts))
    inside, outside = set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            name = importlib.util.resolve_name("." * node.level + (node.module or ""), package)
            names = [name]
        elif isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        else:
            continue
        for name in names:
            parts = name.split(".")
            if parts[0] == "fem_asperity":
                inside.add(parts[1] if len(parts) > 1 else "")
            else:
                outside.add(parts[0])
    return inside, outside


def _layer(path):
    parts = path.relative_to(PACKAGE).parts
    return LAYERS.index(parts[0]) if len(parts) > 1 else len(LAYERS)


def test_every_subpackage_is_a_known_layer():
    subpackages = {p.parent.name for p in PACKAGE.glob("*/__init__.py")}
    assert subpackages == set(LAYERS)


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(PACKAGE)))
def test_a_module_imports_only_from_its_layer_and_below(path):
    inside, _ = _imports(path)
    layer = _layer(path)
    above = {name for name in inside if name in LAYERS and LAYERS.index(name) > layer}
    assert not above, f"{path.relative_to(PACKAGE)} imports from higher layers {above}"


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(PACKAGE)))
def test_scikit_fem_is_imported_only_by_the_fe_solid(path):
    _, outside = _imports(path)
    relative = path.relative_to(PACKAGE).as_posix()
    assert ("skfem" in outside) == (relative in SKFEM_MODULES)


def test_the_closed_forms_load_without_the_solvers():
    """The closed forms' own imports: numpy, scipy, the standard library and the plumbing."""
    for path in (PACKAGE / "closed_forms").glob("*.py"):
        inside, outside = _imports(path)
        assert inside <= {"plumbing", "closed_forms"}
        assert outside <= {"numpy", "scipy", "dataclasses", "typing", "warnings", "math"}, path


def test_the_refit_is_keyed_by_its_own_code_as_well():
    covered = set(revision.revision_modules(("fem_asperity.studies.refit",)))
    assert {"fem_asperity.studies.refit", "fem_asperity.studies.onset",
            "fem_asperity.closed_forms.laws"} <= covered
    assert set(revision.revision_modules()) <= covered


def test_a_packages_relative_imports_resolve_inside_it():
    """`from .compare import ...` in gw/explicit/__init__.py is gw.explicit.compare, not
    gw.compare (a root that reached the package's __init__ used to fail)."""
    covered = set(revision.revision_modules(("gw.explicit",)))
    assert {"gw.explicit.compare", "gw.explicit.interacting", "gw.explicit.whole"} <= covered


def test_the_revision_key_covers_the_solver_and_not_the_interfaces():
    covered = set(revision.revision_modules())
    for module in ("solver.solve", "solver.presets", "solver.result", "path.continuation",
                   "path.grids", "path.landing", "solids.fe", "solids.bem", "closed_forms.lj",
                   "studies.store"):
        assert f"fem_asperity.{module}" in covered
    for module in ("__main__", "plumbing.cli", "solver.output", "studies.refit",
                   "studies.onset", "closed_forms.laws"):
        assert f"fem_asperity.{module}" not in covered


def _revision_with(monkeypatch, module, edit):
    """solver_revision() after `edit` (text → text) of `module`'s source, read through the hook
    the revision uses (the file on disk is never touched)."""
    origin = Path(importlib.util.find_spec(module).origin)
    real_read = Path.read_bytes

    text = real_read(origin).decode()
    assert edit(text) != text, f"the edit does not apply to {module}"

    def read_bytes(self):
        data = real_read(self)
        return edit(data.decode()).encode() if self == origin else data

    monkeypatch.setattr(Path, "read_bytes", read_bytes)
    revision.code_revision.cache_clear()
    revision._source.cache_clear()
    try:
        return revision.solver_revision()
    finally:
        monkeypatch.undo()
        revision.code_revision.cache_clear()
        revision._source.cache_clear()


def test_editing_help_or_a_plot_keeps_stored_curves_and_editing_the_solver_discards_them(
        monkeypatch):
    revision.code_revision.cache_clear()
    revision._source.cache_clear()
    today = revision.solver_revision()
    help_edit = _revision_with(monkeypatch, "fem_asperity.__main__",
                               lambda s: s.replace('help="print JSON', 'help="write JSON'))
    plot_edit = _revision_with(monkeypatch, "fem_asperity.solver.output",
                               lambda s: s.replace("figsize=(10, 4.5)", "figsize=(11, 4.5)"))
    comment_edit = _revision_with(monkeypatch, "fem_asperity.path.continuation",
                                  lambda s: s.replace('"""', '"""Edited. ', 1) + "\n# a note\n")
    solver_edit = _revision_with(monkeypatch, "fem_asperity.path.surface",
                                 lambda s: s.replace("GAP_KEEP = 0.2", "GAP_KEEP = 0.25"))
    kernel_edit = _revision_with(monkeypatch, "fem_asperity.solids.boussinesq",
                                 lambda s: s + "\nEXTRA = 1\n")
    assert help_edit == plot_edit == comment_edit == today
    assert solver_edit != today and kernel_edit != today


def test_the_distribution_ships_every_subpackage():
    """`pip install .` (not only an editable install) carries each folder of the package."""
    tomllib = pytest.importorskip("tomllib")
    from fnmatch import fnmatch

    config = tomllib.loads((PACKAGE.parent / "pyproject.toml").read_text())
    include = config["tool"]["setuptools"]["packages"]["find"]["include"]
    for init in PACKAGE.rglob("__init__.py"):
        name = ".".join(init.parent.relative_to(PACKAGE.parent).parts)
        assert any(fnmatch(name, pattern) for pattern in include), name

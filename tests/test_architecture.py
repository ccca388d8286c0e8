"""The layers of docs/architecture.md as checked contracts, and no code kept only for tests."""

import importlib.util

import grimp
from importlinter.cli import lint_imports

#: Modules run from outside the package: the command line, and the Python API (``feedtherm``
#: imports it by name, on first use).
ENTRY_POINTS = {"feedtherm.cli", "feedtherm.__main__", "feedtherm.api"}


def test_import_contracts_hold(capsys):
    """pyproject.toml's [tool.importlinter] contracts: layers, pure physics, independent models, a system/ without cycles."""
    result = lint_imports(no_cache=True, no_logo=True)
    report = capsys.readouterr().out
    assert result == 0, report
    assert "0 broken" in report


def test_no_module_is_imported_only_by_tests():
    graph = grimp.build_graph("feedtherm", cache_dir=None)
    orphans = []
    for module in sorted(graph.modules):
        if module in ENTRY_POINTS or importlib.util.find_spec(module).submodule_search_locations is not None:
            continue  # a package is imported through its modules
        if not graph.find_modules_that_directly_import(module):
            orphans.append(module)
    assert orphans == [], f"modules no other module of feedtherm imports: {orphans}"

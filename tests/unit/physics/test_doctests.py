"""The doctest examples of feedtherm.physics: every public function has one, and each holds.

Each example's number is printed in the function's source or worked out by hand in its
docstring (docs/architecture.md, "Naming of correlations").
"""

from __future__ import annotations

import doctest
import importlib
import inspect
import pkgutil

import pytest

from feedtherm import physics

MODULES = [
    importlib.import_module(f"{physics.__name__}.{info.name}")
    for info in pkgutil.iter_modules(physics.__path__)
    if not info.name.startswith("_")
]

FUNCTIONS = [
    (module.__name__, name, obj)
    for module in MODULES
    for name, obj in vars(module).items()
    if inspect.isfunction(obj) and obj.__module__ == module.__name__ and not name.startswith("_")
]

DOCTESTS = [
    test
    for module in MODULES
    for test in doctest.DocTestFinder(exclude_empty=True).find(module)
    if test.examples
]


def has_example(func) -> bool:
    """True when the docstring has a numpydoc ``Examples`` section with a ``>>>`` line."""
    doc = inspect.getdoc(func) or ""
    _, heading, section = doc.partition("\nExamples\n--------\n")
    return bool(heading) and ">>>" in section


def test_every_physics_module_and_function_is_scanned():
    names = {name for _, name, _ in FUNCTIONS}
    assert {"air", "bearings", "screw_nut", "validity"} <= {m.__name__.rsplit(".", 1)[1] for m in MODULES}
    assert {"heat_bearing", "Nu_natural_horizontal_cylinder_Morgan", "check_range"} <= names
    assert len(DOCTESTS) >= len(FUNCTIONS)


@pytest.mark.parametrize(("module", "name", "func"), FUNCTIONS, ids=[f"{m}.{n}" for m, n, _ in FUNCTIONS])
def test_public_function_has_an_example(module, name, func):
    assert has_example(func), f"{module}.{name} has no doctest example (numpydoc 'Examples' with >>>)"


def test_has_example_rejects_a_docstring_without_one():
    def documented():
        """Heat.

        Examples
        --------
        >>> 1 + 1
        2
        """

    def undocumented():
        """Heat, with an inline >>> but no Examples section."""

    assert has_example(documented)
    assert not has_example(undocumented)
    assert not has_example(lambda: None)


@pytest.mark.parametrize("test", DOCTESTS, ids=[t.name for t in DOCTESTS])
def test_example_holds(test):
    report: list[str] = []
    result = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE).run(test, out=report.append)
    assert result.failed == 0, "".join(report)

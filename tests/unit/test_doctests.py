"""The examples in the package's docstrings run (as ``--doctest-modules`` would run them):
an example that no longer matches the code fails here."""

import doctest
import importlib
import pkgutil

import pytest

import exubrush

# __main__ runs the command line when imported
MODULES = ["exubrush", *sorted(m.name for m in pkgutil.walk_packages(exubrush.__path__,
                                                                    "exubrush.")
                                if not m.name.endswith("__main__"))]


def _doctests(name):
    return [t for t in doctest.DocTestFinder().find(importlib.import_module(name))
            if t.examples]


WITH_EXAMPLES = [name for name in MODULES if _doctests(name)]


def test_the_package_has_examples_to_run():
    # exubrush itself, simulation, reference.elastica: finding none means the finder broke
    assert len(WITH_EXAMPLES) >= 3, WITH_EXAMPLES


@pytest.mark.parametrize("name", WITH_EXAMPLES)
def test_docstring_examples(name):
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    for test in _doctests(name):
        runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples failed in {name}"

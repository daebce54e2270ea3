"""Small modules and functions of one job: none over the sizes docs/architecture.md states,
but the references' numerics it names (they follow their derivations step by step)."""

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "exubrush"
MODULE_LINES, FUNCTION_LINES = 500, 80
# docs/architecture.md, "Sizes": each with why it stays
LONG_FUNCTIONS = {
    ("reference/elastica.py", "solve_cantilever"),
    ("reference/elastica.py", "_newton_shooting"),
    ("reference/touching_cantilevers.py", "touching_cantilevers"),
}


def _sizes():
    for path in sorted(PACKAGE.rglob("*.py")):
        source = path.read_text(encoding="utf-8")
        name = path.relative_to(PACKAGE).as_posix()
        functions = [(node.name, node.end_lineno - node.lineno + 1)
                     for node in ast.walk(ast.parse(source))
                     if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)]
        yield name, source.count("\n"), functions


def test_no_module_is_longer_than_the_layout_allows():
    long = [(name, lines) for name, lines, _ in _sizes() if lines > MODULE_LINES]
    assert long == []


def test_no_function_is_longer_than_one_job_needs():
    long = {(name, function) for name, _, functions in _sizes()
            for function, lines in functions if lines > FUNCTION_LINES}
    assert long == LONG_FUNCTIONS  # a new one is split, or named here and in the docs

"""Imports run one way, and importing exubrush changes nothing in the importer's process.

The contracts (layers from the parameters up to the command line; pure modules free of
Exudyn and pint) are in pyproject.toml under [tool.importlinter].
"""

import pkgutil
import subprocess
import sys
import tomllib
from pathlib import Path

import grimp

import exubrush

ROOT = Path(__file__).parents[2]  # where pyproject.toml holds the contracts


def fresh_python(script: str, cwd: Path | None = None) -> str:
    """Standard output of ``script`` run in a new interpreter (modules it imports are not
    yet loaded); fails the test with the interpreter's errors if it fails."""
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120, cwd=cwd)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-2000:]
    return done.stdout.strip()


def test_import_contracts_hold():
    script = ("import sys; from importlinter.cli import lint_imports; "
              "sys.exit(lint_imports(no_cache=True))")
    assert "0 broken" in fresh_python(script, cwd=ROOT)


def import_edges(type_only: bool = True) -> dict[str, set[str]]:
    """Each exubrush module and the exubrush modules it imports, function-local imports
    counted and, if ``type_only``, those under ``if TYPE_CHECKING`` (the import-linter
    contracts see the same graph)."""
    graph = grimp.build_graph("exubrush", include_external_packages=False, cache_dir=None,
                              exclude_type_checking_imports=not type_only)
    return {module: set(graph.find_modules_directly_imported_by(module))
            for module in graph.modules}


def contracts() -> list[dict]:
    """The import-linter contracts of pyproject.toml."""
    with open(ROOT / "pyproject.toml", "rb") as file:
        return tomllib.load(file)["tool"]["importlinter"]["contracts"]


def package_edges(edges: dict[str, set[str]]) -> dict[str, set[str]]:
    """The same imports between packages (``exubrush.run``) and top-level modules
    (``exubrush.cli``); the package's own ``__init__`` (the lazy top-level API) left out."""
    def package(module: str) -> str:
        return ".".join(module.split(".")[:2])

    found: dict[str, set[str]] = {}
    for importer, imported in edges.items():
        if importer == "exubrush":
            continue
        targets = {package(m) for m in imported} - {"exubrush", package(importer)}
        found.setdefault(package(importer), set()).update(targets)
    return found


def circles(edges: dict[str, set[str]]) -> list[tuple[str, str]]:
    """Every import ``(a, b)`` of ``edges`` from which ``a`` is reached again."""
    def reached(start: str) -> set[str]:
        seen: set[str] = set()
        todo = [start]
        while todo:
            for nxt in edges.get(todo.pop(), ()):
                if nxt not in seen:
                    seen.add(nxt)
                    todo.append(nxt)
        return seen

    return sorted((a, b) for a, targets in edges.items() for b in targets if a in reached(b))


def test_circles_finds_a_circle_and_only_it():
    edges = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set()}
    assert circles(edges) == [("a", "b"), ("b", "c"), ("c", "a")]
    assert package_edges({"exubrush.x.m": {"exubrush.y.n", "exubrush.x.k"},
                          "exubrush": {"exubrush.x.m"}}) == {"exubrush.x": {"exubrush.y"}}


def test_no_circle_between_modules():
    assert circles(import_edges()) == []


def test_no_circle_between_packages():
    assert circles(package_edges(import_edges())) == []


def test_the_layers_are_one_row_per_package_with_type_only_imports_counted():
    with open(ROOT / "pyproject.toml", "rb") as file:
        assert not tomllib.load(file)["tool"]["importlinter"]["exclude_type_checking_imports"]
    (layers,) = [c["layers"] for c in contracts() if c["type"] == "layers"]
    named = [name.strip() for row in layers for name in row.split("|")]
    packages = {".".join(m.split(".")[:2]) for m in import_edges()} - {"exubrush",
                                                                      "exubrush.__main__"}
    assert sorted(named) == sorted(packages)  # each package in one row, nothing finer


def test_imports_the_pure_modules_contract_ignores_are_type_only():
    """The forbidden contracts count type-only imports too; the few they ignore must load
    nothing at run time."""
    ignored = [line for c in contracts() for line in c.get("ignore_imports", [])]
    every, at_run_time = import_edges(), import_edges(type_only=False)
    assert ignored  # the contracts were read
    for line in ignored:
        importer, imported = (name.strip() for name in line.split("->"))
        assert imported in every[importer], line
        assert imported not in at_run_time[importer], f"{line} is imported at run time"


def test_importing_every_module_keeps_the_matplotlib_backend():
    modules = [m.name for m in pkgutil.walk_packages(exubrush.__path__, "exubrush.")
               if not m.name.endswith("__main__")]
    script = ("import matplotlib; matplotlib.use('svg'); import importlib\n"
              f"for name in {modules!r}: importlib.import_module(name)\n"
              "print(matplotlib.get_backend())")
    assert fresh_python(script) == "svg"
    assert len(modules) > 30  # the walk found the package, not an empty path


def test_the_top_level_api_is_lazy_and_complete():
    script = ("import sys, exubrush\n"
              "assert 'exudyn' not in sys.modules, 'import exubrush loaded Exudyn'\n"
              "for name in exubrush.__all__: getattr(exubrush, name)\n"
              "print(exubrush.__version__)")
    from importlib.metadata import version

    assert fresh_python(script) == version("exubrush")


def test_a_built_in_case_is_read_and_shown_without_pint_or_scipy():
    """`exubrush case` and a run's start read built-in cases: pint's and SciPy's imports
    (about a second) are for unit texts and solvers they do not use."""
    script = ("import sys\n"
              "from exubrush.parameters.io import load_case\n"
              "from exubrush.parameters.fields import to_toml\n"
              "to_toml(load_case('orthogonal', ['motion.periods=1']))\n"
              "print(sorted({'pint', 'scipy'} & set(sys.modules)))")
    assert fresh_python(script) == "[]"

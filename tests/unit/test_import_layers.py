"""Imports run one way, and importing exubrush changes nothing in the importer's process.

The contracts (layers from the parameters up to the command line; pure modules free of
Exudyn and pint) are in pyproject.toml under [tool.importlinter].
"""

import pkgutil
import subprocess
import sys
from pathlib import Path

import exubrush

ROOT = Path(__file__).parents[2]  # where pyproject.toml holds the contracts


def test_import_contracts_hold():
    script = ("import sys; from importlinter.cli import lint_imports; "
              "sys.exit(lint_imports(no_cache=True))")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120, cwd=ROOT)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-2000:]
    assert "0 broken" in done.stdout


def test_importing_every_module_keeps_the_matplotlib_backend():
    modules = [m.name for m in pkgutil.walk_packages(exubrush.__path__, "exubrush.")
               if not m.name.endswith("__main__")]
    script = ("import matplotlib; matplotlib.use('svg'); import importlib\n"
              f"for name in {modules!r}: importlib.import_module(name)\n"
              "print(matplotlib.get_backend())")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "svg"
    assert len(modules) > 30  # the walk found the package, not an empty path


def test_the_top_level_api_is_lazy_and_complete():
    script = ("import sys, exubrush\n"
              "assert 'exudyn' not in sys.modules, 'import exubrush loaded Exudyn'\n"
              "for name in exubrush.__all__: getattr(exubrush, name)\n"
              "print(exubrush.__version__)")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    from importlib.metadata import version

    assert done.stdout.strip() == version("exubrush")

"""exubrush runs on Exudyn's fast build unless asked for the checked one, and says nothing
about it on standard output. Each case runs in a fresh interpreter: the build is chosen at
the first import of exudyn in a process."""

import os
import subprocess
import sys

import pytest

from exubrush.util.exudyn_build import CHECKS_VARIABLE, wants_checked_build

REPORT = ("import sys\n{before}\nimport exubrush, exudyn\n"
          "from exubrush.util.exudyn_build import build_in_use\n"
          "print(exudyn._compiledModuleName, build_in_use())")


def _cpu_has_avx2() -> bool:
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            return " avx2" in cpuinfo.read()
    except OSError:
        return False


def _run(before: str = "", **environ: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in (CHECKS_VARIABLE, "EXUDYN_MODULE")}
    env.update(environ)
    return subprocess.run([sys.executable, "-c", REPORT.format(before=before)],
                          capture_output=True, text=True, timeout=120, env=env)


@pytest.mark.skipif(not _cpu_has_avx2(), reason="Exudyn's fast build needs AVX2")
def test_the_fast_build_is_loaded_silently_by_default():
    done = _run()
    assert done.returncode == 0, done.stderr
    # Exudyn's "Imported exudyn fast version" line is gone: only our report is printed
    assert done.stdout.splitlines() == ["exudynCPPfast fast"]


def test_the_environment_asks_for_the_checked_build():
    done = _run(**{CHECKS_VARIABLE: "1"})
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["exudynCPP checked"]


def test_a_program_that_chose_a_build_keeps_it():
    done = _run(before="sys.exudynFast = False")
    assert done.stdout.splitlines() == ["exudynCPP checked"], done.stderr
    done = _run(before="import exudyn")  # imported before exubrush: nothing changes
    assert done.stdout.splitlines() == ["exudynCPP checked"], done.stderr


@pytest.mark.parametrize(("value", "checked"), [("1", True), ("true", True), (" YES ", True),
                                                ("0", False), ("", False), ("no", False)])
def test_the_checks_variable_is_read_as_a_switch(value, checked):
    assert wants_checked_build({CHECKS_VARIABLE: value}) is checked
    assert wants_checked_build({}) is False

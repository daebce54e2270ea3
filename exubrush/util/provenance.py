"""Which code made a result: the package version and, in a git checkout, the commit."""

from __future__ import annotations

import functools
import subprocess
from importlib import metadata
from pathlib import Path

UNKNOWN_VERSION = "0+unknown"  # running from a source tree that was never installed


@functools.cache
def package_version(name: str = "exubrush") -> str:
    """The version of the installed package ``name`` from its metadata (for exubrush, the
    one version source), read without importing the package."""
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return UNKNOWN_VERSION


@functools.cache
def git_commit() -> str | None:
    """The commit of the checkout the package runs from, with ``+dirty`` if it has
    uncommitted changes; None when it does not run from a git checkout (an installed
    wheel) or git is missing."""
    source = Path(__file__).resolve().parent.parent
    if not (source / ".git").exists():
        return None
    try:
        commit = subprocess.run(["git", "-C", str(source), "rev-parse", "HEAD"],
                                capture_output=True, text=True, timeout=10, check=True)
        status = subprocess.run(["git", "-C", str(source), "status", "--porcelain",
                                 "--untracked-files=no"],
                                capture_output=True, text=True, timeout=10, check=True)
    except (OSError, subprocess.SubprocessError):
        return None
    return commit.stdout.strip() + ("+dirty" if status.stdout.strip() else "")


def code_identity() -> dict[str, str | None]:
    """``{"exubrush": version, "commit": commit or None}``, recorded with runs and
    checkpoints."""
    return {"exubrush": package_version(), "commit": git_commit()}

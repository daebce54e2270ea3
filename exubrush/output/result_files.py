"""A run's results written into a directory, each file complete or absent (see
:func:`write_results`); :class:`~exubrush.output.results.Results` holds what is written."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from exubrush.output.cleaning import part_names
from exubrush.util.files import atomic_file, write_csv

RESULT_FILES = ("forces.csv", "shapes.npz", "forces.png", "tips.npz", "summary.json",
                "cleaning.png", "vibration.png", "tufts.csv")
# the files written only with tip data, whose older copies go first
_TIP_FILES = ("tips.npz", "summary.json", "cleaning.png", "vibration.png", "tufts.csv")


def write_results(results, directory: str | Path) -> Path:
    """Write forces.csv, run.json, shapes.npz, forces.png and, with tip data, tips.npz,
    summary.json (cleaning metrics) and cleaning.png of ``results`` (a
    :class:`~exubrush.output.results.Results`) into ``directory``.

    Each file is written to a temporary file first and renamed, so a file on disk is
    either complete or absent. Results without any time series (a run interrupted
    before every bristle started) write run.json only and remove older result files,
    so files of different runs never sit side by side. run.json is written last: its
    ``status`` describes the files beside it.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    (directory / "run.json").unlink(missing_ok=True)  # no status while files change
    if len(results.time) == 0:
        for name in RESULT_FILES:
            (directory / name).unlink(missing_ok=True)
        _write_metadata(results.metadata, directory)
        return directory
    _write_records(results, directory)
    for name in _TIP_FILES:
        (directory / name).unlink(missing_ok=True)
    if results.cleaning() is not None:
        _write_tip_files(results, directory)
    _write_metadata(results.metadata, directory)
    return directory


def _write_records(results, directory: Path) -> None:
    """forces.csv, shapes.npz and forces.png."""
    from exubrush.output.plotting import plot_forces  # matplotlib when drawn

    columns = results.columns()
    write_csv(directory / "forces.csv", list(columns), zip(*columns.values(), strict=True))
    with atomic_file(directory / "shapes.npz", "wb") as handle:
        extra = {} if results.shape_coordinates is None else {
            "coordinates": results.shape_coordinates}
        np.savez_compressed(handle, time=results.shape_time, nodes=results.shape_nodes,
                            **extra)
    with atomic_file(directory / "forces.png", "wb") as handle:
        plot_forces(results, handle)


def _write_tip_files(results, directory: Path) -> None:
    """tips.npz, summary.json, cleaning.png and, where they apply, tufts.csv and
    vibration.png: what the tips did."""
    from exubrush.output.plotting import plot_cleaning, plot_vibration  # matplotlib

    summary, contacts = results.cleaning(), results.tip_contacts
    with atomic_file(directory / "tips.npz", "wb") as handle:
        np.savez_compressed(handle, time=results.time, position=results.tip_position,
                            force=results.tip_force, in_contact=contacts.touching,
                            part=np.where(contacts.touching, contacts.parts, -1),
                            part_names=np.array(part_names(results.case().surface)))
    vibration, amplitudes = results.vibration()
    extra = {"vibration": vibration} if vibration else {}
    with atomic_file(directory / "summary.json", "w") as handle:
        json.dump({"data_origin": results.metadata.get("data_origin", ""),
                   "cleaning": summary, **extra}, handle, indent=2)
    with atomic_file(directory / "cleaning.png", "wb") as handle:
        plot_cleaning(results, summary, contacts, handle)
    tufts = results.tuft_columns()
    if tufts:
        write_csv(directory / "tufts.csv", list(tufts), zip(*tufts.values(), strict=True))
    if any(a is not None for a in amplitudes):
        with atomic_file(directory / "vibration.png", "wb") as handle:
            plot_vibration(results, vibration, amplitudes, handle)


def _write_metadata(metadata: dict, directory: Path) -> None:
    with atomic_file(directory / "run.json", "w") as handle:
        json.dump(metadata, handle, indent=2, default=_json_default)


def _json_default(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"cannot write {type(value).__name__} to JSON")

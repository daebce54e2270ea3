"""Command line: ``exubrush run``, ``sweep``, ``case``, ``compare``, ``frames`` and ``view``.

Every fault ends in one line on standard error and an exit status: 2 for input that cannot
be used (a parameter, case file, CSV or path), 1 for a run that failed or results that
could not be written, 130 for Ctrl-C or SIGTERM. A file-system fault anywhere (a path under
a plain file, a directory that cannot be written, a full disk, a dangling link, a file that
is not text) is reported with the path and the reason, never as a traceback.
"""

from __future__ import annotations

import contextlib
import signal
import sys
import threading
from pathlib import Path

import click

from exubrush.presets import PRESETS, preset_overrides

# Each command imports what it uses (parameters, numpy, Exudyn, matplotlib), so that
# `exubrush --help` and `exubrush case` start in a fraction of a second.

INPUT_ERROR, RUN_FAILED, INTERRUPTED = 2, 1, 130


def _fail(message: str, status: int = INPUT_ERROR) -> None:
    click.echo(f"exubrush: error: {' '.join(message.split())}", err=True)
    sys.exit(status)


def os_message(err: OSError) -> str:
    """``path: reason`` of a file-system error (both paths of a failed rename)."""
    paths = [str(p) for p in (err.filename, err.filename2) if p is not None]
    reason = err.strerror or type(err).__name__
    return f"{' -> '.join(paths)}: {reason}" if paths else reason


class _Commands(click.Group):
    """The command group: faults that can reach any command end in one line."""

    def invoke(self, ctx):
        try:
            return super().invoke(ctx)
        except OSError as err:
            _fail(os_message(err))
        except UnicodeDecodeError as err:  # e.g. a run.json that is not text
            _fail(f"a file is not UTF-8 text ({err.reason} at byte {err.start})")
        except KeyboardInterrupt:
            _fail("interrupted before the run started; nothing was written",
                  INTERRUPTED)


@click.group(cls=_Commands, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="exubrush")
def main() -> None:
    """Toothbrush bristle deflection and contact forces with Exudyn."""


@main.command()
@click.argument("case")
@click.option("--model", type=click.Choice(["dfm", "prb"]), help="Bristle model [default: dfm].")
@click.option("--segments", type=int, help="DFM rigid bodies per bristle [default: 6].")
@click.option("--periods", type=float,
              help="Slide periods after the approach [default: 2].")
@click.option("--out", type=click.Path(), help="Result directory "
              "[default: results/CASE-MODEL].")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help="Override a parameter by its dotted key, e.g. --set head.rows=2 "
                   "or --set head.material.youngs_modulus='10 MPa'.")
@click.option("--overwrite", is_flag=True,
              help="Replace exubrush results already in --out (other files are never touched).")
@click.option("--quiet", is_flag=True, help="No progress bar.")
@click.option("--preset", type=click.Choice(list(PRESETS)),
              help="Solver settings from the measured run-time/error front: fast, balanced "
                   "(= the defaults) or accurate; --segments and --set override it.")
@click.option("--viewer", is_flag=True, help="Also keep every node's coordinates at the "
              "shape interval, to open the run with 'exubrush view' (output.solution_file = true).")
@click.option("--scheduler", metavar="ADDRESS", help="Solve the bristle groups on a Dask "
              "cluster: tcp://HOST:PORT of its scheduler, or 'local' for one started here "
              "[default: a process pool on this machine].")
@click.option("--workers", type=click.IntRange(min=1),
              help="Processes of the local pool or local Dask cluster [default: every core].")
def run(case, model, segments, periods, out, overrides, overwrite, quiet, preset, viewer,
        scheduler, workers):
    """Simulate CASE (a built-in case, e.g. orthogonal, tuft or robot, or a TOML case file)
    and save the results.

    Finished bristles are kept in OUT/.checkpoint while the run goes on: after Ctrl-C, a
    kill or a crash, the same command resumes where it stopped.
    """
    shortcuts = [f"model.kind={model!r}" if model else None,
                 f"model.segments={segments}" if segments is not None else None,
                 f"motion.periods={periods}" if periods is not None else None,
                 "output.solution_file=true" if viewer else None]
    prepared = _prepared(case, [*preset_overrides(preset), *filter(None, shortcuts),
                                *overrides])
    from exubrush.execution.signals import signals_redirected
    from exubrush.output.rundir import RunDirectory, RunDirectoryError, default_directory
    from exubrush.simulation import simulate

    directory = Path(out or default_directory(prepared.case))
    try:
        store = RunDirectory(directory, prepared, overwrite)
    except RunDirectoryError as err:
        _fail(str(err))
    if store.resumed:
        click.echo(f"resuming: {store.resumed} finished bristle groups read from "
                   f"{store.checkpoint}", err=True)
    # Ctrl-C or SIGTERM while solving: the executor stops the solves, keeps what finished
    # and returns; one that arrives after it (assembling, writing: a second or two) is let
    # pass, so the results are written whole
    threading.Thread(target=_load_plotting, daemon=True).start()
    try:
        with signals_redirected(signal.SIG_IGN), _executor(scheduler, workers) as executor:
            if executor is not None:
                click.echo(f"solving on {executor.describe()}", err=True)
            results = simulate(prepared, progress=not quiet, directory=store, workers=workers,
                               executor=executor)
            results.save(directory)
    except OSError as err:
        _fail(f"results not written: {os_message(err)}; the finished bristles stay in "
              f"{store.checkpoint}: free the space or fix the directory and run the same "
              "command again to resume", RUN_FAILED)
    _report(results, store, directory)


def _prepared(case: str, overrides: list[str]):
    """The run's PreparedCase from the case name or file and its ``--set`` overrides, its
    warnings told on standard error; a bad input ends the command (one line, exit 2)."""
    from exubrush.parameters.fields import ParameterError
    from exubrush.parameters.io import load_case
    from exubrush.run.prepared import prepare
    from exubrush.util.units import UnitError

    try:
        prepared = prepare(load_case(case, overrides))
    except (ParameterError, UnitError) as err:
        _fail(str(err))
    for warning in prepared.warnings:
        click.echo(f"exubrush: warning: {warning}", err=True)
    # some but not all: a head none of whose bristles reach has its own warning (it
    # moves in the air, exubrush.run.prepared.in_the_air)
    if 0 < prepared.unreachable < len(prepared.bristles):
        click.echo(f"exubrush: warning: {prepared.unreachable} of {len(prepared.bristles)} "
                   "bristles cannot reach the surface at motion.interaction_distance = "
                   f"{prepared.case.motion.interaction_distance:g} mm; they get no contact",
                   err=True)
    twins = len(prepared.groups) - len(prepared.solved_groups)
    if twins:
        click.echo(f"{len(prepared.solved_groups)} of {len(prepared.groups)} bristle systems to "
                   f"solve: the other {twins} are twins of those, moving alike along the plane "
                   "(solver.share_identical)", err=True)
    return prepared


def _report(results, store, directory: Path) -> None:
    """Say how the run ended (warnings and notes on standard error); exit 130 for an
    interrupted run, 1 for a failed one (its partial results are saved)."""
    meta = results.metadata
    sanity = meta["sanity"]
    if sanity["peak_normal_force_N"] > sanity["normal_force_bound_N"]:
        click.echo(f"exubrush: warning: peak normal force {sanity['peak_normal_force_N']:.4g} N "
                   f"exceeds the physical bound {sanity['normal_force_bound_N']:.4g} N (every "
                   "bristle straight and fully compressed, x2, and the inertia allowance): "
                   "the result is not physical; "
                   "see run.json 'sanity'", err=True)
    retried = meta["derived"].get("systems_retried", 0)
    if retried:
        click.echo(f"exubrush: note: {retried} bristle system(s) failed with modified Newton "
                   "and were solved again with solver.modified_newton = false (run.json "
                   "'derived')", err=True)
    if meta["status"] == "completed":
        store.close()
        click.echo(f"completed: {meta['simulated_time_s']:.2f} s simulated in "
                   f"{meta['wall_time_s']:.1f} s wall time; results in {directory}/ "
                   "(forces.csv, run.json, forces.png, shapes.npz, tips.npz, summary.json, "
                   "cleaning.png)")
        return
    saved = (f"partial results up to t = {meta['simulated_time_s']:.4g} s in {directory}/"
             if len(results.time) else f"no complete time series yet; status in {directory}/")
    click.echo(f"exubrush: {meta['status']}: {meta['message']}; {saved} (run.json: status "
               f"{meta['status']!r})", err=True)
    sys.exit(INTERRUPTED if meta["status"] == "interrupted" else RUN_FAILED)


def _load_plotting() -> None:
    """Import matplotlib and its PNG writer while the workers solve (the command's process
    waits for them): about a second of the results' writing, taken off the run's end."""
    import matplotlib.backends.backend_agg  # noqa: F401 - imported for its side effect
    from matplotlib import font_manager

    import exubrush.output.plotting  # noqa: F401

    font_manager.findfont(font_manager.FontProperties())


@contextlib.contextmanager
def _executor(scheduler: str | None, workers: int | None, timeout: float | None = None,
              label: str = "--scheduler"):
    """The Dask executor ``scheduler`` asks for (None: the local process pool); a cluster
    that cannot be reached ends the command with exit status 2, before anything is written."""
    if scheduler is None:
        yield None
        return
    from exubrush.execution.cluster import CONNECT_TIMEOUT, ClusterError, dask_executor

    with contextlib.ExitStack() as stack:
        try:
            executor = stack.enter_context(
                dask_executor(scheduler, workers, timeout or CONNECT_TIMEOUT, label))
        except ClusterError as err:
            _fail(str(err))
        yield executor


@main.command()
@click.argument("sweep_file", required=False, type=click.Path())
@click.option("--out", type=click.Path(),
              help="Sweep folder [default: results/sweeps/NAME].")
@click.option("--scheduler", metavar="ADDRESS", help="tcp://HOST:PORT of a Dask scheduler, "
              "or 'local' for a Dask cluster started here [default: the sweep file's "
              "execution.scheduler, else local].")
@click.option("--workers", type=click.IntRange(min=1),
              help="Worker processes of a local cluster [default: every core].")
@click.option("--retry-failed", is_flag=True, help="Solve failed runs again (their finished "
              "bristles are kept); without it they stay failed.")
@click.option("--quiet", is_flag=True, help="No progress bar.")
@click.option("--example", is_flag=True, help="Print a commented sweep file and exit.")
def sweep(sweep_file, out, scheduler, workers, retry_failed, quiet, example):
    """Run the design sweep SWEEP_FILE: every run a run folder, one summary table.

    All runs' bristle groups go into one queue on a Dask cluster (a local one by default).
    Running the same command again skips finished runs and bristles; Ctrl-C stops cleanly
    and keeps every finished run.
    """
    if example:
        from exubrush.sweep.example import EXAMPLE

        click.echo(EXAMPLE, nl=False)
        return
    if sweep_file is None:
        _fail("give a sweep file (exubrush sweep --example prints one)")
    from exubrush.execution.signals import signals_redirected
    from exubrush.output.rundir import RunDirectoryError
    from exubrush.sweep.plan import SweepError, read_sweep
    from exubrush.sweep.runner import check_folder, default_folder, prepare_runs, run_sweep

    try:
        plan = read_sweep(sweep_file)
        prepared = prepare_runs(plan)
        folder = Path(out or default_folder(plan))
        check_folder(folder, plan, prepared)
    except SweepError as err:
        _fail(str(err))
    for warning in sorted({w for case in prepared for w in case.warnings}):
        click.echo(f"exubrush: warning: {warning}", err=True)
    execution = plan.execution
    label = "--scheduler" if scheduler else f"{Path(sweep_file).name}: execution.scheduler"
    groups = sum(len(case.solved_groups) for case in prepared)
    seconds = sum(c.motion.end_time * len(group) for c in prepared for _, group in c.solved_groups)
    click.echo(f"sweep {plan.name}: {len(plan.runs)} runs, {groups} bristle groups, "
               f"{seconds:.4g} bristle-seconds to simulate; folder {folder}/", err=True)
    try:
        with (signals_redirected(signal.SIG_IGN),
              _executor(scheduler or execution.scheduler, workers or execution.workers,
                        execution.timeout, label) as executor):
            click.echo(f"solving on {executor.describe()}", err=True)
            outcome = run_sweep(plan, folder, executor, retry_failed, not quiet, prepared)
    except (SweepError, RunDirectoryError) as err:
        _fail(str(err))
    except OSError as err:
        _fail(f"sweep results not written: {os_message(err)}; finished runs are kept: fix "
              "the cause and run the same command again to resume", RUN_FAILED)
    counts = outcome.counts
    click.echo(f"{counts['completed']} completed, {counts['failed']} failed, "
               f"{counts['interrupted']} unfinished ({outcome.skipped} done before); "
               f"{outcome.wall_time:.1f} s; summary in {folder}/ "
               f"({', '.join(outcome.written[:3])}, ...)")
    if outcome.interrupted:
        _fail("interrupted: finished runs are kept; run the same command again to resume",
              INTERRUPTED)
    if counts["failed"]:
        _fail(f"{counts['failed']} runs failed (status and message in their run.json); "
              "'--retry-failed' solves them again", RUN_FAILED)


@main.command()
@click.argument("case")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help="Override a parameter before printing.")
def case(case, overrides):
    """Print CASE as a complete TOML case file, every parameter with its unit."""
    from exubrush.parameters.fields import ParameterError, to_toml
    from exubrush.parameters.io import load_case
    from exubrush.util.units import UnitError

    try:
        click.echo(to_toml(load_case(case, overrides)), nl=False)
    except (ParameterError, UnitError) as err:
        _fail(str(err))


@main.command()
@click.argument("results_dir", type=click.Path())
@click.argument("measured_csv", type=click.Path())
@click.option("--out", type=click.Path(),
              help="Where to write the comparison [default: RESULTS_DIR/compare-CSVNAME].")
@click.option("--align", "alignment", type=click.Choice(["time", "position"]), default="time",
              show_default=True, help="time: measured time + --time-offset is simulation "
              "time; position: fit the offset so that the slider positions match.")
@click.option("--time-offset", type=float, default=0.0, show_default=True, metavar="SECONDS",
              help="Added to the measured time (the start of the search with --align position).")
@click.option("--flat-speed", type=float, default=0.8, show_default=True, metavar="FRACTION",
              help="Flat zone: slide speed at least FRACTION of the stroke's peak speed.")
@click.option("--invert", multiple=True,
              type=click.Choice(["slider_position", "normal_force", "tangential_force"]),
              help="Flip the sign of a measured channel recorded the other way (repeatable).")
def compare(results_dir, measured_csv, out, alignment, time_offset, flat_speed, invert):
    """Compare the forces of RESULTS_DIR with a measured CSV.

    MEASURED_CSV has the columns time, slider_position, normal_force and tangential_force,
    each with its unit in the header, e.g. 'normal_force [mN]' (see validation/data/README.md).
    Writes comparison.md, comparison.json and compare_*.png.
    """
    from exubrush.output.compare_report import write_comparison
    from exubrush.output.experiment import (
        Alignment,
        ForceSeries,
        align,
        declares_model_output,
        read_measured_csv,
        strokes,
    )
    from exubrush.output.experiment import compare as compare_series
    from exubrush.output.results import ResultsError, read_results

    try:
        results = read_results(results_dir)
        measured = read_measured_csv(measured_csv)
        simulated = ForceSeries.from_results(results)
        settings = Alignment(time_offset=time_offset, by_position=alignment == "position",
                             signs=tuple((channel, -1.0) for channel in invert))
        aligned = align(simulated, measured, settings)
        found = strokes(simulated.time, simulated.slide_velocity, flat_speed)
    except (ResultsError, ValueError) as err:
        _fail(str(err))
    comparison = compare_series(aligned, found)
    directory = Path(out or Path(results_dir) / f"compare-{Path(measured_csv).stem}")
    sources = {"simulation": str(results_dir), "measurement": str(measured_csv),
               "model": results.metadata.get("model", "?"),
               "alignment": ("fitted to the slider positions" if settings.by_position
                             else "given"),
               "model_output": declares_model_output(measured_csv)}
    if results.metadata.get("status", "completed") != "completed":
        click.echo(f"exubrush: warning: the run in {results_dir} is "
                   f"{results.metadata.get('status')}; only its saved part is compared",
                   err=True)
    written = write_comparison(aligned, comparison, directory, sources, flat_speed)
    largest = comparison["largest_flat_difference"]
    if largest["normal_force"] is None:
        click.echo("exubrush: warning: no stroke has its whole flat zone inside the "
                   "measurement; check --time-offset or use --align position", err=True)
    else:
        click.echo(f"{len(comparison['strokes'])} strokes compared; largest flat-zone "
                   "difference (simulation - measurement): "
                   f"F_n {100 * largest['normal_force']:+.1f} %, "
                   f"F_t {100 * largest['tangential_force']:+.1f} %")
    click.echo(f"written to {directory}/: {', '.join(written)}")


def _parse_times(text: str | None) -> list[float] | None:
    if text is None:
        return None
    try:
        return [float(item) for item in text.split(",") if item.strip()]
    except ValueError:
        _fail(f"--times takes simulated times in seconds separated by commas, e.g. "
              f"'7.2,10.2', not {text!r}")


@main.command()
@click.argument("results_dirs", nargs=-1, required=True, type=click.Path())
@click.option("--times", help="Simulated times [s] of the PNG frames, comma separated "
              "[default: 8 instants spread over the run].")
@click.option("--out", type=click.Path(),
              help="Where to write the frames [default: first RESULTS_DIR/frames].")
@click.option("--gif-frames", type=click.IntRange(min=0), default=120, show_default=True,
              help="Frames of the animated GIF through all stored shapes (0: no GIF).")
def frames(results_dirs, times, out, gif_frames):
    """Draw the bristles of one or more runs side by side (PNG frames and a GIF).

    Give a DFM and a PRB run of the same case to compare them frame by frame. To explore a
    run interactively instead, use 'exubrush run --viewer' and 'exubrush view'.
    """
    import numpy as np

    from exubrush.output.frames import load_shapes, write_animation, write_frames
    from exubrush.output.results import ResultsError

    requested = _parse_times(times)
    try:
        runs = [load_shapes(directory) for directory in results_dirs]
    except ResultsError as err:
        _fail(str(err))
    start = max(run.time[0] for run in runs)
    end = min(run.time[-1] for run in runs)
    if end < start:
        _fail("the runs share no time span; frames need overlapping shape samples")
    if requested is None:
        requested = list(np.linspace(start, end, 8))
    outside = [t for t in requested if not start <= t <= end]
    if outside:
        _fail(f"--times {', '.join(f'{t:g}' for t in outside)} s lie outside the stored "
              f"shapes ({start:g} to {end:g} s)")
    directory = Path(out or Path(results_dirs[0]) / "frames")
    directory.mkdir(parents=True, exist_ok=True)
    written = write_frames(runs, requested, directory)
    if gif_frames:
        stored = runs[0].time[(runs[0].time >= start) & (runs[0].time <= end)]
        picked = stored[np.unique(np.linspace(0, stored.size - 1, gif_frames).round()
                                  .astype(int))]
        from tqdm import tqdm

        with tqdm(total=len(picked), desc="animated GIF", unit="frame") as bar:
            write_animation(runs, picked, directory / "bristles.gif",
                            progress=lambda i, n: bar.update(1))
        written.append("bristles.gif")
    click.echo(f"written to {directory}/: {len(written)} files ({written[0]} ... "
               f"{written[-1]})")


@main.command()
@click.argument("results_dir", type=click.Path())
@click.option("--write-only", is_flag=True,
              help="Write the solution file and do not open a window.")
def view(results_dir, write_only):
    """Open a run of 'exubrush run --viewer' in Exudyn's SolutionViewer.

    Writes RESULTS_DIR/exudyn-solution.txt (every node's coordinates at the shape
    interval, the whole head as one Exudyn system) and, where a display is available,
    opens Exudyn's renderer with the SolutionViewer dialog on it.
    """
    from exubrush.output.results import ResultsError
    from exubrush.output.viewer import has_display, open_viewer, prepare

    try:
        results, scene, path = prepare(results_dir)  # refuses coordinates not of the head
    except ResultsError as err:
        _fail(str(err))
    click.echo(f"written {path} ({len(results.shape_coordinates)} rows)")
    if write_only:
        return
    if not has_display():
        click.echo("no display here: on a desktop, run 'exubrush view "
                   f"{results_dir}' to open it in Exudyn's SolutionViewer", err=True)
        return
    open_viewer(scene, path)

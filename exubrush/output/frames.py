"""Bristle frames: centrelines and tip spheres of saved runs, side by side (headless PNG/GIF).

Each run is drawn in two views, seen from the side (slide axis horizontal) and from the
end (the other horizontal axis), in a frame that moves with the head: the horizontal
origin is the centre of the bristle roots, the surface is z = 0. A PRB bristle is drawn as
root, characteristic pivot and tip; a DFM bristle through its N nodes; each as a tube as
thick as its section seen in that view (a round filament's diameter). Where the run let
bristles touch each other (contact.between_bristles), the places they touch in a frame are
marked with red crosses (found again from the stored shapes, exubrush.contact.between).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from exubrush.output.results import ResultsError, read_results
from exubrush.parameters.case import BristleContactLaw, Surface
from exubrush.parameters.surface_kinds import MESH
from exubrush.util.files import atomic_file
from exubrush.world.mesh import MeshError, MeshSurface
from exubrush.world.surfaces import height, to_surface_frame

VIEW_AXES = {"orthogonal": (1, 0), "parallel": (0, 1)}  # (slide axis, other axis) in x, y, z


@dataclass(frozen=True)
class RunShapes:
    """Stored bristle shapes of one run, centred on the head.

    Attributes
    ----------
    label : str
        Title of the run's column.
    time : ndarray (n_t,)
        Shape sample times [s].
    lines : ndarray (n_t, n_bristles, n_points, 3)
        Centreline points [mm], root first, horizontal origin at the roots' centre.
    tip_radius : ndarray (n_bristles,)
        Tip sphere radii [mm].
    half_width : ndarray (n_bristles, 2)
        Half the section's extent along the head's X and Y [mm] (the tube drawn).
    direction : str
        Slide direction (``orthogonal`` or ``parallel``).
    surface : Surface
        The surface brushed.
    mesh : MeshSurface or None
        Its triangle mesh (surface.kind "mesh"; None also when the file is gone: the
        surface is then not drawn).
    between : BristleContactLaw or None
        The law of contact between bristles, if the run had it (contacts are marked).
    centre : ndarray (n_t, 3)
        The roots' centre at each sample, head frame fixed to the surface (z = 0) [mm].
    """

    label: str
    time: np.ndarray
    lines: np.ndarray
    tip_radius: np.ndarray
    half_width: np.ndarray
    direction: str
    surface: Surface
    centre: np.ndarray
    mesh: MeshSurface | None = None
    between: BristleContactLaw | None = None


def load_shapes(directory: str | Path) -> RunShapes:
    """Read the shapes of a result directory (ResultsError if it has none)."""
    from exubrush.models.geometry import head_bristles

    results = read_results(directory)
    if results.shape_time.size == 0:
        raise ResultsError(f"{str(directory)!r} has no bristle shapes (shapes.npz)")
    meta = results.metadata
    case = results.case()
    # the geometry alone: a saved run's slide CSV may be gone, and its motion is not needed
    bristles = head_bristles(case.head)
    nodes = np.array(results.shape_nodes, dtype=float)
    if meta.get("model") == "prb":
        derived = meta.get("derived")
        gamma = derived.get("prb_gamma") if isinstance(derived, dict) else None
        if not isinstance(gamma, int | float) or not 0.0 < gamma <= 1.0:
            raise ResultsError(f"{str(Path(directory) / 'run.json')!r} of a PRB run has no "
                               "characteristic radius factor (derived.prb_gamma in (0, 1]): "
                               "not written by exubrush; make the run again")
        stub = np.array([(1.0 - gamma) * b.length * b.frame[:, 0] for b in bristles])
        pivots = nodes[:, :, :1, :] + stub[None, :, None, :]
        nodes = np.concatenate([nodes[:, :, :1], pivots, nodes[:, :, 1:]], axis=2)
    centre = nodes[:, :, 0, :].mean(axis=1)
    centre[:, 2] = 0.0
    lines = nodes - centre[:, None, None, :]
    label = f"{str(meta.get('model', '?')).upper()}: {Path(directory).name}"
    try:
        mesh = results.surface_mesh()
    except MeshError:
        mesh = None
    return RunShapes(label, np.asarray(results.shape_time), lines,
                     np.array([b.tip_radius for b in bristles]),
                     np.array([[0.5 * b.width, 0.5 * b.height] for b in bristles]),
                     case.motion.direction,
                     case.surface, centre, mesh,
                     case.contact.bristles if case.contact.between_bristles else None)


def nearest_samples(run: RunShapes, times) -> list[int]:
    """Index of the stored shape sample nearest to each requested time [s]."""
    return [int(np.argmin(np.abs(run.time - t))) for t in times]


def _limits(runs: list[RunShapes]) -> tuple[float, float, float]:
    """Half width of the horizontal views and the top of the vertical axis [mm]."""
    reach = max(float(np.max(np.abs(r.lines[..., :2]))) + float(r.tip_radius.max())
                for r in runs)
    top = max(float(np.max(r.lines[..., 2])) for r in runs)
    low = min(float(np.min(r.lines[..., 2]) - r.tip_radius.max()) for r in runs)
    return 1.05 * reach, min(-0.05 * top, low - 0.3), 1.05 * top


def tube_outline(points: np.ndarray, radius: float) -> np.ndarray:
    """Closed outline (2 n, 2) of a tube of ``radius`` around the 2-D polyline ``points``
    (n, 2): each point offset both ways along the mean normal of its segments."""
    tangents = np.diff(points, axis=0)
    tangents /= np.maximum(np.linalg.norm(tangents, axis=1, keepdims=True), 1e-12)
    at_points = np.vstack([tangents[:1], tangents[:-1] + tangents[1:], tangents[-1:]])
    at_points /= np.maximum(np.linalg.norm(at_points, axis=1, keepdims=True), 1e-12)
    normals = np.column_stack([-at_points[:, 1], at_points[:, 0]])
    return np.vstack([points + radius * normals, (points - radius * normals)[::-1]])


def _touching(lines: np.ndarray, radii: np.ndarray, law: BristleContactLaw) -> np.ndarray:
    """Where the bristles of one shape sample (bristles, points, 3) touch [mm]."""
    # imported here: it loads numba, which runs without contact between bristles do not need
    from exubrush.contact.between import Chains, contact_locations

    count, points = lines.shape[:2]
    chains = Chains.from_polylines(
        [list(range(b * points, (b + 1) * points)) for b in range(count)], list(radii))
    return contact_locations(chains, lines.reshape(-1, 3), law)


def _draw_view(axis, run: RunShapes, sample: int, horizontal: int, limits) -> None:
    from matplotlib.collections import PatchCollection, PolyCollection
    from matplotlib.patches import Circle

    lines = run.lines[sample]
    # a bristle's thickness seen in this view is its section's extent along the view's
    # horizontal axis (the bend's own plane is nearly the view's in both views)
    radii = run.half_width[:, horizontal]
    axis.add_collection(PolyCollection(
        [tube_outline(line[:, [horizontal, 2]], r) for line, r in zip(lines, radii, strict=True)],
        facecolors="tab:blue", edgecolors="none", alpha=0.45))
    if run.between is not None:
        touching = _touching(lines, run.half_width.max(axis=1), run.between)
        axis.plot(touching[:, horizontal], touching[:, 2], "x", color="tab:red", ms=4, mew=1.0)
    tips = [Circle((p[horizontal], p[2]), r) for p, r in zip(lines[:, -1], run.tip_radius,
                                                            strict=True)]
    axis.add_collection(PatchCollection(tips, facecolor="tab:orange", edgecolor="0.3",
                                        linewidth=0.4, alpha=0.7))
    half, bottom, top = limits
    along = np.linspace(-half, half, 801)
    points = np.zeros((along.size, 3))
    points[:, :2] = run.centre[sample, :2]
    points[:, horizontal] += along
    local = to_surface_frame(run.surface, points)
    if run.surface.kind != MESH:
        profile = height(run.surface, local[:, 0], local[:, 1])
    elif run.mesh is not None:  # the highest triangle over each point of the section
        profile = np.maximum(run.mesh.heights(local[:, :2]), bottom)
    else:
        profile = None
    if profile is not None:
        axis.fill_between(along, np.minimum(profile, bottom), profile, color="0.85")
        axis.plot(along, profile, color="0.3", lw=0.8)
    axis.set_xlim(-half, half)
    axis.set_ylim(bottom, top)
    axis.set_aspect("equal")


def _figure(runs: list[RunShapes]):
    # matplotlib (0.8 s of import) only once there is something to draw: a fault in the
    # saved runs is reported without it
    from exubrush.output.plotting import figure

    return figure(2, len(runs), figsize=(4.5 * len(runs), 5.5), squeeze=False)


def _fill(fig, axes, runs, samples, limits) -> None:
    for column, (run, sample) in enumerate(zip(runs, samples, strict=True)):
        slide, other = VIEW_AXES[run.direction]
        for row, (horizontal, view) in enumerate(((slide, "side view"), (other, "end view"))):
            axis = axes[row][column]
            axis.clear()
            _draw_view(axis, run, sample, horizontal, limits)
            axis.set_xlabel(f"{'xyz'[horizontal]} from the head centre [mm] ({view})")
            axis.set_ylabel("z above surface [mm]")  # longer ran into the row above
        axes[0][column].set_title(f"{run.label}\nt = {run.time[sample]:.2f} s", fontsize=9)
    fig.suptitle("exubrush bristle shapes (simulation)", fontsize=10)


def write_frames(runs: list[RunShapes], times, directory: Path) -> list[str]:
    """One PNG per requested time, runs side by side; return the file names."""
    limits = _limits(runs)
    names = []
    for k, t in enumerate(times):
        fig, axes = _figure(runs)
        _fill(fig, axes, runs, [nearest_samples(run, [t])[0] for run in runs], limits)
        fig.tight_layout()
        name = f"frame_{k:03d}_t{t:08.3f}.png"
        with atomic_file(directory / name, "wb") as handle:
            fig.savefig(handle, format="png", dpi=100)
        names.append(name)
    return names


def write_animation(runs: list[RunShapes], times, target: Path, fps: float = 8.0,
                    progress=None) -> None:
    """An animated GIF through ``times`` (nearest stored samples), runs side by side.

    ``progress(i, n)`` is called after each frame, if given.
    """
    from matplotlib.animation import FuncAnimation, PillowWriter

    limits = _limits(runs)
    fig, axes = _figure(runs)

    def update(t):
        _fill(fig, axes, runs, [nearest_samples(run, [t])[0] for run in runs], limits)
        return []

    update(times[0])
    fig.tight_layout()  # after a first drawing, so that titles and labels keep their room
    animation = FuncAnimation(fig, update, frames=list(times), init_func=lambda: [],
                              blit=False)
    temporary = target.with_name(f".{target.name}.partial.gif")
    animation.save(temporary, writer=PillowWriter(fps=fps), dpi=80,
                   progress_callback=progress)
    temporary.replace(target)

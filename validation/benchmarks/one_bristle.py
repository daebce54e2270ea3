"""One bristle of a case's head, or the group of touching bristles that holds it, built as
exubrush builds it for a run: the command-line options and the system that the scripts on
one system (profile_bristle.py, step_attempts.py, split_rates.py) share. Import it after
choosing Exudyn's core (it imports exubrush)."""

from __future__ import annotations

import argparse

from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare
from exubrush.run.scene import build_scene
from exubrush.run.solve import group_settings


def add_arguments(parser: argparse.ArgumentParser, case: str, bristle: int,
                  group: bool = False) -> None:
    """--case, --model, --periods, --bristle and --set, with these defaults; with
    ``group``, also --group (solve the bristle's whole group: build's ``group``)."""
    parser.add_argument("--case", default=case)
    parser.add_argument("--model", default="dfm", choices=["dfm", "prb"])
    parser.add_argument("--periods", type=float, default=1.0)
    parser.add_argument("--bristle", type=int, default=bristle, help="index in the head")
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE")
    if group:
        parser.add_argument("--group", action="store_true",
                            help="solve the bristle's whole group (bristles that can touch it)")


def build(parser: argparse.ArgumentParser, args: argparse.Namespace, group: bool = False):
    """(the prepared case, the bristle's scene, its Exudyn settings) for the parsed
    options; with ``group``, the scene of the whole group the bristle is solved in (the
    bristles that can touch it, with contact.between_bristles). The scene's pre-step
    function is not set yet. A bad case, override or bristle index ends the script with
    the parser's one-line error (exit code 2)."""
    try:
        case = load_case(args.case, [f"model.kind='{args.model}'",
                                     f"motion.periods={args.periods:g}", *args.overrides])
        prepared = prepare(case)
    except ParameterError as error:
        parser.error(str(error))
    count = len(prepared.bristles)
    if not 0 <= args.bristle < count:
        parser.error(f"--bristle {args.bristle}: the head has bristles 0 to {count - 1}")
    selection = (args.bristle,)
    if group:
        selection = next(g for g in prepared.groups if args.bristle in g)
    scene = build_scene(prepared, selection)
    return prepared, scene, group_settings(prepared, scene, selection)

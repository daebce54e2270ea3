"""validation/benchmarks/contact_cost.py: the tufts it writes are the ones it names, and
each row's figure is the ratio its target is about."""

import pytest

from exubrush.parameters.io import load_case

TUFTS = {7: "0.8 mm", 19: "1.2 mm", 37: "1.6 mm", 61: "2.0 mm"}  # hexagonal packings


def _rows(benchmark_script, folder):
    return benchmark_script("contact_cost").rows(folder)


@pytest.mark.parametrize("filaments", sorted(TUFTS))
def test_each_tuft_file_holds_its_filaments_in_their_hole(benchmark_script, tmp_path, filaments):
    case_file, overrides = _rows(benchmark_script, tmp_path)["filaments"]["runs"][str(filaments)]
    case = load_case(case_file, overrides)
    assert case.head.tufts[0].filaments == filaments
    assert case.head.tufts[0].diameter == pytest.approx(float(TUFTS[filaments].split()[0]))
    assert case.contact.between_bristles


def test_figures_are_the_ratios_the_targets_are_about(benchmark_script, tmp_path):
    every = _rows(benchmark_script, tmp_path)
    assert every["tuft window"]["figure"]({"contact": 30.0, "free": 10.0}) == 3.0
    assert every["tooth row"]["figure"]({"interdental": 9.0, "plane": 6.0}) == 1.5
    # seconds per filament: 7 filaments in 14 s and 61 in 183 s are 2 and 3 s each
    walls = {"7": 14.0, "19": 38.0, "37": 74.0, "61": 183.0}
    assert every["filaments"]["figure"](walls) == pytest.approx(1.5)


def test_seeds_run_each_run_once_per_seed_and_figures_use_the_sums(benchmark_script):
    script = benchmark_script("contact_cost")
    calls = []

    class Results:
        metadata = {"completed": True, "solver_statistics": {"steps": 1, "jacobian_updates": 1},
                    "derived": {}}

    def fake_run(tree, what, case, overrides, out):
        calls.append((case, overrides))
        wall = {"head.seed=1": 10.0, "head.seed=2": 30.0}.get(overrides[-1], 1.0)
        return Results(), {"wall": wall * (2.0 if "free" in case else 1.0)}

    script.run_in_tree = fake_run
    row = {"runs": {"contact": ("tuft", ["motion.periods=0.1"]),
                    "free": ("tuft-free", ["motion.periods=0.1"])}}
    records = script.measure(row, {"this": None}, 1, seeds=[1, 2])
    assert calls == [("tuft", ["motion.periods=0.1", "head.seed=1"]),
                     ("tuft", ["motion.periods=0.1", "head.seed=2"]),
                     ("tuft-free", ["motion.periods=0.1", "head.seed=1"]),
                     ("tuft-free", ["motion.periods=0.1", "head.seed=2"])]
    assert [r["seed"] for r in records] == [1, 2, 1, 2]
    assert script.summed_walls(records, "this") == {"contact": 40.0, "free": 80.0}
    # without seeds, the case's own seed: no override added
    calls.clear()
    script.measure(row, {"this": None}, 1)
    assert calls[0] == ("tuft", ["motion.periods=0.1"])


def test_nineteen_filaments_row_compares_the_same_tuft_with_and_without_contact(
        benchmark_script, tmp_path):
    row = _rows(benchmark_script, tmp_path)["19 filaments"]
    contact = load_case(*row["runs"]["contact"])
    free = load_case(*row["runs"]["free"])
    assert contact.head.tufts[0].filaments == free.head.tufts[0].filaments == 19
    assert contact.contact.between_bristles and not free.contact.between_bristles
    assert not free.solver.share_identical  # every filament solved, none taken from a twin
    assert row["figure"]({"contact": 50.0, "free": 5.0}) == 10.0

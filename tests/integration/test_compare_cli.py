"""``exubrush compare``: a saved run against a measured CSV, end to end (no solve)."""

import csv
import json

import numpy as np
import pytest

from exubrush.output.results import Results


def _save_run(directory, series):
    empty = np.zeros((0, 0, 0, 3))
    Results(series.time, series.slider_position, series.normal_force,
            series.tangential_force, np.zeros_like(series.time), np.zeros(0), empty,
            metadata={"case": "synthetic", "model": "dfm", "status": "completed"}).save(directory)


def _write_measured(path, series, shift, normal_unit="mN"):
    factor = 1000.0 if normal_unit == "mN" else 1.0
    with open(path, "w", newline="") as handle:
        handle.write("# synthetic measurement for a test\n")
        writer = csv.writer(handle)
        writer.writerow(["time [s]", "slider_position [mm]", f"normal_force [{normal_unit}]",
                         "tangential_force [N]"])
        for row in zip(series.time - shift, series.slider_position,
                       factor * series.normal_force, series.tangential_force, strict=True):
            writer.writerow([f"{v:.9g}" for v in row])


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_compare_writes_summary_and_plots(cli, tmp_path, sine_run):
    _save_run(tmp_path / "run", sine_run())
    _write_measured(tmp_path / "rig.csv", sine_run(scale=1.1), shift=0.5)
    done = cli("compare", str(tmp_path / "run"), str(tmp_path / "rig.csv"),
                     "--align", "position", "--out", str(tmp_path / "cmp"))
    assert done.returncode == 0, done.stderr
    record = json.loads((tmp_path / "cmp" / "comparison.json").read_text())
    # the measured clock is 0.5 s behind; positions are sampled every 10 ms, so the fit
    # lands within a fraction of a sample
    assert abs(record["time_offset_s"] - 0.5) < 2e-3
    assert len(record["strokes"]) == 3
    for row in record["strokes"]:
        # every measured force is 10 % higher: (1 - 1.1) / 1.1, to the interpolation error
        # of the 2 ms residual misalignment on flat forces
        assert abs(row["relative_difference"]["normal_force"] - (1 / 1.1 - 1)) < 1e-3
    summary = (tmp_path / "cmp" / "comparison.md").read_text()
    assert "| 0 | - |" in summary and "F_n -9.1 %" in summary
    for name in ("compare_run.png", "compare_flat.png", "compare_period.png"):
        assert (tmp_path / "cmp" / name).stat().st_size > 10_000


def test_compare_refuses_a_directory_without_results(cli_here, tmp_path, sine_run):
    _write_measured(tmp_path / "rig.csv", sine_run(), shift=0.0)
    done = cli_here("compare", str(tmp_path), str(tmp_path / "rig.csv"))
    assert done.returncode == 2
    assert "holds no run.json" in done.stderr and "Traceback" not in done.stderr


@pytest.mark.slow  # 1.1 s (saving the run draws its plot): full run only
def test_compare_refuses_a_measured_file_without_units(cli_here, tmp_path, sine_run):
    _save_run(tmp_path / "run", sine_run())
    (tmp_path / "rig.csv").write_text("time,slider_position [mm],normal_force [N],"
                                      "tangential_force [N]\n0,0,1,0\n1,1,1,0\n")
    done = cli_here("compare", str(tmp_path / "run"), str(tmp_path / "rig.csv"))
    assert done.returncode == 2
    assert "column 'time' has no unit" in done.stderr and "Traceback" not in done.stderr


@pytest.mark.slow  # 1.2 s or more beside a second worker: full run only
def test_a_file_declaring_model_output_is_never_called_a_measurement(cli, tmp_path, sine_run):
    _save_run(tmp_path / "run", sine_run())
    path = tmp_path / "demo.csv"
    _write_measured(path, sine_run(), shift=0.0)
    path.write_text("# NOT MEASURED DATA: model output\n" + path.read_text())
    done = cli("compare", str(tmp_path / "run"), str(path), "--out", str(tmp_path / "c"))
    assert done.returncode == 0, done.stderr
    assert "declares it model output" in (tmp_path / "c" / "comparison.md").read_text()

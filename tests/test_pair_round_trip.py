"""Every pair file the project writes is read by every command (issue 18): the shipped
examples (`gearmesh example NAME`), `optimise --write-pair`, the workflow's optimum
(results/.../optimise/NAME/pair.yaml, named after its pair, not its file), a micro-geometry
variant and a datasheet pair written back."""

from __future__ import annotations

import json
import re

import pytest

from gearmesh.cli import main
from gearmesh.datasets.optimise import optimise_summary, optimum_pair
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair, pair_from_dict, variant_pair
from gearmesh.pipeline import write_pair

from pairs import low_fluctuation_pair1

SMALL_GA = ["--population", "4", "--generations", "1"]

#: Every command on one pair file, each with its cheapest honest settings.
COMMANDS = {
    "validate": [],
    "geometry": [],
    "stiffness": ["--slices", "20", "--positions", "24", "--torque-Nm", "100"],
    "ltca": ["--torque-Nm", "100", "--positions", "16", "--points", "8"],
    "impact": ["--torque-Nm", "100", "--speed-rpm", "3000", "--points", "20"],
    "dynamics": ["--torque-Nm", "100", "--speeds", "2000:2000:100"],
    "optimise": ["--torque-Nm", "100", "--speed-rpm", "3000", *SMALL_GA],
}


def _example(folder, capsys):
    assert main(["example", "low_fluctuation_pair1"]) == 0
    path = folder / "example.yaml"
    path.write_text(capsys.readouterr().out)
    return path


def _write_pair_option(folder, capsys):
    source = _example(folder, capsys)
    path = folder / "optimum.yaml"
    assert main(["optimise", str(source), "--torque-Nm", "100", "--speed-rpm", "3000", *SMALL_GA,
                 "--write-pair", str(path)]) == 0
    capsys.readouterr()
    return path


def _workflow_optimum(folder, capsys):
    """As the workflow's optimise rule writes it: the pair's own name in a file called pair.yaml."""
    pair = pair_from_dict(low_fluctuation_pair1())
    ds = optimise_summary(pair, torque_Nm=100.0, speed_rpm=3000.0, population=4, generations=1, objective="force",
                          tolerance_statistic=None)[1]
    path = folder / "optimise" / "force" / "pair.yaml"
    return write_pair(optimum_pair(pair, ds), path)


def _variant(folder, capsys):
    pair = pair_from_dict(low_fluctuation_pair1())
    spec = {"modification": {"pinion": {"tip_relief_um": 8, "tip_relief_length_mm": 1.0, "crowning_um": 3,
                                        "unmodified_lead_length_mm": 10}}}
    return write_pair(variant_pair(pair, "relief", spec), folder / "relief" / "pair.yaml")


def _datasheet(folder, capsys):
    """Tip and bore diameters, no material, shifts and a centre distance: written back as
    coefficients (the material left out again, so its defaults are stated again)."""
    data = low_fluctuation_pair1(profile_shift=[0.2, 0.1], center_distance_mm=69.9, tip_diameter_mm=[55.0, 91.5],
                         bore_diameter_mm=[30, 50])
    del data["material"], data["addendum_coefficient"], data["bore_radius_mm"]
    return write_pair(pair_from_dict(data), folder / "datasheet.yaml")


WRITERS = {"example": _example, "write-pair": _write_pair_option, "workflow optimum": _workflow_optimum,
           "variant": _variant, "datasheet": _datasheet}


@pytest.mark.parametrize("writer", WRITERS)
def test_a_written_pair_reads_back_as_the_same_pair(tmp_path, capsys, writer):
    path = WRITERS[writer](tmp_path, capsys)
    pair = load_pair(path)
    again = load_pair(write_pair(pair, tmp_path / "again.yaml"))
    assert again.name == pair.name and again.modification == pair.modification
    a, b = pair_geometry(pair), pair_geometry(again)
    for field in ("eps_alpha", "eps_beta", "center_distance", "backlash_normal"):
        assert getattr(b, field) == pytest.approx(getattr(a, field), rel=1e-12, abs=1e-15), field
    assert b.tip_radius == pytest.approx(a.tip_radius, rel=1e-12)


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("writer", WRITERS)
def test_every_written_pair_is_read_by_every_command(tmp_path, capsys, writer, command):
    path = WRITERS[writer](tmp_path, capsys)
    code = main([command, str(path), *COMMANDS[command], "--json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    result = json.loads(out)
    assert result.get("name", load_pair(path).name) == load_pair(path).name


def test_a_written_pair_has_no_round_trip_digits(tmp_path):
    """Amounts pass through SI (5 µm -> 5e-06 m -> 5.000000000000001 µm): the file rounds them
    back to what was meant (issue 25), and a real optimum's digits to 12 significant ones."""
    pair = pair_from_dict(low_fluctuation_pair1())
    spec = {"modification": {"pinion": {"crowning_um": 5, "tip_relief_um": 24.861413680690358,
                                        "tip_relief_length_mm": 0.7}}}
    text = write_pair(variant_pair(pair, "relief", spec), tmp_path / "pair.yaml").read_text()
    assert "crowning_um: 5.0\n" in text and "tip_relief_um: 24.8614136807\n" in text
    assert "tip_relief_length_mm: 0.7\n" in text
    numbers = [float(n) for n in re.findall(r"-?\d+\.\d+(?:e-?\d+)?", text)]
    assert numbers and all(float(f"{n:.12g}") == n for n in numbers), text

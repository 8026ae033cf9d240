"""The command line: JSON keys, exit code 2 with one message for bad input."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from gearmesh.cli import main

GEOMETRY_KEYS = {
    "eps_alpha", "eps_beta", "eps_gamma", "transverse_pressure_angle_deg", "operating_pressure_angle_deg",
    "base_helix_angle_deg", "center_distance_mm", "backlash_mm", "base_radius_mm", "tip_radius_mm",
    "root_radius_mm", "form_radius_mm", "mass_kg", "inertia_kg_m2", "mean_contact_length_mm",
    "min_contact_length_mm", "max_contact_length_mm",
}


def test_geometry_json_has_the_documented_keys(root, capsys):
    assert main(["geometry", str(root / "config/pairs/seed001_pair1.yaml"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert GEOMETRY_KEYS <= set(out)
    for key in ("base_radius_mm", "tip_radius_mm", "root_radius_mm", "form_radius_mm", "mass_kg", "inertia_kg_m2"):
        assert len(out[key]) == 2
    # radii order on each gear: root < base or not, but form < tip and root < tip always
    for i in range(2):
        assert out["root_radius_mm"][i] < out["form_radius_mm"][i] < out["tip_radius_mm"][i]
    assert out["min_contact_length_mm"] <= out["mean_contact_length_mm"] <= out["max_contact_length_mm"]


def test_validate_accepts_pairs_and_studies(root, monkeypatch, capsys):
    monkeypatch.chdir(root)
    assert main(["validate", "config/pairs/seed003_pair.yaml"]) == 0
    assert main(["validate", "config/studies/low_fluctuation.yaml"]) == 0


@pytest.mark.parametrize("text, field", [
    ("name: x\nteeth: [29, 71]\nnormal_module_mm: 5\nnormal_pressure_angle_deg: 20\n"
     "helix_angle_deg: 27.5\nface_width_mm: 42\ncenter_distance_mm: 261.0\n", "center_distance_mm"),
    ("name: x\nteeth: [29, 49]\nnormal_module_mm: -1\nnormal_pressure_angle_deg: 20\n"
     "helix_angle_deg: 10\nface_width_mm: 20\n", "normal_module_mm"),
    ("name: x\nteeth: [29, 49]\nnormal_module_mm: 2\nnormal_pressure_angle_deg: 20\n"
     "helix_angle_deg: 10\nface_width_mm: 20\ncolour: red\n", "pair.colour"),
    ("study: s\npairs: [seed001_pair1]\ncontact_lines: {positions: 0}\n", "contact_lines.positions"),
    ("[not, a, mapping", "file"),
])
def test_bad_input_exits_2_with_one_message(tmp_path, root, monkeypatch, text, field):
    monkeypatch.chdir(root)
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    proc = subprocess.run([sys.executable, "-m", "gearmesh.cli", "validate", str(path)],
                          capture_output=True, text=True)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"gearmesh: error: {field}")
    assert proc.stdout == ""


def test_dynamics_json_per_speed(root, capsys):
    assert main(["dynamics", str(root / "config/pairs/seed001_pair1.yaml"), "--torque-Nm", "200",
                 "--speeds", "4000:6000:1000", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["speeds"]
    assert [r["speed_rpm"] for r in rows] == [4000.0, 5000.0, 6000.0]
    for row in rows:
        assert {"speed_rpm", "dte_rms_um", "mesh_force_mean_N", "mesh_force_max_N"} <= set(row)
        assert row["mesh_force_max_N"] >= row["mesh_force_mean_N"] > 0


@pytest.mark.parametrize("args, field", [
    (["--torque-Nm", "0", "--speeds", "1000:2000:100"], "torque_Nm"),
    (["--torque-Nm", "200", "--speeds", "2000:1000:100"], "speeds_rpm.stop"),
    (["--torque-Nm", "200", "--speeds", "fast"], "speeds_rpm"),
])
def test_dynamics_refuses_bad_options(root, capsys, args, field):
    assert main(["dynamics", str(root / "config/pairs/seed001_pair1.yaml"), *args]) == 2
    assert capsys.readouterr().err.startswith(f"gearmesh: error: {field}")

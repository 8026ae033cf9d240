"""The command line as a new user meets it (issue 18): one torque convention everywhere and
stated in every result, the pair's own backlash, the shipped examples, --version, usage and
help text."""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import subprocess
import sys
import sysconfig

import pytest

from gearmesh.cli import build_parser, main
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import example_pairs, load_pair


def _json(capsys, argv) -> dict:
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("on", [[], ["--on", "gear"]])
def test_ltca_and_dynamics_with_the_same_flags_act_on_the_same_gear(root, capsys, on):
    """Same flags, same load: the dynamics' mean normal mesh force at a low speed is the static
    normal force T1/(r_b1 cos β_b) of the LTCA's transverse force T1/r_b1 (issue 18: the
    dynamics once took the torque on the gear, 65.5 kN instead of 259 kN)."""
    path = str(root / "config/pairs/low_fluctuation_pair1.yaml")
    ltca = _json(capsys, ["ltca", path, "--torque-Nm", "200", *on, "--positions", "16", "--points", "10"])
    dyn = _json(capsys, ["dynamics", path, "--torque-Nm", "200", *on, "--speeds", "200:200:100"])
    geom = pair_geometry(load_pair(path))
    expected_t1 = 200.0 * (29 / 49 if on else 1.0)
    for out in (ltca, dyn):
        assert (out["torque_Nm"], out["torque_on"]) == (200.0, "gear" if on else "pinion")
        assert out["pinion_torque_Nm"] == pytest.approx(expected_t1)
    assert ltca["force_transverse_N"] == pytest.approx(expected_t1 / geom.base_radius[0], rel=1e-9)
    static_normal = ltca["force_transverse_N"] / math.cos(geom.base_helix_angle)
    assert dyn["speeds"][0]["mesh_force_mean_normal_N"] == pytest.approx(static_normal, rel=1e-3)


@pytest.mark.parametrize("command", [
    ["stiffness", "--slices", "20", "--positions", "20"],
    ["impact", "--speed-rpm", "3000"],
])
def test_every_torque_result_states_the_torque_and_its_gear(root, capsys, command):
    path = str(root / "config/pairs/low_fluctuation_pair1.yaml")
    out = _json(capsys, [command[0], path, "--torque-Nm", "200", "--on", "gear", *command[1:]])
    assert (out["torque_Nm"], out["torque_on"]) == (200.0, "gear")
    assert out["pinion_torque_Nm"] == pytest.approx(200.0 * 29 / 49)


def test_optimise_states_the_backlash_of_its_dynamics(root, capsys):
    path = str(root / "config/pairs/low_fluctuation_pair1.yaml")
    out = _json(capsys, ["optimise", path, "--torque-Nm", "200", "--population", "4", "--generations", "1",
                         "--dynamic-factor", "1.0", "--dynamic-speeds-rpm", "1000,3000", "--backlash-um", "40"])
    assert (out["backlash_um"], out["backlash_source"]) == (40.0, "given")
    assert (out["torque_on"], out["pinion_torque_Nm"]) == ("pinion", 200.0)


def test_dynamics_backlash_defaults_to_the_pairs_own(tmp_path, root, capsys):
    text = (root / "config/pairs/low_fluctuation_pair1.yaml").read_text() + "profile_shift: [0.1, 0.1]\ncenter_distance_mm: 69.7\n"
    path = tmp_path / "wide.yaml"
    path.write_text(text)
    own = pair_geometry(load_pair(path)).backlash_normal * 1e6
    assert own > 10  # a real backlash, not the old fixed 60 µm
    out = _json(capsys, ["dynamics", str(path), "--torque-Nm", "200", "--speeds", "1000:1000:100"])
    assert out["backlash_um"] == pytest.approx(own) and out["backlash_source"] == "pair"


# --------------------------------------------------------------------------------------
# The first hour: examples, version, usage, help
# --------------------------------------------------------------------------------------


def test_example_lists_the_shipped_pairs_and_prints_one_every_command_reads(tmp_path, capsys):
    listing = _json(capsys, ["example"])
    assert set(listing) == set(example_pairs()) and "helical_z29_71_m5" in listing
    assert all(source for source in listing.values())
    assert main(["example", "helical_z29_71_m5"]) == 0
    path = tmp_path / "mine.yaml"
    path.write_text(capsys.readouterr().out)
    assert _json(capsys, ["geometry", str(path)])["name"] == "helical_z29_71_m5"
    assert main(["example", "seed999"]) == 2
    assert capsys.readouterr().err.startswith("gearmesh: error: example = 'seed999': must be one of")


def test_the_examples_are_the_workflow_pair_library(root):
    """One source of truth: the study library config/pairs is the package's pairs folder."""
    library = {p.stem: p.read_bytes() for p in (root / "config/pairs").glob("*.yaml")}
    assert library == {name: p.read_bytes() for name, p in example_pairs().items()}


def test_version_and_bare_command(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0 and capsys.readouterr().out.startswith("gearmesh ")
    assert main([]) == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: gearmesh") and "example" in out and "is required" not in out


def test_help_speaks_plainly_and_shows_each_default_once(capsys):
    parser = build_parser()
    commands = [a for a in parser._actions if a.dest == "command"][0].choices
    for name, sub in commands.items():
        text = sub.format_help()
        assert "seed 0" not in text.lower() and "config/pairs" not in text, name
        # only what a pip install has: no repository files (docs/, tests/, workflow/)
        assert not re.search(r"\b(docs|tests|workflow)/", parser.format_help() + text), name
        assert "default: None" not in text, name
        formatter = sub._get_formatter()
        for action in sub._actions:
            assert formatter._get_help_string(action).count("default") <= 1, (name, action.dest)
    assert "(default: pinion)" in commands["optimise"].format_help()  # the list default, as words
    assert "(default: 0)" in commands["optimise"].format_help()  # --seed: a zero default is shown


@pytest.mark.workflow
def test_a_pip_install_ships_the_examples_every_command_reads(tmp_path, root):
    """From a NON-editable install (the package built into a folder of its own, run without the
    editable finder): `gearmesh example NAME` written to a file is read by `gearmesh geometry`."""
    source = tmp_path / "source"
    source.mkdir()
    for item in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy(root / item, source / item)
    shutil.copytree(root / "src", source / "src", ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    target = tmp_path / "installed"
    pip = subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", "--target", str(target),
                          str(source)], capture_output=True, text=True, timeout=300)
    if pip.returncode and "No matching distribution found for setuptools" in pip.stderr:
        pytest.skip("offline: pip cannot fetch the build backend")
    assert pip.returncode == 0, pip.stderr[-2000:]
    # -S: no site processing, so neither the editable install's finder nor its path are seen;
    # the dependencies come from this interpreter's library folders, after the installed copy
    libraries = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"]}
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(target), *libraries])}

    def gearmesh(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, "-S", "-m", "gearmesh.cli", *args], capture_output=True, text=True,
                              env=env, cwd=tmp_path, timeout=120)

    where = subprocess.run([sys.executable, "-S", "-c", "import gearmesh; print(gearmesh.__file__)"],
                           capture_output=True, text=True, env=env, timeout=60)
    assert where.stdout.startswith(str(target)), where
    example = gearmesh("example", "low_fluctuation_pair1")
    assert example.returncode == 0, example.stderr
    (tmp_path / "pair.yaml").write_text(example.stdout)
    geometry = gearmesh("geometry", "pair.yaml", "--json")
    assert geometry.returncode == 0, geometry.stderr
    assert json.loads(geometry.stdout)["eps_alpha"] == pytest.approx(1.470, abs=5e-4)

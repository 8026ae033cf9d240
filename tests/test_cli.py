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
    assert main(["geometry", str(root / "config/pairs/low_fluctuation_pair1.yaml"), "--json"]) == 0
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
    assert main(["validate", "config/pairs/transition_curve_z23_62.yaml"]) == 0
    assert main(["validate", "config/studies/low_fluctuation.yaml"]) == 0


@pytest.mark.parametrize("text, field", [
    ("name: x\nteeth: [29, 71]\nnormal_module_mm: 5\nnormal_pressure_angle_deg: 20\n"
     "helix_angle_deg: 27.5\nface_width_mm: 42\ncenter_distance_mm: 261.0\n", "center_distance_mm"),
    ("name: x\nteeth: [29, 49]\nnormal_module_mm: -1\nnormal_pressure_angle_deg: 20\n"
     "helix_angle_deg: 10\nface_width_mm: 20\n", "normal_module_mm"),
    ("name: x\nteeth: [29, 49]\nnormal_module_mm: 2\nnormal_pressure_angle_deg: 20\n"
     "helix_angle_deg: 10\nface_width_mm: 20\ncolour: red\n", "pair.colour"),
    ("study: s\npairs: [low_fluctuation_pair1]\ncontact_lines: {positions: 0}\n", "contact_lines.positions"),
    ("[not, a, mapping", "file"),
])
@pytest.mark.workflow
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
    assert main(["dynamics", str(root / "config/pairs/low_fluctuation_pair1.yaml"), "--torque-Nm", "200",
                 "--speeds", "4000:6000:1000", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rows = out["speeds"]
    # the supports and the damping it used, stated (issue 28): the low-fluctuation paper's pair file gives its bearings
    assert out["supports"].startswith("supports radial [150, 150] N/um") and "from the pair file" in out["supports"]
    assert out["damping_ratio"] == 0.07 and "mesh mode" in out["damping_ratio_meaning"]
    assert [r["speed_rpm"] for r in rows] == [4000.0, 5000.0, 6000.0]
    for row in rows:
        assert {"speed_rpm", "dynamic_te_mean_um", "dynamic_te_std_um", "mesh_deflection_mean_um",
                "mesh_force_mean_normal_N", "mesh_force_max_normal_N"} <= set(row)
        assert row["mesh_force_max_normal_N"] >= row["mesh_force_mean_normal_N"] > 0


@pytest.mark.parametrize("args, field", [
    (["--torque-Nm", "0", "--speeds", "1000:2000:100"], "torque_Nm"),
    (["--torque-Nm", "200", "--speeds", "2000:1000:100"], "speeds_rpm.stop"),
    (["--torque-Nm", "200", "--speeds", "fast"], "speeds_rpm"),
])
def test_dynamics_refuses_bad_options(root, capsys, args, field):
    assert main(["dynamics", str(root / "config/pairs/low_fluctuation_pair1.yaml"), *args]) == 2
    assert capsys.readouterr().err.startswith(f"gearmesh: error: {field}")


PAIR_TEXT = ("name: x\nteeth: [29, 49]\nnormal_module_mm: 1.75\nnormal_pressure_angle_deg: 25\n"
             "helix_angle_deg: 10\nface_width_mm: 20\nbore_radius_mm: [15, 25]\n"
             "material: {youngs_modulus_GPa: 210, poisson_ratio: 0.3, density_kg_m3: 7850}\n")


@pytest.mark.parametrize("content, field, words", [
    (b"\xff\xfe\x00binary", "file", "UTF-8"),
    (PAIR_TEXT.replace("teeth: [29, 49]\n", "teeth: [29, 49]\nteeth: [20, 40]\n").encode(), "teeth", "twice"),
    (PAIR_TEXT.replace("normal_module_mm: 1.75", "normal_module_mm: 1e6").encode(), "normal_module_mm", "1.0e+6"),
    (PAIR_TEXT.replace("bore_radius_mm: [15, 25]", "bore_radius_mm: [24, 25]").encode(), "bore_radius_mm[0]",
     "root radius"),
])
def test_malformed_files_get_one_clear_message(tmp_path, capsys, content, field, words):
    path = tmp_path / "bad.yaml"
    path.write_bytes(content)
    assert main(["validate", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"gearmesh: error: {field}") and words in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("extra, field", [
    ("variants: {v: {modification: {pinion: {tip_relief_um: 5}}}}\n", "variants.v.modification.pinion.tip_relief_length_mm"),
    ("stiffness_table: {pairs: [p], variants: {a: {eps_alpha: 0.5}}}\n", "stiffness_table.variants.a.eps_alpha"),
    ("stiffness_table: {pairs: [p], variants: {a: {colour: 1}}}\n", "stiffness_table.variants.a.pair.colour"),
    ("helix_sweep: {pairs: [p], start_deg: 40, stop_deg: 10, step_deg: 1}\n", "helix_sweep.stop_deg"),
])
def test_study_validation_builds_every_variant(tmp_path, capsys, extra, field):
    (tmp_path / "pairs").mkdir()
    (tmp_path / "pairs/p.yaml").write_text(PAIR_TEXT.replace("name: x", "name: p"))
    study = tmp_path / "study.yaml"
    study.write_text(f"study: s\npairs: [p]\npairs_dir: {tmp_path / 'pairs'}\n" + extra)
    assert main(["validate", str(study)]) == 2
    assert capsys.readouterr().err.startswith(f"gearmesh: error: {field}")


def test_study_pair_without_bore_is_refused_up_front(tmp_path, capsys):
    (tmp_path / "pairs").mkdir()
    (tmp_path / "pairs/p.yaml").write_text(PAIR_TEXT.replace("name: x", "name: p").replace("bore_radius_mm: [15, 25]\n",
                                                                                            ""))
    study = tmp_path / "study.yaml"
    study.write_text(f"study: s\npairs: [p]\npairs_dir: {tmp_path / 'pairs'}\n")
    assert main(["validate", str(study)]) == 2
    assert capsys.readouterr().err.startswith("gearmesh: error: bore_radius_mm")


def test_cli_bounds_grid_sizes(root, capsys):
    assert main(["stiffness", str(root / "config/pairs/low_fluctuation_pair1.yaml"), "--slices", "100000000"]) == 2
    assert capsys.readouterr().err.startswith("gearmesh: error: --slices")


def test_validate_json_reports_invalid_input(tmp_path, capsys):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\nteeth: [29, 71]\nnormal_module_mm: -5\nnormal_pressure_angle_deg: 20\n"
                   "helix_angle_deg: 10\nface_width_mm: 20\n")
    assert main(["validate", str(bad), "--json"]) == 2
    out = json.loads(capsys.readouterr().out)
    assert out["valid"] is False and len(out["errors"]) == 1 and "normal_module_mm" in out["errors"][0]


def test_help_shows_the_defaults(capsys):
    with pytest.raises(SystemExit):
        main(["stiffness", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "(default: 200)" in text and "(default: fe)" in text


def test_rating_text_starts_with_the_verdict_and_groups_the_factors(root, capsys):
    """The first line says whether S_H and S_F of the weaker gear meet their minimums; then the
    result by group, every number of the JSON output among them (nothing dropped); a minimum above
    the rated safety factor turns the verdict to FAIL."""
    pair = str(root / "config/pairs/helical_z29_71_m5.yaml")
    base = ["rating", pair, "--torque-Nm", "1000", "--speed-rpm", "5000", "--positions", "16", "--points", "20"]
    assert main([*base, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert main(base) == 0
    text = capsys.readouterr().out.splitlines()
    s_h, s_f = min(data["S_H"]), min(data["S_F"])
    assert text[0] == (f"PASS: S_H {s_h:.3g} >= S_Hmin {data['S_Hmin']:g}, S_F {s_f:.3g} >= S_Fmin "
                       f"{data['S_Fmin']:g} (the weaker gear of each)")
    headings = [line for line in text[1:] if line and not line.startswith(" ")]
    assert headings[:4] == ["operating point", "load factors (ISO 6336-1)", "pitting (ISO 6336-2)",
                            "tooth root (ISO 6336-3)"] and headings[-1] == "notes"
    section = text.index("pitting (ISO 6336-2)")
    assert any(line.split() == ["S_H", "pinion", f"{data['S_H'][0]:.6g},", "gear", f"{data['S_H'][1]:.6g}"]
               for line in text[section:])
    shown = {line.split()[0] for line in text if line.startswith("  ") and not line.startswith("  -")}
    flat = {k.rsplit(".", 1)[-1] if "." not in k.split(".", 1)[-1] else k.split(".", 1)[1]
            for k in _dotted(data) if not k.startswith("notes")}
    assert flat <= shown, flat - shown
    assert len([line for line in text if line.startswith("  - ")]) == len(data["notes"])
    assert main([*base, "--factor", f"S_Hmin={s_h * 1.01}"]) == 0
    assert capsys.readouterr().out.startswith(f"FAIL: S_H {s_h:.3g} < S_Hmin")


def _dotted(data, prefix=""):
    for key, value in data.items():
        if isinstance(value, dict):
            yield from _dotted(value, f"{prefix}{key}.")
        else:
            yield f"{prefix}{key}"


def test_the_safety_verdict_reads_every_factor_with_a_minimum():
    """A safety factor the rating gains (with its minimum) joins the verdict without a change."""
    from gearmesh.commands import safety_verdict

    ok, line = safety_verdict({"S_H": [1.2, 1.1], "S_Hmin": 1.0, "S_F": [2.0, 1.9], "S_Fmin": 1.4,
                               "S_S": 1.5, "S_Smin": 1.8, "S_Hmin_note": "x"})
    assert not ok and line == ("FAIL: S_H 1.1 >= S_Hmin 1, S_F 1.9 >= S_Fmin 1.4, S_S 1.5 < S_Smin 1.8 "
                               "(the weaker gear of each)")
    for values in ([float("nan"), 2.0], [2.0, float("nan")]):
        assert safety_verdict({"S_H": values, "S_Hmin": 1.0})[0] is False


#: What each command needs on its command line besides its pair file (small grids where it runs).
_COMMAND_LINES = {"geometry": [], "stiffness": ["--slices", "20", "--positions", "16"],
                  "ltca": ["--torque-Nm", "20000"], "impact": ["--torque-Nm", "20000", "--speed-rpm", "500"],
                  "rating": ["--torque-Nm", "20000", "--speed-rpm", "500"],  # the declared default: ltca
                  "rating --method iso": ["--torque-Nm", "20000", "--speed-rpm", "500", "--method", "iso"],
                  "dynamics": ["--torque-Nm", "20000", "--speeds", "500"],
                  "optimise": ["--torque-Nm", "20000", "--population", "4", "--generations", "1"]}


def test_what_validate_accepts_every_command_that_needs_nothing_more_runs(tmp_path, capsys):
    """One rule for required inputs: a datasheet pair without a bore is valid; validate names the
    key it lacks and the commands that need it; each of those refuses naming the key to add, and
    every other command runs (the geometry, the ISO rating by the standard's factors)."""
    import argparse

    from gearmesh.cli import build_parser

    pair = tmp_path / "stage.yaml"
    pair.write_text("teeth: [24, 95]\nnormal_module_mm: 14\nnormal_pressure_angle_deg: 20\nhelix_angle_deg: 10\n"
                    "face_width_mm: 200\nprofile_shift: [0.48, 0.6691]\ncenter_distance_mm: 861.0\n"
                    "tip_diameter_mm: [380.747, 1395.376]\nbasic_rack_profile: ISO 53 A\n")
    assert main(["validate", str(pair), "--json"]) == 0
    needs = json.loads(capsys.readouterr().out)["needs"]
    assert list(needs) == ["bore_radius_mm"] and "bore_diameter_mm" in needs["bore_radius_mm"]
    needing = needs["bore_radius_mm"].split("needed by ", 1)[1].split(", ")
    action = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    takes_a_pair = {name for name, p in action.choices.items() if any(a.dest == "pair" for a in p._actions)}
    assert {c.split()[0] for c in _COMMAND_LINES} == takes_a_pair  # every command is judged here
    for command, options in _COMMAND_LINES.items():
        code = main([command.split()[0], str(pair), *options, "--json"])
        out, err = capsys.readouterr()
        if command in needing:
            assert code == 2 and err.startswith("gearmesh: error: bore_radius_mm = None: is required for "), err
            assert "add bore_radius_mm (or bore_diameter_mm" in err, err
        else:
            assert code == 0, (command, err)
            assert "ltca" not in json.loads(out) if command == "rating --method iso" else True


@pytest.mark.parametrize("kind, key", [("pair", "bore_radus_mm"), ("pair", "colour"), ("study", "bogus"),
                                       ("study", "ltca.torque_Nm")])
def test_an_unknown_key_is_refused_in_whole_words(root, tmp_path, capsys, kind, key):
    """The message lists the allowed keys when they fit in a line, else the closest ones and the
    command that lists them all: never a list cut off in the middle of a word."""
    import yaml

    if kind == "pair":
        data = {**yaml.safe_load((root / "config/pairs/helical_z29_71_m5.yaml").read_text()), key: 1}
    else:
        data = {"study": "x", "pairs": ["helical_z29_71_m5"]}
        section, _, name = key.rpartition(".")
        data.update({section: {name: 1}} if section else {name: 1})
    path = tmp_path / "file.yaml"
    path.write_text(yaml.safe_dump(data))
    assert main(["validate", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "…" not in err and "unknown key" in err, err
    if key == "bore_radus_mm":
        assert "did you mean bore_radius_mm" in err and "gearmesh schema pair --format markdown" in err
    if key == "ltca.torque_Nm":
        assert "allowed keys are contact_law, corner_extension" in err and "torques_Nm" in err


@pytest.mark.workflow
def test_gearmesh_run_leaves_no_snakemake_timer_to_wait_for(tmp_path, monkeypatch):
    """'gearmesh run' runs Snakemake in its own process and then exits at once: a run that
    scheduled jobs leaves Snakemake's job-rate timers (threading.Timer, 1 s each by default, which
    the interpreter waited for) cancelled, and the heap frozen for the last collection."""
    import gc
    import threading

    from gearmesh.launch import run_snakemake

    (tmp_path / "Snakefile").write_text('rule all:\n    input: "b"\nrule b:\n    input: "a"\n    output: "b"\n'
                                        '    shell: "cp a b"\nrule a:\n    output: "a"\n    shell: "echo a > a"\n')
    monkeypatch.chdir(tmp_path)
    started = []
    real_start = threading.Timer.start
    monkeypatch.setattr(threading.Timer, "start", lambda self: (started.append(self), real_start(self)))
    try:
        with pytest.raises(SystemExit) as exc:
            run_snakemake(["--cores", "1", "--quiet"])
        assert exc.value.code == 0 and (tmp_path / "b").read_text() == "a\n"
        assert started, "Snakemake scheduled no timer: nothing tested"
        # cancelled (or already fired): none would keep the process waiting (its finished event set)
        assert all(t.finished.is_set() for t in started), "a timer the process would wait for"
        assert gc.get_freeze_count() > 0
    finally:
        gc.unfreeze()


def test_gearmesh_run_starts_the_job_server_ahead_only_for_jobs_run_here(tmp_path, monkeypatch):
    """'gearmesh run' starts the job server before Snakemake reads the Snakefile when its command
    line runs jobs here; a dry run, a report, a lint or another executor starts none."""
    import gc

    from gearmesh import jobserver
    from gearmesh.launch import snakemake_inputs

    monkeypatch.chdir(tmp_path)  # no profiles/default: only the command line counts
    monkeypatch.delenv("SNAKEMAKE_PROFILE", raising=False)
    monkeypatch.delenv(jobserver.ENV, raising=False)
    assert snakemake_inputs(["--cores", "2"]).local_jobs
    for argv in (["-n"], ["--report", "r.html"], ["--lint"], ["--executor", "dryrun"], ["--executor", "touch"]):
        assert not snakemake_inputs(argv).local_jobs, argv
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "config.yaml").write_text("study: s\npairs: [low_fluctuation_pair1]\n")
    started = []
    monkeypatch.setattr(jobserver, "start_ahead", lambda modules: started.append(list(modules)))
    monkeypatch.setattr("snakemake.cli.main", lambda argv: None)
    try:
        for argv, ahead in ((["-n", "--cores", "2"], False), (["--cores", "2"], True)):
            started.clear()
            assert main(["run", *argv]) == 0
            assert bool(started) is ahead and (not ahead or started[0] == jobserver.stage_modules())
    finally:
        gc.unfreeze()  # run_snakemake froze this process's heap for its exit

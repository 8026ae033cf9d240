"""One gear, one answer: the same question asked through every door — the ``gearmesh`` command,
the Python API (the stage function and the physics function beneath it) and the workflow —
gets one number, and every answer names its model choices and the line of its forces.

The study below sets only what the command line can say too (the torque, the speed, the
excitation); everything else is each door's default, so a default declared twice and drifted
apart fails here (issue 25: the CLI's LTCA used the cantilever tooth while the workflow used
the FE tooth, 20.35 against 18.59 µm)."""

from __future__ import annotations

import functools
import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from gearmesh.contact_model import ContactModel
from gearmesh.choices import CONTACT_LAWS, DEFAULT_CONTACT_LAW, DEFAULT_TOOTH_METHOD, FORCE_LINES
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.io import read_dataset

from test_workflow import _scratch_workflow, _snakemake

pytestmark = pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake not installed")

PAIR, SOFT = "low_fluctuation_pair1", "low_fluctuation_pair1_206GPa"
TORQUE_NM, SPEED_RPM, QUASI_STATIC_RPM = 20.0, 3000.0, 100.0
STUDY = {"study": "doors", "pairs": [PAIR],
         "ltca": {"torques_Nm": [TORQUE_NM]}, "rating": {"speed_rpm": SPEED_RPM},
         "impact": {"torques_Nm": [TORQUE_NM], "speeds_rpm": [SPEED_RPM], "design_speed_rpm": SPEED_RPM},
         "dynamics": {"torques_Nm": TORQUE_NM, "speeds_rpm": [QUASI_STATIC_RPM], "excitation": "ltca",
                      "sample_speeds_rpm": [], "refine_resonances": False}}


def _cli(*args: str) -> dict:
    """The command's JSON answer; each command line runs once per test session (the same question is
    asked by more than one test, and the answer of a run cannot change)."""
    return json.loads(_cli_stdout(args))


@functools.lru_cache(maxsize=None)
def _cli_stdout(args: tuple[str, ...]) -> str:
    proc = subprocess.run([sys.executable, "-m", "gearmesh", *args, "--json"], capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stdout


@pytest.fixture(scope="module")
def doors(tmp_path_factory):
    """The workflow's results of the study (one pair, every setting the CLI cannot give at its
    default), and the pair files: the shipped pair (210 GPa) and the same pair at 206 GPa,
    ISO 6336-1's steel."""
    root = Path(__file__).resolve().parents[1]
    work = _scratch_workflow(root, tmp_path_factory.mktemp("doors"), STUDY)
    spec = yaml.safe_load((work / "config/pairs" / f"{PAIR}.yaml").read_text())
    spec.update(name=SOFT, material={**(spec.get("material") or {}), "youngs_modulus_GPa": 206.0})
    (work / "config/pairs" / f"{SOFT}.yaml").write_text(yaml.safe_dump(spec))
    proc = _snakemake(work)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return work


def _pair_file(work: Path, name: str = PAIR) -> str:
    return str(work / "config/pairs" / f"{name}.yaml")


@pytest.mark.workflow
def test_ltca_one_answer(doors):
    """LTE and loaded mesh stiffness: workflow file, CLI, stage function and physics function."""
    from gearmesh.datasets.ltca import ltca_dataset, ltca_summary
    from gearmesh.ltca import ltca

    pair = load_pair(_pair_file(doors))
    flow = read_dataset(doors / "results/doors" / PAIR / "standard/ltca.nc")
    cli = _cli("ltca", _pair_file(doors), "--torque-Nm", str(TORQUE_NM))
    api = ltca_summary(pair, TORQUE_NM)
    stage = ltca_dataset(pair, torques_Nm=[TORQUE_NM])
    physics = ltca(pair_geometry(pair), [TORQUE_NM], 64, contact=ContactModel(points=50))
    lte = {"workflow": flow["lte"].values[0], "stage": stage["lte"].values[0], "physics": physics.lte[0]}
    for door, value in lte.items():
        np.testing.assert_allclose(value, lte["workflow"], rtol=1e-12, err_msg=door)
    k_mean = float(flow["loaded_mesh_stiffness_mean"].values[0]) * 1e-6
    for door, summary in (("cli", cli), ("api", api)):
        assert summary["lte_mean_um"] == pytest.approx(lte["workflow"].mean() * 1e6, rel=1e-12), door
        assert summary["lte_peak_to_peak_um"] == pytest.approx(np.ptp(lte["workflow"]) * 1e6, rel=1e-12), door
        assert summary["loaded_mesh_stiffness_mean_transverse_N_per_um"] == pytest.approx(k_mean, rel=1e-12), door
        assert (summary["tooth_model"], summary["contact_law"]) == (DEFAULT_TOOTH_METHOD, DEFAULT_CONTACT_LAW)
    assert (flow.attrs["tooth_model"], flow.attrs["contact_law"]) == (DEFAULT_TOOTH_METHOD, DEFAULT_CONTACT_LAW)
    assert physics.model.method == DEFAULT_TOOTH_METHOD and physics.model.law.name == DEFAULT_CONTACT_LAW
    # a different choice is a different answer, and says so
    other = _cli("ltca", _pair_file(doors), "--torque-Nm", str(TORQUE_NM), "--method", "transition")
    assert other["tooth_model"] == "transition" and other["lte_mean_um"] != pytest.approx(cli["lte_mean_um"])


@pytest.mark.workflow
def test_rating_one_answer(doors):
    """S_H and S_F, K_Hβ from the LTCA of the misaligned mesh: workflow file, CLI and stage API at
    each one's default method (one default, declared once)."""
    from gearmesh.datasets.rating import rating_summary

    pair = load_pair(_pair_file(doors))
    flow = read_dataset(doors / "results/doors" / PAIR / "standard/rating.nc")
    cli = _cli("rating", _pair_file(doors), "--torque-Nm", str(TORQUE_NM), "--speed-rpm", str(SPEED_RPM))
    api = rating_summary(pair, TORQUE_NM, speed_rpm=SPEED_RPM)
    for door, summary in (("cli", cli), ("api", api)):
        assert summary["method"] == flow.attrs["factor_method"], door
        np.testing.assert_allclose(summary["S_H"], flow["S_H"].values[0], rtol=1e-9, err_msg=door)
        np.testing.assert_allclose(summary["S_F"], flow["S_F"].values[0], rtol=1e-9, err_msg=door)
        assert summary["K_Hbeta"] == pytest.approx(float(flow["K_Hbeta"].values[0]), rel=1e-9), door


@pytest.mark.workflow
def test_impact_one_answer(doors):
    """The energy method's F_s: workflow file, CLI, stage function, physics function."""
    from gearmesh.datasets.impact import impact_summary
    from gearmesh.impact import impact_model, impact_response, impact_static

    pair = load_pair(_pair_file(doors))
    flow = read_dataset(doors / "results/doors" / PAIR / "standard/impact.nc")
    want = float(flow["impact_force"].sel(speed=SPEED_RPM).values[0])
    cli = _cli("impact", _pair_file(doors), "--torque-Nm", str(TORQUE_NM), "--speed-rpm", str(SPEED_RPM))
    api = impact_summary(pair, TORQUE_NM, SPEED_RPM)
    model = impact_model(pair_geometry(pair))
    static = impact_static(model, np.array([TORQUE_NM]))
    physics = float(impact_response(model, static, np.array([SPEED_RPM]))[1].force[0, 0, 0])
    for door, value in (("cli", cli["impact_force_transverse_N"]), ("api", api["impact_force_transverse_N"]),
                        ("physics", physics)):
        assert value == pytest.approx(want, rel=1e-9), door
    assert (cli["tooth_model"], cli["contact_law"]) == (flow.attrs["tooth_model"], flow.attrs["contact_law"])
    assert flow["impact_force"].attrs["force_line"] == "transverse"


@pytest.mark.workflow
def test_quasi_static_dynamics_one_answer(doors):
    """The dynamic TE at a speed far below every resonance (the LTCA excitation): the workflow's
    dynamics.nc and the CLI's sweep agree, and both are the LTCA's loaded TE."""
    flow = read_dataset(doors / "results/doors" / PAIR / "standard/dynamics.nc")
    ltca = read_dataset(doors / "results/doors" / PAIR / "standard/ltca.nc")
    cli = _cli("dynamics", _pair_file(doors), "--torque-Nm", str(TORQUE_NM), "--speeds", str(QUASI_STATIC_RPM),
               "--excitation", "ltca")
    row = cli["speeds"][0]
    dte = float(flow["dynamic_te_mean"].sel(speed=QUASI_STATIC_RPM).values[0]) * 1e6
    assert row["dynamic_te_mean_um"] == pytest.approx(dte, rel=1e-9)
    assert dte == pytest.approx(float(ltca["lte"].values[0].mean()) * 1e6, rel=2e-3)  # quasi-static: the LTE
    force = float(flow["mesh_force_mean"].sel(speed=QUASI_STATIC_RPM).values[0])
    assert row["mesh_force_mean_normal_N"] == pytest.approx(force, rel=1e-9)
    assert flow["mesh_force_mean"].attrs["force_line"] == "normal"
    # the normal force is the transverse one over cos(beta_b), the one the LTCA reports
    cos_beta_b = np.cos(pair_geometry(load_pair(_pair_file(doors))).base_helix_angle)
    assert force == pytest.approx(float(ltca["force"].values[0]) / cos_beta_b, rel=1e-3)
    assert (cli["tooth_model"], cli["contact_law"]) == (flow.attrs["tooth_model"], flow.attrs["contact_law"])


@pytest.mark.workflow
def test_force_keys_name_their_line(doors):
    """Every force in the JSON ends in _transverse_N or _normal_N, every force column of a CSV
    table ends in its line, every force variable of every netCDF file carries force_line."""
    lines = tuple(FORCE_LINES)
    outputs = [_cli("ltca", _pair_file(doors), "--torque-Nm", str(TORQUE_NM)),
               _cli("impact", _pair_file(doors), "--torque-Nm", str(TORQUE_NM), "--speed-rpm", str(SPEED_RPM)),
               _cli("dynamics", _pair_file(doors), "--torque-Nm", str(TORQUE_NM), "--speeds", "1000"),
               _cli("rating", _pair_file(doors), "--torque-Nm", str(TORQUE_NM), "--speed-rpm", str(SPEED_RPM))]

    def keys(obj):
        if isinstance(obj, dict):
            for k, v in obj.items():
                yield k
                yield from keys(v)
        elif isinstance(obj, list):
            for v in obj:
                yield from keys(v)

    force_keys = [k for out in outputs for k in keys(out) if k.endswith("_N")]
    assert len(force_keys) >= 8
    assert all(k.endswith(tuple(f"_{line}_N" for line in lines)) for k in force_keys), force_keys
    for path in sorted((doors / "results").rglob("*.nc")):
        ds = read_dataset(path)
        for name, var in ds.variables.items():
            if var.attrs.get("units") == "N":
                assert var.attrs.get("force_line") in lines, f"{path.name}: {name}"
    csvs = sorted((doors / "results").rglob("*.csv"))
    assert csvs
    for path in csvs:
        for column in pd.read_csv(path, nrows=0).columns:
            if column.endswith("[N]"):
                assert column.split(" [")[0].endswith(tuple(f"_{line}" for line in lines)), f"{path.name}: {column}"


@pytest.mark.workflow
def test_iso_stiffness_follows_the_modulus_through_every_door(doors):
    """ISO 6336-1's c' at 210 and 206 GPa: in proportion to E (9.3.1), and the same from the
    CLI, the stage function and the physics function, and (210 GPa) the workflow's stiffness.nc."""
    from gearmesh.datasets.stiffness import stiffness_summary
    from gearmesh.stiffness import iso6336_stiffness

    flow = float(read_dataset(doors / "results/doors" / PAIR / "stiffness.nc")["iso6336_c_single"]) * 1e-9
    values = {}
    for name in (PAIR, SOFT):
        pair = load_pair(_pair_file(doors, name))
        cli = _cli("stiffness", _pair_file(doors, name), "--slices", "20", "--positions", "16")
        api = stiffness_summary(pair, method="transition", slices=20, positions=16)
        physics = iso6336_stiffness(pair_geometry(pair))["c_prime"]
        assert cli["iso6336_c_single_N_per_mm_um"] == pytest.approx(physics, rel=1e-12)
        assert api["iso6336_c_single_N_per_mm_um"] == pytest.approx(physics, rel=1e-12)
        values[pair.material.youngs_modulus] = physics
    assert values[load_pair(_pair_file(doors)).material.youngs_modulus] == pytest.approx(flow, rel=1e-12)
    (e_soft, c_soft), (e_hard, c_hard) = sorted(values.items())
    assert e_soft == 206e9 and e_hard != e_soft
    assert c_hard / c_soft == pytest.approx(e_hard / e_soft, rel=1e-12)


def test_contact_laws_are_declared_once():
    from gearmesh import ltca_model, settings

    assert ltca_model.CONTACT_LAWS is CONTACT_LAWS
    assert settings.DEFAULT_TOOTH_METHOD == DEFAULT_TOOTH_METHOD


def test_every_function_defaults_to_the_declared_choice():
    """No public function of the package, physics or stage, carries a tooth-model, contact-law or
    tip-edge default of its own: each takes the one of gearmesh.choices, or none, and every default
    contact model (``contact``, gearmesh.contact_model) has them too. (The tables' own reach,
    DEFAULT_TABLE_EXTENSION, is another quantity with its own default.)"""
    import importlib
    import inspect
    import pkgutil

    import gearmesh
    from gearmesh.choices import DEFAULT_CORNER_EXTENSION, TOOTH_METHODS
    from gearmesh.contact_model import DEFAULT_TABLE_EXTENSION, ContactModel

    declared = {"method": DEFAULT_TOOTH_METHOD, "contact_law": DEFAULT_CONTACT_LAW,
                "contact_law_name": DEFAULT_CONTACT_LAW, "name": DEFAULT_CONTACT_LAW,
                "corner_extension": DEFAULT_CORNER_EXTENSION}
    seen, wrong = 0, []
    for info in pkgutil.walk_packages(gearmesh.__path__, "gearmesh."):
        if info.name.endswith(("__main__", "jobserver")):
            continue
        module = importlib.import_module(info.name)
        for fname, func in inspect.getmembers(module, inspect.isfunction):
            if func.__module__ != module.__name__ or fname.startswith("_"):
                continue
            for p in inspect.signature(func).parameters.values():
                if isinstance(p.default, ContactModel):
                    seen += 1
                    c = p.default
                    if (c.method, c.contact_law) != (DEFAULT_TOOTH_METHOD, DEFAULT_CONTACT_LAW) \
                            or c.extension not in (DEFAULT_CORNER_EXTENSION, DEFAULT_TABLE_EXTENSION):
                        wrong.append(f"{module.__name__}.{fname}({p.name}={c!r})")
                    continue
                if p.name not in declared or p.default in (inspect.Parameter.empty, None):
                    continue  # required, or None: the study section's (itself the declared default)
                if p.name == "method" and p.default not in TOOTH_METHODS:
                    continue  # another kind of method (the optimiser's GA, a slice rule)
                if p.name == "name" and p.default not in CONTACT_LAWS:
                    continue
                seen += 1
                if p.default != declared[p.name]:
                    wrong.append(f"{module.__name__}.{fname}({p.name}={p.default!r})")
    assert seen >= 12 and not wrong, wrong  # 12 in all: five keywords and seven contact models


@pytest.mark.workflow
def test_every_result_names_the_deflections_it_includes(doors):
    """The gear bodies and the system deflection (shafts and bearings) each result was computed with,
    named in the file as the physics layer states them: the LTCA, the impact stage, the dynamics and
    the rating."""
    from gearmesh.body import describe_body
    from gearmesh.deflection import describe_deflection

    geom = pair_geometry(load_pair(_pair_file(doors)))
    for stage in ("ltca", "impact", "dynamics", "rating"):
        attrs = read_dataset(doors / "results/doors" / PAIR / f"standard/{stage}.nc").attrs
        assert attrs["gear_body"] == describe_body(geom), stage
        assert attrs["system_deflection"] == describe_deflection(geom), stage

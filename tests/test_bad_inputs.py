"""A corpus of bad inputs (issue 11), generated here: pair files, study configs, hostile files
and CLI arguments. Each is refused with exit code 2 and one stderr line
``gearmesh: error: FIELD ...`` naming the field, no traceback, nothing written, in bounded
time and memory; ``snakemake -n`` refuses the same study configs before any job; a run killed
at a random moment and rerun leaves no temporary file behind."""

from __future__ import annotations

import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import pytest
import yaml

from gearmesh.cli import main
from gearmesh.io import host_name
from pairs import low_fluctuation_pair1

# Bounded work without a clock (timings differ 2x between machines): a refusal allocates less than
# this much (tracemalloc traces numpy's buffers too), and a hang (a FIFO opened for reading)
# becomes a failure after HANG_GUARD_S instead of a CI run that never ends.
PEAK_BYTES_PER_REFUSAL = 400 * 2**20  # a study check builds a coarse FE tooth (~200 MiB)
HANG_GUARD_S = 120
MAX_LINE = 800  # characters of the one error line (field, excerpt of the value, rule)


def _pair(**changes) -> dict:
    return low_fluctuation_pair1(**{"name": "p", **changes})


def _without(key: str) -> dict:
    data = _pair()
    data.pop(key)
    return data


# (id, pair-file mapping, field the error line must start with)
BAD_PAIRS = [
    ("module 1e6 mm", _pair(normal_module_mm=1.0e6), "normal_module_mm"),
    ("module 1e-9 mm", _pair(normal_module_mm=1.0e-9), "normal_module_mm"),
    ("module 0", _pair(normal_module_mm=0), "normal_module_mm"),
    ("module text", _pair(normal_module_mm="big"), "normal_module_mm"),
    ("module 1e6 as YAML text", _pair(normal_module_mm="1e6"), "normal_module_mm"),
    ("module nan", _pair(normal_module_mm=float("nan")), "normal_module_mm"),
    ("module inf", _pair(normal_module_mm=float("inf")), "normal_module_mm"),
    ("face 1e-6 mm", _pair(face_width_mm=1.0e-6), "face_width_mm"),
    ("face 1e6 mm", _pair(face_width_mm=1.0e6), "face_width_mm"),
    ("face one of three", _pair(face_width_mm=[20, 20, 20]), "face_width_mm"),
    ("face negative gear", _pair(face_width_mm=[20, -1]), "face_width_mm[1]"),
    ("crowning 5 mm on 1.75", _pair(modification={"pinion": {"crowning_um": 5000}}), "modification.pinion.crowning_um"),
    ("tip relief 100 mm", _pair(modification={"gear": {"tip_relief_um": 1.0e5, "tip_relief_length_mm": 1}}),
     "modification.gear.tip_relief_um"),
    ("root relief 1 mm", _pair(modification={"gear": {"root_relief_um": 1000, "root_relief_length_mm": 1}}),
     "modification.gear.root_relief_um"),
    ("negative crowning", _pair(modification={"gear": {"crowning_um": -1}}), "modification.gear.crowning_um"),
    ("relief without length", _pair(modification={"gear": {"tip_relief_um": 5}}),
     "modification.gear.tip_relief_length_mm"),
    ("relief longer than flank", _pair(modification={"gear": {"tip_relief_um": 5, "tip_relief_length_mm": 50}}),
     "modification.gear.root_relief_length_mm + tip_relief_length_mm"),
    ("lead length beyond face", _pair(modification={"gear": {"unmodified_lead_length_mm": 500}}),
     "modification.gear.unmodified_lead_length_mm"),
    ("unknown modification key", _pair(modification={"gear": {"bulge_um": 1}}), "modification.gear.bulge_um"),
    ("modification of a third gear", _pair(modification={"idler": {}}), "modification.idler"),
    ("name with path", _pair(name="../../etc/x"), "name"),
    ("name absolute path", _pair(name="/etc/passwd"), "name"),
    ("name empty", _pair(name=""), "name"),
    ("name a number", _pair(name=7), "name"),
    ("name 300 characters", _pair(name="n" * 300), "name"),
    ("name with a space", _pair(name="my pair"), "name"),
    ("teeth one", _pair(teeth=[29]), "teeth"),
    ("teeth 3", _pair(teeth=[3, 49]), "teeth[0]"),
    ("teeth float", _pair(teeth=[29.5, 49]), "teeth[0]"),
    ("teeth bool", _pair(teeth=[True, 49]), "teeth[0]"),
    ("pressure angle 0", _pair(normal_pressure_angle_deg=0), "normal_pressure_angle_deg"),
    ("pressure angle 60", _pair(normal_pressure_angle_deg=60), "normal_pressure_angle_deg"),
    ("helix 75", _pair(helix_angle_deg=75), "helix_angle_deg"),
    ("helix negative", _pair(helix_angle_deg=-10), "helix_angle_deg"),
    ("helix hand up", _pair(helix_hand="up"), "helix_hand"),
    ("shift 5", _pair(profile_shift=[5, 0]), "profile_shift[0]"),
    ("centre distance negative", _pair(center_distance_mm=-70), "center_distance_mm"),
    ("centre distance too small", _pair(center_distance_mm=50), "center_distance_mm"),
    ("bore beyond root", _pair(bore_radius_mm=[24, 25]), "bore_radius_mm[0]"),
    ("bore negative", _pair(bore_radius_mm=[-1, 25]), "bore_radius_mm[0]"),
    ("poisson 0.7", _pair(material={"youngs_modulus_GPa": 210, "poisson_ratio": 0.7, "density_kg_m3": 7850}),
     "material.poisson_ratio"),
    ("young negative", _pair(material={"youngs_modulus_GPa": -1, "poisson_ratio": 0.3, "density_kg_m3": 7850}),
     "material.youngs_modulus_GPa"),
    ("material density text", _pair(material={"density_kg_m3": "heavy"}), "material.density_kg_m3"),
    ("addendum 0.1", _pair(addendum_coefficient=0.1), "addendum_coefficient"),
    ("tool tip too round", _pair(tool_tip_radius_coefficient=0.9), "tool_tip_radius_coefficient[0]"),
    ("unknown key", _pair(colour="red"), "pair.colour"),
    ("no teeth", _without("teeth"), "teeth"),
    ("no module", _without("normal_module_mm"), "normal_module_mm"),
    ("a list, not a mapping", [1, 2, 3], "pair"),
    ("huge value under unknown key", _pair(junk=list(range(5000))), "pair.junk"),
]

# (id, raw file content, field) — hostile or malformed files
ALIAS_BOMB = "name: p\n" + 'a0: &a0 ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]\n' + "".join(
    f"a{k}: &a{k} [" + ",".join([f"*a{k - 1}"] * 9) + "]\n" for k in range(1, 10))
BAD_FILES = [
    ("alias bomb", ALIAS_BOMB, "file"),
    ("one alias", "name: &n p\nteeth: [29, 49]\nother: *n\n", "file"),
    ("deep nesting", "x: " + "[" * 5000 + "]" * 5000 + "\n", "file"),
    ("30000 nodes", "x: [" + ",".join(["1"] * 30000) + "]\n", "file"),
    ("too large", "# " + "x" * 300_000 + "\n", "file"),
    ("binary", b"\xff\xfe\x00binary\x00", "file"),
    ("latin-1", "name: caf\xe9\n".encode("latin-1"), "file"),
    ("python tag", "!!python/object/apply:os.system ['echo pwned']\n", "file"),
    ("not YAML", "[not, a, mapping", "file"),
    ("tab indentation", "name: p\n\tteeth: [29, 49]\n", "file"),
    ("duplicate key", yaml.safe_dump(_pair()) + "teeth: [20, 40]\n", "teeth"),
    ("empty file", "", "file"),  # neither a pair file nor a study config: validate says so, not "pair file"
]

BASE_STUDY = {"study": "s", "pairs": ["p"]}


def _study(**sections) -> dict:
    return {**BASE_STUDY, **sections}


SPEEDS = {"start": 2000, "stop": 4000, "step": 1000}
# (id, study-config mapping, field)
BAD_STUDIES = [
    ("no study", {"pairs": ["p"]}, "study"),
    ("study name 300 chars", _study(study="s" * 300), "study"),
    ("study name with slash", _study(study="a/b"), "study"),
    ("pairs empty", _study(pairs=[]), "pairs"),
    ("pair name path", _study(pairs=["../x"]), "pairs[0]"),
    ("pair missing", _study(pairs=["nope"]), "pairs"),
    ("unknown section", _study(colour=1), "colour"),
    ("huge list under unknown key", _study(junk=list(range(5000))), "junk"),
    ("positions 2", _study(contact_lines={"positions": 2}), "contact_lines.positions"),
    ("stiffness torque nan", _study(stiffness={"torque_Nm": float("nan")}), "stiffness.torque_Nm"),
    ("stiffness torque inf", _study(stiffness={"torque_Nm": float("inf")}), "stiffness.torque_Nm"),
    ("stiffness torque 1e12", _study(stiffness={"torque_Nm": 1.0e12}), "stiffness.torque_Nm"),
    ("stiffness torque 1e30", _study(stiffness={"torque_Nm": 1.0e30}), "stiffness.torque_Nm"),
    ("stiffness grid 2e9", _study(stiffness={"slices": 20000, "positions": 100000}), "stiffness.slices"),
    ("stiffness method", _study(stiffness={"method": "fem"}), "stiffness.method"),
    ("ltca torque nan", _study(ltca={"torques_Nm": [float("nan")]}), "ltca.torques_Nm[0]"),
    ("ltca torque 1e12", _study(ltca={"torques_Nm": [1.0e12]}), "ltca.torques_Nm[0]"),
    # the lead slope is the pair's (lead_slope_deviation_um), no longer a study setting
    ("ltca lead slope moved", _study(ltca={"lead_slope_um": [1.0e6, 0]}), "ltca.lead_slope_um"),
    ("ltca grid", _study(ltca={"positions": 10000, "points": 2000}), "ltca.points"),
    ("tca corner nan", _study(tca={"corner_extension": float("nan")}), "tca.corner_extension"),
    ("helix sweep stop < start", _study(helix_sweep={"pairs": ["p"], "start_deg": 40, "stop_deg": 10,
                                                     "step_deg": 1}), "helix_sweep.stop_deg"),
    ("helix sweep step 1e-9", _study(helix_sweep={"pairs": ["p"], "start_deg": 0, "stop_deg": 30,
                                                  "step_deg": 1.0e-9}), "helix_sweep.step_deg"),
    ("helix sweep start nan", _study(helix_sweep={"pairs": ["p"], "start_deg": float("nan"), "stop_deg": 30,
                                                  "step_deg": 1}), "helix_sweep.start_deg"),
    ("dynamics stop < start", _study(dynamics={"speeds_rpm": {"start": 5000, "stop": 1000, "step": 100}}),
     "dynamics.speeds_rpm.stop"),
    ("dynamics start nan", _study(dynamics={"speeds_rpm": {"start": float("nan"), "stop": 1000, "step": 100}}),
     "dynamics.speeds_rpm.start"),
    ("dynamics a million speeds", _study(dynamics={"speeds_rpm": {"start": 1000, "stop": 2000, "step": 0.001}}),
     "dynamics.speeds_rpm"),
    ("dynamics speeds too slow", _study(dynamics={"speeds_rpm": {"start": 1, "stop": 2, "step": 1}}),
     "dynamics.speeds_rpm"),
    ("dynamics work", _study(dynamics={"speeds_rpm": {"start": 100, "stop": 20000, "step": 1}}),
     "dynamics.speeds_rpm"),
    ("dynamics torque inf", _study(dynamics={"torques_Nm": float("inf")}), "dynamics.torques_Nm"),
    ("dynamics torque 1e12", _study(dynamics={"torques_Nm": 1.0e12, "speeds_rpm": SPEEDS}), "dynamics.torques_Nm"),
    ("dynamics torques list 1e12", _study(dynamics={"torques_Nm": [100, 1.0e12], "speeds_rpm": SPEEDS}),
     "dynamics.torques_Nm"),
    ("dynamics excitation", _study(dynamics={"excitation": "impact"}), "dynamics.excitation"),
    ("dynamics ltca without LTCA", _study(dynamics={"excitation": "ltca", "speeds_rpm": SPEEDS}),
     "dynamics.excitation"),
    ("dynamics table work", _study(dynamics={"excitation": "contact", "table_positions": 100000,
                                             "table_approaches": 100000, "speeds_rpm": SPEEDS}),
     "dynamics.table_positions"),
    ("dynamics damping nan", _study(dynamics={"damping_ratio": float("nan")}), "dynamics.damping_ratio"),
    ("dynamics bearing nan", _study(dynamics={"bearing_k_radial_N_per_m": float("nan")}),
     "dynamics.bearing_k_radial_N_per_m"),
    ("dynamics bearing 0", _study(dynamics={"bearing_k_axial_N_per_m": 0}), "dynamics.bearing_k_axial_N_per_m"),
    ("dynamics backlash nan", _study(dynamics={"backlash_um": float("nan")}), "dynamics.backlash_um"),
    ("dynamics courant nan", _study(dynamics={"courant": float("nan")}), "dynamics.courant"),
    ("dynamics courant 1.5", _study(dynamics={"courant": 1.5, "speeds_rpm": SPEEDS}), "dynamics.courant"),
    ("dynamics record odd", _study(dynamics={"record_cycles": 3, "speeds_rpm": SPEEDS}), "dynamics.record_cycles"),
    ("dynamics TE nan", _study(dynamics={"transmission_error_um": [0, float("nan")]}),
     "dynamics.transmission_error_um[1]"),
    ("dynamics steps per cycle", _study(dynamics={"steps_per_cycle_min": 10 ** 7, "speeds_rpm": SPEEDS}),
     "dynamics.speeds_rpm"),
    ("dynamics points per cycle", _study(dynamics={"points_per_cycle": 10 ** 9}), "dynamics.points_per_cycle"),
    ("dynamics 1000 sample speeds", _study(dynamics={"sample_speeds_rpm": [1000.0] * 1000}),
     "dynamics.sample_speeds_rpm"),
    ("train phase nan", _study(train_dynamics={"phase_offsets_cycles": [0, float("nan")]}),
     "train_dynamics.phase_offsets_cycles[1]"),
    ("train force 1e20", _study(train_dynamics={"static_force_N": 1.0e20}), "train_dynamics.static_force_N"),
    ("variant name with slash", _study(variants={"a/b": {}}), "variants"),
    ("variant crowning 5 mm", _study(variants={"v": {"modification": {"pinion": {"crowning_um": 5000}}}}),
     "variants.v.modification.pinion.crowning_um"),
    ("comparison without dynamics", _study(dynamics_comparison={}), "dynamics_comparison"),
    ("stiffness Fourier order 30 of 8 positions", _study(stiffness={"positions": 8, "fourier_order": 30}),
     "stiffness.fourier_order"),
    ("dynamics Fourier order 30 of 24 positions", _study(stiffness={"positions": 24},
                                                         dynamics={"fourier_order": 30, "speeds_rpm": SPEEDS}),
     "dynamics.fourier_order"),
    ("dynamics TE table and LTCA", _study(ltca={"torques_Nm": [100], "on": "gear"}, dynamics={"torques_Nm": 100, "on": "gear",
        "transmission_error_um": [0, 1, 0, 1, 0, 1, 0, 1], "speeds_rpm": SPEEDS}), "dynamics.transmission_error_um"),
    ("dynamics TE table too short", _study(dynamics={"transmission_error_um": [0, 1, 0], "speeds_rpm": SPEEDS}),
     "dynamics.fourier_order"),
    ("train 101 speeds", _study(train_dynamics={"speeds_rpm": {"start": 1000, "stop": 2000, "step": 10}}),
     "train_dynamics.speeds_rpm"),
    ("YAML on as true", "study: s\npairs: [p]\nltca: {on: gear}\n", "ltca.True"),
    ("impact torque 1e12", _study(impact={"torques_Nm": [1.0e12]}), "impact.torques_Nm[0]"),
    ("impact lead slope moved", _study(impact={"torques_Nm": [100], "lead_slope_um": [0, 1.0e6]}),
     "impact.lead_slope_um"),
    ("optimise torque 1e30", _study(optimise={"run": {"torque_Nm": 1.0e30}}), "optimise.run.torque_Nm"),
    ("optimise torque nan", _study(optimise={"run": {"torque_Nm": float("nan")}}), "optimise.run.torque_Nm"),
    ("optimise old flat section", _study(optimise={"method": "ga"}), "optimise.method"),
    ("optimise run name with a dot", _study(optimise={"a.b": {}}), "optimise"),
    ("optimise spectrum without the design torque", _study(optimise={"run": {"torques_Nm": [400, 1600]}}),
     "optimise.run.torque_Nm"),
    ("optimise spectrum torque 1e30", _study(optimise={"run": {"torque_Nm": 400, "torques_Nm": [400, 1.0e30]}}),
     "optimise.run.torques_Nm[1]"),
    ("optimise weights count", _study(optimise={"run": {"torque_Nm": 100, "torques_Nm": [100, 200],
                                                        "statistic": "mean", "weights": [1]}}), "optimise.run.weights"),
    ("optimise weights with max", _study(optimise={"run": {"torque_Nm": 100, "torques_Nm": [100, 200],
                                                           "weights": [1, 2]}}), "optimise.run.weights"),
    ("optimise weights negative", _study(optimise={"run": {"weights": [-1]}}), "optimise.run.weights[0]"),
    ("optimise statistic", _study(optimise={"run": {"statistic": "median"}}), "optimise.run.statistic"),
    ("optimise dynamic one speed", _study(optimise={"run": {"objective": "dynamic", "torque_Nm": 100,
                                                            "dynamic_speeds_rpm": [5000]}}),
     "optimise.run.dynamic_speeds_rpm"),
    ("optimise robust single point", _study(optimise={"run": {"objective": "robust", "torque_Nm": 100,
                                                              "tolerance_statistic": None}}),
     "optimise.run.objective"),
    ("optimise robust by default, no samples", _study(optimise={"run": {"torque_Nm": 100}}),
     "optimise.run.tolerance_statistic"),
    ("optimise unknown pareto objective", _study(optimise={"run": {"method": "nsga2",
                                                                   "pareto_objectives": ["impact", "noise"]}}),
     "optimise.run.pareto_objectives"),
    ("optimise negative pressure factor", _study(optimise={"run": {"constraints": {"pressure_factor": -1}}}),
     "optimise.run.constraints.pressure_factor"),
    ("optimise S_Hmin out of range", _study(optimise={"run": {"constraints": {"S_Hmin": 50}}}),
     "optimise.run.constraints.S_Hmin"),
    ("optimise harmonic order 4", _study(optimise={"run": {"constraints": {"harmonic_orders": [4]}}}),
     "optimise.run.constraints.harmonic_orders"),
    ("optimise tolerance statistic", _study(optimise={"run": {"tolerance_statistic": "median"}}),
     "optimise.run.tolerance_statistic"),
    ("optimise tolerance statistic without tolerances", _study(optimise={"run": {"torque_Nm": 100,
                                                                                 "tolerance_statistic": "max"}}),
     "optimise.run.tolerance_statistic"),
    ("optimise cvar level 100", _study(tolerances={"grade": 6}, optimise={"run": {
        "torque_Nm": 100, "tolerance_statistic": "cvar", "tolerance_level_percent": 100}}),
     "optimise.run.tolerance_level_percent"),
    ("optimise percentile level 101", _study(optimise={"run": {"tolerance_level_percent": 101}}),
     "optimise.run.tolerance_level_percent"),
    ("optimise window step coarse", _study(optimise={"run": {"torque_Nm": 100, "torques_Nm": [100, 150],
                                                             "tolerance_statistic": None,
                                                             "load_window_step_Nm": 60}}),
     "optimise.run.load_window_step_Nm"),
    ("optimise window step 0", _study(optimise={"run": {"load_window_step_Nm": 0}}),
     "optimise.run.load_window_step_Nm"),
    ("variant from unknown run", _study(variants={"o": {"from": "optimise.nothing"}}, optimise={"run": {
        "torque_Nm": 100}}), "variants.o.from"),
    ("variant from old form", _study(variants={"o": {"from": "optimise"}}), "variants.o.from"),
    ("tolerances grade 12", _study(tolerances={"grade": 12}), "tolerances.grade"),
    ("tolerances grade text", _study(tolerances={"grade": "six"}), "tolerances.grade"),
    ("tolerances lead on idler", _study(tolerances={"lead_on": ["idler"]}), "tolerances.lead_on"),
    ("tolerances samples -1", _study(tolerances={"samples": -1}), "tolerances.samples"),
    ("tolerances samples 1e6", _study(tolerances={"samples": 1000000}), "tolerances.samples"),
    ("tolerances sampling", _study(tolerances={"sampling": "sobol"}), "tolerances.sampling"),
    ("tolerances unknown parameter", _study(tolerances={"modification": {"tooth_um": 2}},
                                            optimise={"run": {"torque_Nm": 100}}),
     "tolerances.modification.tooth_um"),
    ("tolerances negative amount", _study(tolerances={"modification": {"tip_relief_um": -2}}),
     "tolerances.modification.tip_relief_um"),
    ("tolerances unknown key", _study(tolerances={"class": 6}), "tolerances.class"),
    ("impact window step 0", _study(impact={"torques_Nm": [100], "load_window_step_Nm": 0}),
     "impact.load_window_step_Nm"),
    ("impact design torque not among", _study(impact={"torques_Nm": [100], "design_torque_Nm": 50}),
     "impact.design_torque_Nm"),
    ("comparison couple unknown", _study(dynamics={"speeds_rpm": SPEEDS}, dynamics_comparison={"couples": [["p", "q"]]}),
     "dynamics_comparison.couples[0]"),
]

# (id, argv after the pair file, field)
BAD_ARGS = [
    ("torque text", ["ltca", "--torque-Nm", "abc"], "--torque-Nm"),
    ("torque nan", ["ltca", "--torque-Nm", "nan"], "torque_Nm"),
    ("torque inf", ["stiffness", "--torque-Nm", "inf"], "torque_Nm"),
    ("torque 1e12", ["ltca", "--torque-Nm", "1e12"], "--torque-Nm"),
    ("torque 1e30", ["stiffness", "--torque-Nm", "1e30"], "--torque-Nm"),
    ("torque negative", ["ltca", "--torque-Nm", "-5"], "torque_Nm"),
    ("torque missing", ["ltca"], "--torque-Nm"),
    ("slices 0", ["stiffness", "--slices", "0"], "--slices"),
    ("slices x positions", ["stiffness", "--slices", "20000", "--positions", "100000"], "--slices"),
    ("method", ["stiffness", "--method", "fem"], "--method"),
    ("ltca grid", ["ltca", "--torque-Nm", "100", "--positions", "10000", "--points", "2000"], "--points"),
    ("contact law", ["ltca", "--torque-Nm", "100", "--contact-law", "hertz"], "--contact-law"),
    ("speeds text", ["dynamics", "--torque-Nm", "200", "--speeds", "fast"], "speeds_rpm"),
    ("speeds stop < start", ["dynamics", "--torque-Nm", "200", "--speeds", "2000:1000:100"], "speeds_rpm.stop"),
    ("speeds nan", ["dynamics", "--torque-Nm", "200", "--speeds", "nan:1000:100"], "speeds_rpm"),
    ("speeds a million", ["dynamics", "--torque-Nm", "200", "--speeds", "1000:2000:0.001"], "speeds_rpm"),
    ("speeds work", ["dynamics", "--torque-Nm", "200", "--speeds", "100:20000:1"], "speeds_rpm"),
    ("speeds huge string", ["dynamics", "--torque-Nm", "200", "--speeds", "1:" * 50_000], "speeds_rpm"),
    ("backlash nan", ["dynamics", "--torque-Nm", "200", "--speeds", "1000", "--backlash-um", "nan"], "--backlash-um"),
    ("on idler", ["ltca", "--torque-Nm", "100", "--on", "idler"], "--on"),
    ("impact torque 1e12", ["impact", "--torque-Nm", "1e12", "--speed-rpm", "5000"], "--torque-Nm"),
    ("optimise torque 1e30", ["optimise", "--torque-Nm", "1e30", "--speed-rpm", "5000"], "--torque-Nm"),
    ("optimise no torque", ["optimise"], "--torque-Nm"),
    ("optimise torques text", ["optimise", "--torques-Nm", "100,abc"], "--torques-Nm"),
    ("optimise torques nan", ["optimise", "--torques-Nm", "100,nan"], "--torques-Nm"),
    ("optimise torques 1e30", ["optimise", "--torques-Nm", "100,1e30"], "--torques-Nm"),
    ("optimise torques negative", ["optimise", "--torques-Nm", "100,-5"], "torques_Nm"),
    ("optimise weights count", ["optimise", "--torques-Nm", "100,200", "--weights", "1"], "weights"),
    ("optimise weights text", ["optimise", "--torques-Nm", "100,200", "--weights", "1,x"], "--weights"),
    ("optimise objective", ["optimise", "--torque-Nm", "100", "--objective", "noise"], "--objective"),
    ("optimise dynamic factor zero", ["optimise", "--torque-Nm", "100", "--dynamic-factor", "0"],
     "--dynamic-factor"),
    ("optimise constraint text", ["optimise", "--torque-Nm", "100", "--pressure-factor", "tight"], "--pressure-factor"),
    ("optimise orders out of range", ["optimise", "--torque-Nm", "100", "--harmonic-orders", "1,7"],
     "--harmonic-orders"),
    ("optimise flag word", ["optimise", "--torque-Nm", "100", "--criteria-over-samples", "maybe"],
     "--criteria-over-samples"),
    ("optimise pareto word", ["optimise", "--torque-Nm", "100", "--pareto-objectives", "impact,noise"],
     "--pareto-objectives"),
    ("optimise robust single point", ["optimise", "--torque-Nm", "100", "--objective", "robust",
                                      "--tolerance-samples", "0"], "objective"),
    ("optimise grade text", ["optimise", "--torque-Nm", "100", "--grade", "six"], "--grade"),
    ("optimise samples -1", ["optimise", "--torque-Nm", "100", "--tolerance-samples", "-1"], "--tolerance-samples"),
    ("optimise samples text", ["optimise", "--torque-Nm", "100", "--tolerance-samples", "x"], "--tolerance-samples"),
    ("optimise grade 0", ["optimise", "--torque-Nm", "100", "--tolerance-samples", "4", "--grade", "0"],
     "--grade"),
    ("optimise samples without tolerances", ["optimise", "--torque-Nm", "100", "--tolerance-samples", "4",
                                             "--grade", "none"], "tolerance_statistic"),
    ("optimise level 150", ["optimise", "--torque-Nm", "100", "--tolerance-samples", "4", "--grade", "6",
                            "--tolerance-statistic", "percentile", "--tolerance-level", "150"],
     "--tolerance-level"),
    ("optimise sampling", ["optimise", "--torque-Nm", "100", "--sampling", "sobol"], "--sampling"),
    ("optimise amount tolerance nan", ["optimise", "--torque-Nm", "100", "--tolerance-samples", "4",
                                       "--amount-tolerance-um", "nan"], "tolerances.modification"),
    ("optimise write pair folder", ["optimise", "--torque-Nm", "100", "--write-pair", "/nonexistent/o.yaml"],
     "--write-pair"),
    ("optimise write pair not yaml", ["optimise", "--torque-Nm", "100", "--write-pair", "o.txt"], "--write-pair"),
    ("optimise write pair bad name", ["optimise", "--torque-Nm", "100", "--write-pair", "a b.yaml"], "--write-pair"),
    ("unknown command", None, "command"),
    ("unknown option", ["stiffness", "--colour", "red"], "arguments"),
]


def _refused(argv: list[str], capsys, cwd: Path, field: str) -> str:
    """Run the CLI in-process; assert the refusal contract; return the error line."""
    before = sorted(cwd.rglob("*"))
    def hung(signum, frame):
        raise AssertionError(f"no refusal after {HANG_GUARD_S} s: the CLI blocks on {argv}")

    previous = signal.signal(signal.SIGALRM, hung)
    signal.alarm(HANG_GUARD_S)
    tracemalloc.start()
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse refusals exit through parser.error
        code = exc.code
    finally:
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    out, err = capsys.readouterr()
    lines = err.strip().splitlines()
    assert code == 2, err
    assert len(lines) == 1, err[:2000]
    assert lines[0].startswith(f"gearmesh: error: {field}"), lines[0]
    assert "Traceback" not in err and out == ""
    assert len(lines[0]) <= MAX_LINE
    assert peak < PEAK_BYTES_PER_REFUSAL, f"{peak / 2**20:.0f} MiB allocated before the refusal"
    assert sorted(cwd.rglob("*")) == before  # nothing written
    return lines[0]


def _write(path: Path, content) -> Path:
    if isinstance(content, bytes):
        path.write_bytes(content)
    elif isinstance(content, str):
        path.write_text(content)
    else:
        path.write_text(yaml.safe_dump(content, sort_keys=False))
    return path


@pytest.mark.parametrize("data, field", [c[1:] for c in BAD_PAIRS], ids=[c[0] for c in BAD_PAIRS])
def test_bad_pair_file_is_refused(tmp_path, capsys, data, field):
    path = _write(tmp_path / "p.yaml", data)
    for command in (["validate"], ["geometry"]):
        _refused([*command, str(path)], capsys, tmp_path, field)


@pytest.mark.parametrize("content, field", [c[1:] for c in BAD_FILES], ids=[c[0] for c in BAD_FILES])
def test_hostile_file_is_refused(tmp_path, capsys, content, field):
    path = _write(tmp_path / "p.yaml", content)
    _refused(["validate", str(path)], capsys, tmp_path, field)


@pytest.mark.parametrize("path", ["/dev/zero", "/dev/urandom", "/dev/null", "/tmp", "/nonexistent/x.yaml"])
def test_what_is_not_a_file_is_refused(tmp_path, capsys, path):
    _refused(["validate", path], capsys, tmp_path, "file")


def test_fifo_is_refused_without_blocking(tmp_path, capsys):
    os.mkfifo(tmp_path / "fifo.yaml")  # opening it would block until a writer comes
    _refused(["validate", str(tmp_path / "fifo.yaml")], capsys, tmp_path, "file")


@pytest.fixture
def study_dir(tmp_path, monkeypatch):
    """A folder with a working pair p under pairs/ (studies name pairs_dir: pairs)."""
    (tmp_path / "pairs").mkdir()
    (tmp_path / "pairs/p.yaml").write_text(yaml.safe_dump(_pair()))
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.mark.parametrize("config, field", [c[1:] for c in BAD_STUDIES], ids=[c[0] for c in BAD_STUDIES])
def test_bad_study_config_is_refused(study_dir, capsys, config, field):
    path = _write(study_dir / "study.yaml", config + "pairs_dir: pairs\n" if isinstance(config, str)
                  else {**config, "pairs_dir": "pairs"})
    _refused(["validate", str(path)], capsys, study_dir, field)


def test_the_study_corpus_base_is_valid(study_dir, capsys):
    """The mutations above are refused for what they change: the base study passes."""
    path = _write(study_dir / "study.yaml", {**_study(dynamics={"speeds_rpm": SPEEDS}), "pairs_dir": "pairs"})
    assert main(["validate", str(path)]) == 0
    assert "study config" in capsys.readouterr().out


@pytest.mark.parametrize("args, field", [c[1:] for c in BAD_ARGS], ids=[c[0] for c in BAD_ARGS])
def test_bad_cli_arguments_are_refused(tmp_path, capsys, args, field):
    path = _write(tmp_path / "p.yaml", _pair())
    argv = ["frobnicate", str(path)] if args is None else [args[0], str(path), *args[1:]]
    _refused(argv, capsys, tmp_path, field)


def test_corpus_has_at_least_100_inputs():
    count = len(BAD_PAIRS) + len(BAD_FILES) + len(BAD_STUDIES) + len(BAD_ARGS) + 6
    assert count >= 100


def _cli(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "gearmesh.cli", *args], capture_output=True, text=True,
                          cwd=cwd, timeout=60)


@pytest.mark.workflow
def test_hostile_files_in_a_fresh_process_stay_small(tmp_path):
    """Alias bomb, /dev/zero, 30000 nodes and a large file as separate processes: one line,
    exit 2, no traceback, and the largest child stays below 400 MB of resident memory."""
    (tmp_path / "bomb.yaml").write_text(ALIAS_BOMB)
    (tmp_path / "nodes.yaml").write_text(BAD_FILES[3][1])
    (tmp_path / "big.yaml").write_text(BAD_FILES[4][1])
    for path in ("bomb.yaml", "/dev/zero", "nodes.yaml", "big.yaml"):
        proc = _cli("validate", path, cwd=tmp_path)
        assert proc.returncode == 2 and proc.stdout == ""
        assert len(proc.stderr.splitlines()) == 1 and proc.stderr.startswith("gearmesh: error: file")
    # the peak of these children alone: RUSAGE_CHILDREN of this process also counts every earlier
    # test's children (a workflow job of the end-to-end test), so measure them from a fresh parent
    script = ("import resource, subprocess, sys\n"
              "for p in sys.argv[1:]:\n"
              "    subprocess.run([sys.executable, '-m', 'gearmesh.cli', 'validate', p], capture_output=True, timeout=60)\n"
              "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
    out = subprocess.run([sys.executable, "-c", script, "bomb.yaml", "/dev/zero", "nodes.yaml", "big.yaml"],
                         capture_output=True, text=True, cwd=tmp_path, timeout=300)
    peak_mb = int(out.stdout.strip()) / 1024
    assert peak_mb < 400


# --------------------------------------------------------------------------------------
# The workflow refuses the same study configs before any job, and leaves no debris
# --------------------------------------------------------------------------------------

needs_snakemake = pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake not installed")


def _workflow_copy(root: Path, tmp: Path) -> Path:
    for item in ("Snakefile", "workflow", "config"):
        src = root / item
        (shutil.copytree(src, tmp / item) if src.is_dir() else shutil.copy(src, tmp / item))
    return tmp


def _snakemake(cwd: Path, *args: str, **kwargs) -> subprocess.Popen | subprocess.CompletedProcess:
    exe = shutil.which("snakemake", path=str(Path(sys.executable).parent)) or "snakemake"
    return subprocess.run([exe, "--cores", "2", *args], cwd=cwd, capture_output=True, text=True, timeout=300,
                          **kwargs)


SNAKEMAKE_CASES = [  # (file name, content, field): a handful, each Snakemake start costs ~2 s
    ("nan.yaml", "study: s\npairs: [low_fluctuation_pair1]\nltca: {torques_Nm: [.nan]}\n", "ltca.torques_Nm[0]"),
    ("speeds.yaml", "study: s\npairs: [low_fluctuation_pair1]\ndynamics: {speeds_rpm: {start: 5000, stop: 1000, step: 10}}\n",
     "dynamics.speeds_rpm.stop"),
    ("twice.yaml", "study: s\nstudy: t\npairs: [low_fluctuation_pair1]\n", "study"),
    ("long.yaml", f"study: {'s' * 300}\npairs: [low_fluctuation_pair1]\n", "study"),
    ("nostudy.yaml", "pairs: [low_fluctuation_pair1]\n", "study"),
    ("comparison.yaml", "study: s\npairs: [low_fluctuation_pair1]\ndynamics_comparison: {}\n", "dynamics_comparison"),
    ("bomb.yaml", "study: s\npairs: [low_fluctuation_pair1]\n" + ALIAS_BOMB.replace("name: p\n", ""), "file"),
]


@pytest.mark.workflow
@needs_snakemake
def test_snakemake_refuses_the_same_configs_before_any_job(root, tmp_path, monkeypatch, capsys):
    work = _workflow_copy(root, tmp_path)
    monkeypatch.chdir(work)
    for name, content, field in SNAKEMAKE_CASES:
        (work / name).write_text(content)
        line = _refused(["validate", name], capsys, work, field)
        proc = _snakemake(work, "-n", "--configfile", name)
        assert proc.returncode == 2, (name, proc.stderr[-2000:])
        assert "Traceback" not in proc.stderr and len(proc.stderr.strip().splitlines()) == 1, proc.stderr[-2000:]
        if field == "file":  # the same reason; Snakemake passes the file by its absolute path
            assert proc.stderr.strip() == line.replace(f"'{name}'", f"'{work / name}'")
        else:
            assert proc.stderr.strip() == line
        assert not (work / "results").exists()


def _dead_pid() -> int:
    """The PID of a process of this host that has exited."""
    proc = subprocess.Popen([sys.executable, "-c", ""])
    proc.wait()
    return proc.pid


@pytest.mark.workflow
@needs_snakemake
def test_killed_run_rerun_leaves_no_temporary_files(root, tmp_path):
    """kill -9 of the whole run at a random moment, then --unlock and a rerun: every target
    exists and no .NAME.HOST.PID.tmp.* is left (some planted as if from an earlier killed run)."""
    work = _workflow_copy(root, tmp_path)
    config = {"study": "k", "pairs": ["low_fluctuation_pair1"], "contact_lines": {"positions": 24},
              "geometry": {"involute_points": 20, "fillet_points": 10, "face_points": 5},
              "stiffness": {"slices": 40, "positions": 24}}
    (work / "k.yaml").write_text(yaml.safe_dump(config))
    base = work / "results/k/low_fluctuation_pair1"
    (base / "plots").mkdir(parents=True)
    (base / f".geometry.{host_name()}.{_dead_pid()}.tmp.nc").write_bytes(b"CDF\x01truncated")
    (base / f"plots/.stiffness.{host_name()}.{_dead_pid()}.tmp.png").write_bytes(b"")
    exe = shutil.which("snakemake", path=str(Path(sys.executable).parent)) or "snakemake"
    run = subprocess.Popen([exe, "--cores", "2", "--configfile", "k.yaml"], cwd=work, start_new_session=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(random.Random(11).uniform(2.0, 5.0))
    try:
        os.killpg(run.pid, signal.SIGKILL)
    except ProcessLookupError:  # finished already: the planted files still test the cleanup
        pass
    run.wait(timeout=60)
    assert _snakemake(work, "--unlock", "--configfile", "k.yaml").returncode == 0
    again = _snakemake(work, "--configfile", "k.yaml", "--rerun-incomplete")
    assert again.returncode == 0, again.stderr[-3000:]
    leftovers = [p.name for p in (work / "results").rglob("*") if ".tmp" in p.name]
    assert leftovers == []
    for name in ("geometry.nc", "contact_lines.nc", "stiffness.nc", "plots/stiffness.png"):
        assert (base / name).stat().st_size > 0
    # the killed run's job-server socket folder (gearmesh.jobserver) was removed by the rerun's server
    from gearmesh.jobserver import FOLDER_PREFIX

    assert not list(Path(tempfile.gettempdir()).glob(f"{FOLDER_PREFIX}{run.pid}-*"))


@pytest.mark.parametrize("name", ["helical_z29_71_m5", "low_fluctuation_pair1", "transition_curve_z23_62"])
def test_the_dynamics_work_estimate_is_within_a_fifth_of_the_fe_tooths(name):
    """The work limit's estimate takes the hob-fillet cantilever's stiffness for the FE tooth's
    (checks._ESTIMATE_METHOD: two FE solves cost more than the rest of a study's checks): its RK4
    steps are at most 20 % fewer than the same coarse model on the FE tooth gives, and never more
    (the cantilever is the more compliant tooth), as its docstring says."""
    import numpy as np

    from gearmesh.datasets.dynamics import checks
    from gearmesh.datasets.dynamics.inputs import _solver
    from gearmesh.dynamics import step_plan
    from gearmesh.pairfile import example_pair, load_pair
    from gearmesh.schema import settings_object
    from gearmesh.settings import Dynamics

    pair = load_pair(example_pair(name))
    section = settings_object(Dynamics, {"torques_Nm": [200.0], "speeds_rpm": [1000.0, 5000.0, 20000.0]})
    assert section.method == "fe"

    def steps(model, speeds) -> int:
        _, per_cycle, transient, _ = step_plan(model, speeds, _solver(section))
        return int(((transient + _solver(section).record_cycles) * per_cycle).max())

    speeds, (estimate,) = checks._pair_estimate(pair, section, 24)
    fe = checks.pair_model_of(pair, 200.0, section, "tvms", (checks._ESTIMATE_SLICES, 24))
    assert np.array_equal(speeds, [1000.0, 5000.0, 20000.0])
    assert 0.8 * steps(fe, speeds) <= steps(estimate, speeds) <= steps(fe, speeds)

"""Figures: every plot function draws from the datasets the stages write (coarse settings) and
the drawn figure has none of the layout faults of :mod:`figure_checks` (a legend entry for
nothing drawn or for a hidden curve, overlapping texts, a label cut by its axes, a legend over
a curve); the checker itself catches each fault; labels and scales say what they should."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from matplotlib.collections import QuadMesh
from matplotlib.figure import Figure

from figure_checks import layout_faults
from gearmesh.datasets import dynamics as dy
from gearmesh.datasets import geometry as geo
from gearmesh.datasets import impact as im
from gearmesh.datasets import ltca as lt
from gearmesh.datasets import optimise as opd
from gearmesh.datasets import stiffness as st
from gearmesh.datasets.fe import fe_compliance_dataset
from gearmesh.gear import load_pair
from gearmesh.plots import dynamics, fe, geometry, impact, ltca, optimise, stiffness
from gearmesh.plots.common import coinciding, end_labels, number, pair_label, subplots, title

ROOT = Path(__file__).resolve().parents[1]
COARSE_IMPACT = {"points": 15, "window_positions": 16, "face_samples": 65}
#: The optimisations as single-point runs (the default, robust over tolerance samples, needs a tolerances section)
SINGLE_POINT = {"objective": "force", "tolerance_statistic": None}
RELIEF = {"modification": {"gear": {"tip_relief_um": 20, "tip_relief_length_mm": 3}, "pinion": {"crowning_um": 10}}}


@pytest.fixture(scope="module")
def data():
    """Every stage's dataset of the impact case pair (standard and relieved) at coarse settings,
    the three-gear train and the study tables: a few seconds."""
    pair = load_pair(ROOT / "config/pairs/seed000_case.yaml")
    relief = st.apply_variant(pair, "relief", RELIEF)
    out = {"geometry": geo.geometry_dataset(pair), "contact_lines": geo.contact_lines_dataset(pair, positions=60),
           "stiffness": st.stiffness_dataset(pair, slices=40, positions=60, torque_Nm=1000),
           "tca": lt.tca_dataset(relief, positions=24, points=15),
           "ltca": lt.ltca_dataset(relief, torques_Nm=(400, 1600), positions=24, points=15),
           "helix_sweep": geo.helix_sweep_dataset({"case": pair}, 10, 30, 5, positions=60),
           "stiffness_table": st.stiffness_table_dataset({"case": pair}, methods=("traditional", "transition"),
                                                         slices=40, positions=60),
           "slice_convergence": st.slice_convergence_dataset({"case": pair}, slices=(10, 20, 40), positions=60),
           "fe_compliance": fe_compliance_dataset(pair, size=0.3, roll_nodes=5),
           "train": dy.train_dataset(load_pair(ROOT / "config/pairs/seed004_pair.yaml"), slices=40, positions=60),
           "ga": opd.optimise_dataset(pair, population=6, generations=2, random_baseline=True, **SINGLE_POINT,
                                      **COARSE_IMPACT),
           "nsga": opd.optimise_dataset(pair, method="nsga2", population=6, generations=2, **SINGLE_POINT,
                                        pareto_objectives=["impact", "lte", "root_stress"],
                                        constraints={"root_stress_factor": 1.1}, **COARSE_IMPACT)}
    for name, p in (("standard", pair), ("relief", relief)):
        out[f"impact_{name}"] = im.impact_dataset(p, torques_Nm=(400, 1600), speeds_rpm=(2500, 5000),
                                                  simulate_torques_Nm=(1600,), variant=name, design_torque_Nm=400,
                                                  load_window_step_Nm=400, **COARSE_IMPACT)
        out[f"dynamics_{name}"] = dy.dynamics_dataset(
            p, torques_Nm=(1000,), excitation="contact", speeds_rpm={"start": 2000, "stop": 8000, "step": 2000},
            slices=40, positions=60, sample_speeds_rpm=(5000,), refine_resonances=False, points=15,
            table_positions=16, table_approaches=16, variant=name)
        for key in (f"impact_{name}", f"dynamics_{name}"):
            out[key].attrs["variant"] = name
    for ds in out.values():
        ds.attrs["pair_name"] = "seed000_case"
    return out


@pytest.fixture
def drawn(monkeypatch):
    """The figures saved while the test runs, by file name."""
    figures: dict[str, Figure] = {}
    save = Figure.savefig

    def recording(self, fname, *args, **kwargs):
        save(self, fname, *args, **kwargs)
        figures[Path(str(fname)).name.split(".")[1] if str(fname).count(".") > 1 else Path(str(fname)).stem] = self

    monkeypatch.setattr(Figure, "savefig", recording)
    return figures


def _outputs(tmp_path, *names):
    return {name: str(tmp_path / f"{name}.png") for name in names}


# (plot function, its inputs from the data fixture, its outputs)
FIGURES = {
    "geometry": (geometry.geometry_figures, {"geometry": "geometry"}, ("tooth_profile",)),
    "contact_lines": (geometry.contact_lines_figures, {"contact_lines": "contact_lines"},
                      ("contact_length", "contact_lines")),
    "helix_sweep": (geometry.helix_sweep_figures, {"helix_sweep": "helix_sweep"}, ("helix_sweep",)),
    "stiffness": (stiffness.stiffness_figures, {"stiffness": "stiffness"}, ("stiffness",)),
    "stiffness_table": (stiffness.stiffness_table_figures, {"stiffness_table": "stiffness_table"},
                        ("stiffness_table",)),
    "slice_convergence": (stiffness.slice_convergence_figures, {"slice_convergence": "slice_convergence"},
                          ("slice_convergence",)),
    "fe": (fe.fe_compliance_figures, {"fe_compliance": "fe_compliance"}, ("fe_compliance",)),
    "tca": (ltca.tca_figures, {"tca": "tca"}, ("tca",)),
    "ltca": (ltca.ltca_figures, {"ltca": "ltca"}, ("te_lte", "contact_pattern")),
    "impact": (impact.impact_figures, {"impact": "impact_relief"}, ("force_speed", "trajectory", "simulation")),
    "impact_variants": (impact.impact_study_figures, {"impact": ["impact_standard", "impact_relief"]},
                        ("impact_force", "robustness")),
    "dynamics": (dynamics.dynamics_figures, {"dynamics": "dynamics_relief"}, ("rms", "spectrum", "engagement")),
    "dynamics_variants": (dynamics.dynamics_variants_figures, {"dynamics": ["dynamics_standard", "dynamics_relief"]},
                          ("dynamics_variants",)),
    "dynamics_comparison": (dynamics.dynamics_comparison_figures,
                            {"dynamics": ["dynamics_standard", "dynamics_relief"]}, ("dynamics_comparison",)),
    "train": (dynamics.train_figures, {"train": "train"}, ("spectrum",)),
    "optimise": (optimise.optimise_figures, {"ga": "ga"}, ("convergence", "modification")),
    "pareto": (optimise.pareto_figures, {"ga": "nsga"}, ("pareto",)),
}


def _draw(name, data, tmp_path):
    function, inputs, outputs = FIGURES[name]
    given = {k: [data[v] for v in names] if isinstance(names, list) else data[names] for k, names in inputs.items()}
    paths = _outputs(tmp_path, *outputs)
    function(given, paths)
    return paths


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_figures_are_written_without_layout_faults(name, data, drawn, tmp_path):
    paths = _draw(name, data, tmp_path)
    assert all(Path(p).stat().st_size > 10_000 for p in paths.values())
    assert set(drawn) == set(paths)
    faults = {figure: layout_faults(fig) for figure, fig in drawn.items()}
    assert not any(faults.values()), faults


def test_contact_pattern_scale_per_panel_and_no_contact_on_the_colour_bar(data, drawn, tmp_path):
    _draw("ltca", data, tmp_path)
    fig = drawn["contact_pattern"]
    meshes = [c for a in fig.axes for c in a.collections if isinstance(c, QuadMesh) and c.colorbar is not None]
    assert len(meshes) == data["ltca"].sizes["torque"]
    tops = [m.norm.vmax for m in meshes]
    assert tops[0] < tops[-1]  # the light load on its own scale, not on the heaviest's
    apart = []
    for mesh in meshes:
        cells = np.ma.getdata(mesh.get_array())
        assert np.isclose(mesh.norm.vmax, cells.max())
        # cells without contact drawn in the colour map's "under" colour, shown on the bar when there are any
        apart.append(bool((cells < 0).any()))
        assert mesh.colorbar.extend == ("min" if apart[-1] else "neither")
        assert ("no contact" in mesh.colorbar.ax.get_xlabel()) == apart[-1]
        assert not np.allclose(mesh.cmap.get_under()[:3], mesh.cmap(0.0)[:3])
    assert any(apart)


def test_te_lte_writes_the_separation_at_phi_1a(data, drawn, tmp_path):
    _draw("ltca", data, tmp_path)
    ax = drawn["te_lte"].axes[0]
    value = float(data["ltca"]["te_next_pair_at_engagement"]) * 1e6
    assert any(t.get_text() == f"TE(φ1A) = {number(value)} µm" for t in ax.texts)
    labels = ax.get_legend_handles_labels()[1]
    assert sum("touches before A" in s or "touches after A" in s for s in labels) == data["ltca"].sizes["torque"]


def test_modification_title_in_words_and_convergence_states_a_reduction(data, drawn, tmp_path):
    _draw("optimise", data, tmp_path)
    title = drawn["modification"]._suptitle.get_text()
    assert "tip relief" in title and "lead crowning" in title or "no crowning" in title
    assert not any(f"y{k}" in title for k in range(1, 7))
    head = drawn["convergence"].axes[0].get_title()
    assert "+" not in head and ("below the standard gear" in head or "above the standard gear" in head)


def test_over_precise_numbers_are_not_printed():
    assert [number(v) for v in (118.367, 170.045, 12500.0, 1000.0, 13.224, 0.01234, 2.5, 0.0)] == \
        ["118", "170", "12500", "1000", "13.2", "0.0123", "2.5", "0"]
    assert number(1.22e-15) == "1.22e-15" and number(float("nan")) == "nan"


def test_coinciding_curves_are_grouped_by_the_axis_range():
    x = np.linspace(0, 1, 50)
    curves = [x, x + 1e-4, 2 * x, x]
    assert coinciding(curves) == [[0, 1, 3], [2]]
    assert coinciding(curves, span=1e-3) == [[0, 3], [1], [2]]  # on a fine axis they separate


def test_end_labels_are_spread_and_outside_the_axes():
    fig, ax = subplots(figsize=(4, 3))
    for k in range(5):
        ax.plot([0, 1], [0, 1 + 0.001 * k])
    ax.set_ylim(0, 1.1)
    end_labels(ax, [1 + 0.001 * k for k in range(5)], [f"line {k}" for k in range(5)])
    assert layout_faults(fig) == []
    assert all(t.xy[0] == 1.0 for t in ax.texts)


def _faulty(kind: str) -> Figure:
    fig, ax = subplots(figsize=(4, 3))
    x = np.linspace(0, 1, 30)
    ax.plot(x, x, label="curve")
    if kind == "empty":
        ax.plot([], [], label="nothing")
    elif kind == "zero band":
        ax.axvspan(0.5, 0.5, label="band of no width")
    elif kind == "hidden":
        ax.plot(x, x, ls="--", label="same curve")
    elif kind == "overlap":
        ax.text(0.5, 0.5, "first text")
        ax.text(0.5, 0.5, "second text")
    elif kind == "cut":
        ax.annotate("a label across the frame", (1.0, 0.5), xytext=(-20, 0), textcoords="offset points")
    elif kind == "covered":
        ax.plot(x, 1 - x, label="falling")
        ax.legend(loc="center")
        return fig
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1))
    return fig


@pytest.mark.parametrize("kind, message", [
    ("empty", "nothing drawn"), ("zero band", "nothing drawn"), ("hidden", "hidden under another"),
    ("overlap", "texts overlap"), ("cut", "cut by the frame"), ("covered", "legend covers the curve")])
def test_the_layout_checker_finds_each_fault(kind, message):
    faults = layout_faults(_faulty(kind))
    assert any(message in f for f in faults), faults
    assert layout_faults(_faulty("none")) == []


@pytest.mark.workflow
def test_plot_modules_do_not_use_pyplot():
    code = ("import sys; import gearmesh.plots.common, gearmesh.plots.dynamics, gearmesh.plots.fe, "
            "gearmesh.plots.geometry, gearmesh.plots.impact, gearmesh.plots.ltca, gearmesh.plots.optimise, "
            "gearmesh.plots.stiffness; print('matplotlib.pyplot' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_figures_are_headed_by_the_pair_as_a_reader_knows_it():
    """A shipped example pair by its data (its name, seed000_case, is a source file number); a
    pair of the user's own by its name and data; a result without pair data by its name."""
    import json

    import xarray as xr
    from gearmesh.pipeline import provenance_config

    pair = load_pair(ROOT / "config/pairs/seed000_case.yaml")
    ds = xr.Dataset(attrs={"pair_name": "seed000_case", "config_json": json.dumps(provenance_config({}, pair))})
    assert title(ds, "LTE") == "29/71 teeth, module 5 mm, helix 27.5°, face 42 mm — LTE"
    ds.attrs["pair_name"] = "stage_2"
    assert pair_label(ds) == "stage_2: 29/71 teeth, module 5 mm, helix 27.5°, face 42 mm"
    assert pair_label(xr.Dataset(attrs={"pair_name": "stage_2"})) == "stage_2"

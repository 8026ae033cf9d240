"""Figures: every plot function draws from the datasets the stages write (coarse settings) and
the drawn figure has none of the layout faults of :mod:`figure_checks` (a legend entry for
nothing drawn or for a hidden curve, overlapping texts, a label cut by its axes, a legend over
a curve); the checker itself catches each fault; labels and scales say what they should."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.collections import QuadMesh
from matplotlib.figure import Figure
from PIL import Image

from figure_checks import layout_faults
from gearmesh.datasets import dynamics as dy
from gearmesh.datasets import geometry as geo
from gearmesh.datasets import impact as im
from gearmesh.datasets import ltca as lt
from gearmesh.datasets import optimise as opd
from gearmesh.datasets import stiffness as st
from gearmesh.datasets.fe import fe_compliance_dataset
from gearmesh.pairfile import load_pair, variant_pair
from gearmesh.plots import dynamics, fe, geometry, impact, ltca, optimise, stiffness
from gearmesh.plots.common import DPI, coinciding, end_labels, lay_out, number, pair_label, save, subplots, title

ROOT = Path(__file__).resolve().parents[1]
COARSE_IMPACT = {"points": 15, "window_positions": 16, "face_samples": 65}
#: The optimisations as single-point runs (the default, robust over tolerance samples, needs a tolerances section)
SINGLE_POINT = {"objective": "force", "tolerance_statistic": None}
RELIEF = {"modification": {"gear": {"tip_relief_um": 20, "tip_relief_length_mm": 3}, "pinion": {"crowning_um": 10}}}


@pytest.fixture(scope="module")
def data():
    """Every stage's dataset of the impact case pair (standard and relieved) at coarse settings,
    the three-gear train and the study tables: a few seconds."""
    pair = load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml")
    relief = variant_pair(pair, "relief", RELIEF)  # a micro-geometry variant of the same pair, as the workflow makes it
    out = {"geometry": geo.geometry_dataset(pair), "contact_lines": geo.contact_lines_dataset(pair, positions=60),
           "stiffness": st.stiffness_dataset(pair, slices=40, positions=60, torque_Nm=1000),
           "tca": lt.tca_dataset(relief, positions=24, points=15),
           "ltca": lt.ltca_dataset(relief, torques_Nm=(400, 1600), positions=24, points=15),
           "helix_sweep": geo.helix_sweep_dataset({"case": pair}, pairs=["case"], start_deg=10, stop_deg=30,
                                                  step_deg=5, positions=60),
           "stiffness_table": st.stiffness_table_dataset({"case": pair}, pairs=["case"],
                                                         methods=("traditional", "transition"), slices=40, positions=60),
           "slice_convergence": st.slice_convergence_dataset({"case": pair}, pairs=["case"], slices=(10, 20, 40),
                                                              positions=60),
           "fe_compliance": fe_compliance_dataset(pair, size=0.3, roll_nodes=5),
           "train": dy.train_dataset(load_pair(ROOT / "config/pairs/printing_train_z88.yaml"), slices=40, positions=60),
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
        ds.attrs["pair_name"] = "helical_z29_71_m5"
    return out


@pytest.fixture
def drawn(monkeypatch):
    """The figures saved while the test runs, by file name."""
    figures: dict[str, Figure] = {}
    save = Figure.savefig

    def recording(self, fname, *args, **kwargs):
        save(self, fname, *args, **kwargs)
        self.written_cropped = kwargs.get("bbox_inches") == "tight"  # for layout_faults
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
    faults = {figure: layout_faults(fig, fig.written_cropped) for figure, fig in drawn.items()}
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
    """The separation at φ1A in the legend (not written over the curves), and each torque's entry
    timing as the dataset's flag says it."""
    _draw("ltca", data, tmp_path)
    ax = drawn["te_lte"].axes[0]
    ltca = data["ltca"]
    value = float(ltca["te_next_pair_at_engagement"]) * 1e6
    labels = ax.get_legend_handles_labels()[1]
    assert any(s.endswith(f"TE(φ1A) = {number(value)} µm") for s in labels) and not ax.texts
    timing = [("before" if early else "after") for early in ltca["touches_before_engagement"].values]
    assert [s.split("touches ")[1] for s in labels if "touches" in s] == [f"{t} A" for t in timing]


def test_modification_title_in_words_and_convergence_states_a_reduction(data, drawn, tmp_path):
    _draw("optimise", data, tmp_path)
    title = drawn["modification"]._suptitle.get_text()
    assert "tip relief" in title and "lead crowning" in title or "no crowning" in title
    assert not any(f"y{k}" in title for k in range(1, 7))
    head = drawn["convergence"].axes[0].get_title()
    assert "+" not in head and ("below the standard gear" in head or "above the standard gear" in head)


@pytest.mark.parametrize("bodies", [False, True], ids=["teeth alone", "solid-disc bodies"])
def test_stiffness_figure_shows_what_is_in_series_and_adds_up_to_k(data, drawn, tmp_path, bodies):
    """The stiffness figure's series terms add up to 1/K; its one-pair curve, summed over the pairs
    in mesh one base pitch apart, is the tooth pairs' stiffness; and K is those pairs in series with
    the mesh terms (the dataset's own: none for the default teeth alone, the gear bodies where the
    pair file describes them), which the legend names."""
    from gearmesh.plots.stiffness import PAIR_TERMS, _series_terms

    if bodies:  # the case pair with solid-disc webs (its face width) held at the bore
        from gearmesh.body import read_body

        pair = load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml")
        solid = pair.with_changes(body=read_body({"web_thickness_mm": [w * 1e3 for w in pair.face_width]}))
        ds = st.stiffness_dataset(solid, slices=40, positions=60, torque_Nm=1000)
        data = {**data, "stiffness": ds}
    ds = data["stiffness"]
    terms, pairs = _series_terms(ds)
    k = ds["mesh_stiffness"].values
    np.testing.assert_allclose(sum(terms.values()), 1.0 / k, rtol=1e-10)
    x = ds["position"].values
    pitch = x[-1] - x[0] + (x[1] - x[0])
    summed = sum(np.interp(x + j * pitch, ds["pair_position"].values, ds["pair_stiffness"].values, left=0, right=0)
                 for j in range(-6, 7))
    np.testing.assert_allclose(summed, pairs, rtol=1e-9)
    mesh = {t: c for t, c in terms.items() if t not in PAIR_TERMS.values()}
    assert ("gear bodies" in mesh) == bodies and set(mesh) <= {"gear bodies"}
    np.testing.assert_allclose(1.0 / (1.0 / pairs + sum(mesh.values(), np.zeros_like(k))), k, rtol=1e-10)
    _draw("stiffness", data, tmp_path)
    top, series = drawn["stiffness"].axes[:2]
    labels = top.get_legend_handles_labels()[1]
    assert labels[0] == ("K(φ): the tooth pairs, in series with the gear bodies" if bodies else "K(φ): the tooth pairs")
    if bodies:
        assert np.all(pairs > k)
        drawn_pairs = next(line for line in top.lines if line.get_label().startswith("the tooth pairs in parallel"))
        np.testing.assert_allclose(drawn_pairs.get_ydata(), pairs * 1e-6)
    else:
        np.testing.assert_allclose(pairs, k, rtol=1e-10)
    assert len(series.collections) == len(terms)  # one stacked band per series term


def test_the_impact_index_is_named_and_set_beside_the_simulated_excess(data, drawn, tmp_path):
    """F_s is called the energy method's impact index in the figure and the table, and its ratio
    to the entering pair's simulated excess stands beside it, the same number in both."""
    from gearmesh.choices import IMPACT_INDEX

    sets = [data["impact_standard"], data["impact_relief"]]
    table = im.impact_table_dataset(sets)
    ratio = table["impact_index_over_simulated_excess"]
    simulated = np.isfinite(table["simulated_entering_excess"].values)
    assert simulated.any() and not simulated.all()  # the simulated torque only
    np.testing.assert_allclose(ratio.values[simulated], (table["impact_force"] / table["simulated_entering_excess"])
                               .values[simulated], rtol=1e-12)
    assert table["impact_force"].attrs["long_name"].startswith(IMPACT_INDEX)
    _draw("impact_variants", data, tmp_path)
    fig = drawn["impact_force"]
    assert all(ax.get_ylabel().startswith(IMPACT_INDEX) for ax in fig.axes[:2])
    labels = fig.axes[0].get_legend_handles_labels()[1]
    for k, variant in enumerate(table["variant"].values):
        t = table["torque"].values[simulated[k]][0]
        expected = f"{number(float(ratio.sel(variant=variant, torque=t)), 2)}× at {number(t)} N m"
        assert any(lab.startswith(str(variant)) and expected in lab for lab in labels), (expected, labels)


def test_convergence_names_the_penalised_objective_j(data, drawn, tmp_path):
    """With constraints the objective is J, F_s plus the penalty of the violated constraints (up to
    many times F_s): labelled so, not as F_s; without, it is F_s itself."""
    optimise.plot_convergence(data["nsga"], tmp_path / "nsga.png")
    optimise.plot_convergence(data["ga"], tmp_path / "ga.png")
    constrained, plain = drawn["nsga"].axes[0], drawn["ga"].axes[0]
    assert constrained.get_ylabel().startswith("objective J = F_s + penalty of violated")
    assert "optimum J " in constrained.get_title()
    assert plain.get_ylabel() == "objective: F_s (N)" and "optimum J" not in plain.get_title()


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
    elif kind == "off canvas":
        fig.text(0.9, 0.5, "a_word_past_the_right_edge")  # no break: cannot be made to fit
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1))
    fig.set_layout_engine("constrained")  # the legend beside the axes kept on the canvas
    return fig


@pytest.mark.parametrize("kind, message", [
    ("empty", "nothing drawn"), ("zero band", "nothing drawn"), ("hidden", "hidden under another"),
    ("overlap", "texts overlap"), ("cut", "cut by the frame"), ("covered", "legend covers the curve"),
    ("off canvas", "off the canvas")])
def test_the_layout_checker_finds_each_fault(kind, message):
    faults = layout_faults(_faulty(kind), cropped=False)
    assert any(message in f for f in faults), faults
    assert layout_faults(_faulty("none"), cropped=False) == []


LONG = ("a pair of the user's own with a long name: 29/71 teeth, module 5 mm, helix 27.5°, face 42 mm — "
        "what the figure shows, at some length, so that it cannot fit on one line of a small figure")


def _png_size(path) -> tuple[int, int]:
    with Image.open(path) as im:
        return im.size


def test_a_laid_out_figure_is_written_as_laid_out_with_its_titles_broken_onto_the_canvas(tmp_path):
    fig, axes = subplots(1, 2, figsize=(5, 3), layout="constrained")
    for ax in axes:
        ax.plot([0, 1], [0, 1], label="curve")
    axes[1].legend(loc="upper left", bbox_to_anchor=(1.02, 1))  # beside the axes: the left one is off centre
    fig.suptitle(LONG)
    axes[0].set_title("a panel title much wider than its panel, which is narrower than the figure")
    save(fig, tmp_path / "f.png")
    assert _png_size(tmp_path / "f.png") == (5 * DPI, 3 * DPI)  # constrained layout's margins, not cropped
    head, *rest = fig.texts[0].get_text().split("\n")
    # broken where a dash separates when that line fits (the second), else at the next kind (a colon)
    assert head.endswith(":") and rest[0].endswith(" —")
    assert "\n" in axes[0].get_title()
    assert layout_faults(fig, cropped=False) == []


@pytest.mark.parametrize("rc", [{"figure.autolayout": True}, {"figure.constrained_layout.use": True}])
def test_a_laid_out_figure_is_written_as_laid_out_under_a_matplotlibrc_that_asks_for_a_layout(rc, tmp_path):
    with matplotlib.rc_context(rc):
        fig, axes = subplots(1, 2, figsize=(5, 3), layout="constrained")
        for ax in axes:
            ax.plot([0, 1], [0, 1], label="curve")
        axes[1].legend(loc="upper left", bbox_to_anchor=(1.02, 1))
        assert lay_out(fig)
        positions = [ax.get_position().bounds for ax in fig.axes]
        fig.savefig(tmp_path / "f.png", dpi=DPI)  # as save writes it
        assert [ax.get_position().bounds for ax in fig.axes] == positions


@pytest.mark.parametrize("off", ["a figure-level word", "an x label", "a y label"])
def test_a_figure_with_something_off_its_canvas_is_cropped_to_what_it_draws(off, tmp_path):
    fig = _faulty("off canvas" if off == "a figure-level word" else "none")  # constrained layout
    word = "an_x_label_of_one_word_far_wider_than_the_figure_it_is_drawn_in" * 2
    if off == "an x label":
        fig.axes[0].set_xlabel(word)
    elif off == "a y label":
        fig.axes[0].set_ylabel(word)
    save(fig, tmp_path / "f.png")
    assert _png_size(tmp_path / "f.png") != (4 * DPI, 3 * DPI)  # cropped to what it draws
    assert layout_faults(fig) == []
    plain, ax = subplots(figsize=(4, 3))  # no layout engine: cropped as before
    ax.plot([0, 1], [0, 1])
    save(plain, tmp_path / "g.png")
    assert _png_size(tmp_path / "g.png") != (4 * DPI, 3 * DPI)


@pytest.mark.workflow
def test_plot_modules_do_not_use_pyplot():
    code = ("import sys; import gearmesh.plots.common, gearmesh.plots.dynamics, gearmesh.plots.fe, "
            "gearmesh.plots.geometry, gearmesh.plots.impact, gearmesh.plots.ltca, gearmesh.plots.optimise, "
            "gearmesh.plots.stiffness; print('matplotlib.pyplot' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_figures_are_headed_by_the_pair_as_a_reader_knows_it():
    """A shipped example pair by its data (its name, helical_z29_71_m5, is a source file number); a
    pair of the user's own by its name and data; a result without pair data by its name."""
    import json

    import xarray as xr
    from gearmesh.pipeline import provenance_config

    pair = load_pair(ROOT / "config/pairs/helical_z29_71_m5.yaml")
    ds = xr.Dataset(attrs={"pair_name": "helical_z29_71_m5", "config_json": json.dumps(provenance_config({}, pair))})
    assert title(ds, "LTE") == "29/71 teeth, module 5 mm, helix 27.5°, face 42 mm — LTE"
    ds.attrs["pair_name"] = "stage_2"
    assert pair_label(ds) == "stage_2: 29/71 teeth, module 5 mm, helix 27.5°, face 42 mm"
    assert pair_label(xr.Dataset(attrs={"pair_name": "stage_2"})) == "stage_2"


def test_signoff_figure_says_what_its_markers_mean_in_legible_type(tmp_path, drawn):
    """Filled circles meet, crosses fail, open circles are the nominal gear (shown, not judged):
    the figure's legend says so (it said 'o meets' of the open circles too); two panels a row and
    every text at least 9 pt, so the report's page-wide image keeps them legible."""
    from matplotlib.text import Text
    from test_datasets_signoff import _table, _variant

    from gearmesh.plots.signoff import plot_signoff

    variants = [_variant("standard", {}), _variant("a", {"p": 0.7, "w_p": 1.3}), _variant("b", {"sf": 1.3})]
    plot_signoff(_table(variants, reference="standard", basis="population"), tmp_path / "population.png")
    plot_signoff(_table(variants, reference="standard", basis="nominal"), tmp_path / "nominal.png")
    for name, nominal_shown in (("population", True), ("nominal", False)):
        fig = drawn[name]
        (legend,) = fig.legends
        labels = [t.get_text() for t in legend.get_texts()]
        assert {"a", "b", "meets the criterion", "fails it", "the criterion's limit"} <= set(labels)
        assert ("nominal gear (shown, not judged)" in labels) == nominal_shown
        assert fig.get_figwidth() <= 10 and max(len(ax.get_lines()) > 0 for ax in fig.axes)
        sizes = [t.get_fontsize() for t in fig.findobj(Text) if t.get_text().strip()]
        assert min(sizes) >= 9, min(sizes)
        panel = fig.axes[0]
        markers = {line.get_marker() for line in panel.get_lines() if len(line.get_xdata())}
        assert "x" in markers or "o" in markers


def test_pressure_map_names_and_shows_its_lines_and_peak(data, drawn, tmp_path):
    """The SAP and tip lines in a colour of their own inside the frame, the peak's circle inside it
    and in the legend; the 3-D directions of the dynamics figure named."""
    from gearmesh.plots.rating import plot_pressure_map

    plot_pressure_map(data["ltca"], None, tmp_path / "pressure_map.png")
    fig = drawn["pressure_map"]
    (legend,) = fig.legends
    assert [t.get_text() for t in legend.get_texts()] == ["start of active profile (SAP)", "tip",
                                                          "the largest pressure (title)"]
    for ax in fig.axes[:data["ltca"].sizes["torque"]]:
        lo, hi = ax.get_ylim()
        lines = {line.get_label(): line for line in ax.get_lines()}
        for name in ("start of active profile (SAP)", "tip", "the largest pressure (title)"):
            y = np.asarray(lines[name].get_ydata(), dtype=float)
            assert np.all((y > lo) & (y < hi)), (name, y, lo, hi)
        assert lines["tip"].get_color() not in ("white", "w")
    _draw("dynamics", data, tmp_path)
    rms = drawn["rms"]
    assert "standard deviations" in rms.axes[0].get_title()
    titles = [ax.get_legend().get_title().get_text() for ax in rms.axes[1:3]]
    assert all("x: along the line of centres" in t and "z: axial" in t for t in titles)


def test_trajectory_labels_of_close_points_do_not_overlap(data, drawn, tmp_path):
    """Mesh-in points a few hundredths of a millimetre apart (the design_point variant's 400 and
    1300 N m) get labels moved apart, not printed on one another."""
    ds = data["impact_relief"].copy(deep=True)
    rho = ds["mesh_in_rho_pinion"].values
    ds["mesh_in_rho_pinion"].values[:] = rho[0] + np.arange(rho.size) * 0.05e-3  # apart, closer than a text line
    ds["mesh_in_face_position"].values[:] = ds["mesh_in_face_position"].values[0]
    impact.plot_mesh_in_trajectory(ds, tmp_path / "trajectory.png")
    fig = drawn["trajectory"]
    assert len(fig.axes[1].texts) == rho.size  # one label each: apart on the page, though close
    assert not layout_faults(fig), layout_faults(fig)

"""Stiffness-stage figures: K(φ) with its Fourier fit and the ISO mean, the comparison table,
and the slice-count convergence.

The figure jobs (``stiffness_figures``, ``stiffness_table_figures``, ``slice_convergence_figures``, each
``(inputs, outputs)`` as every ``*_figures`` of :mod:`gearmesh.plots`) take ``inputs``, a mapping of str to
xarray.Dataset (the rule's netCDF inputs by name), and ``outputs``, a mapping of str to the path of each PNG
by name; they write them and return None.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..choices import TOOTH_MODEL_NAMES
from .common import MM, number, plain_axis, save, subplots, title, UM

N_PER_UM = 1e-6  # N/m -> N/µm


#: The series terms of the mesh stiffness as a reader knows them: a term of one tooth pair (the
#: compliance of each gear's tooth, ``*_pinion``/``*_gear``, and the contact) or a term of the whole
#: mesh in series with all pairs (the gear bodies, and any further term the stiffness dataset
#: carries, named by its own name).
PAIR_TERMS = {"pinion": "pinion tooth (bending, shear, compression, foundation)",
              "gear": "gear tooth (bending, shear, compression, foundation)", "hertz": "contact (Hertz)"}
MESH_TERMS = {"body": "gear bodies"}


def _series_terms(ds: xr.Dataset) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """The compliance (m/N, per position) of each series term of K, grouped as :data:`PAIR_TERMS`
    and mesh terms (every other component of the dataset by name), and the stiffness of the tooth
    pairs in parallel without the mesh terms (N/m): 1/K = Σ compliances exactly."""
    groups: dict[str, np.ndarray] = {}
    pairs = np.zeros(ds.sizes["position"])
    for name, k in zip(ds["component"].values, ds["component_stiffness"].values):
        name = str(name)
        with np.errstate(divide="ignore"):
            c = np.where(np.isfinite(k) & (k > 0), 1.0 / k, 0.0)
        group = name.rpartition("_")[2] if name.rpartition("_")[2] in PAIR_TERMS else name
        label = PAIR_TERMS.get(group) or MESH_TERMS.get(group) or group.replace("_", " ")
        groups[label] = groups.get(label, 0.0) + c
        if group in PAIR_TERMS:
            pairs = pairs + c
    return groups, 1.0 / pairs


def plot_mesh_stiffness(ds: xr.Dataset, path: str | Path) -> Path:
    """K(φ) with its Fourier series, the ISO 6336-1 mean and the tooth pairs in parallel without
    the terms in series with the whole mesh (gear bodies, ...); what is in series, as stacked
    compliances that add up to 1/K; one tooth pair's k (teeth and contact) with the mean of all
    pairs in parallel; and the LSTE.

    Parameters
    ----------
    ds : xarray.Dataset
        stiffness.nc: over ``position`` (m of pinion roll) ``mesh_stiffness``, ``mesh_stiffness_fourier``
        (N/m), ``component_stiffness`` (N/m) over (component, position), ``pair_stiffness`` (N/m) over
        ``pair_position`` (m), ``iso6336_mesh_stiffness``, ``mean_stiffness`` (N/m), ``fluctuation`` (1);
        with a torque ``lste`` (m), ``lste_mean``, ``lste_peak_to_peak`` (m), ``pinion_torque`` (N m).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    n = 4 if "lste" in ds else 3
    fig, axes = subplots(n, 1, figsize=(11, 2.8 * n + 0.6), sharex=False, layout="constrained")
    ax = axes[0]
    x = ds["position"].values * MM
    terms, pairs = _series_terms(ds)
    contact = ("contact: tangent of the loaded contact at the LSTE torque" if "lste" in ds
               else "contact: constant line contact, no load")  # the dataset's contact_term
    terms = {contact if name == PAIR_TERMS["hertz"] else name: c for name, c in terms.items()}
    mesh_terms = [t for t in terms if t not in PAIR_TERMS.values() and t != contact]
    ax.plot(x, ds["mesh_stiffness"].values * N_PER_UM, lw=1.8,
            label="K(φ): " + ", in series with ".join(["the tooth pairs", *(f"the {t}" for t in mesh_terms)]))
    ax.plot(x, ds["mesh_stiffness_fourier"].values * N_PER_UM, "--", lw=1.2,
            label=f"Fourier series of K, order {ds.attrs.get('fourier_order', '')}")
    if mesh_terms:
        ax.plot(x, pairs * N_PER_UM, "-.", lw=1.2, color="tab:green",
                label="the tooth pairs in parallel (teeth and contact) alone")
    ax.axhline(float(ds["iso6336_mesh_stiffness"]) * N_PER_UM, color="k", ls=":", lw=1, label="ISO 6336-1 cγα·b")
    ax.margins(y=0.08)
    ax.set_ylabel("K (N/µm)")
    ax.set_xlabel("pinion roll distance over one base pitch (mm)")
    model = TOOTH_MODEL_NAMES.get(ds.attrs.get("tooth_model", ""), ds.attrs.get("tooth_model", ""))
    ax.set_title(title(ds, f"mesh stiffness, {model}, {ds.attrs.get('slices', '')} slices; "
                           f"εk = {100 * float(ds.fluctuation):.1f} %", own_line=True), fontsize=10)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(alpha=0.3)
    plain_axis(ax, ds["mesh_stiffness"].values * N_PER_UM, "N/µm", "K(φ)")
    ax = axes[1]
    ax.stackplot(x, *[c * 1e9 for c in terms.values()], labels=list(terms), alpha=0.85)  # m/N -> µm/kN
    ax.plot(x, 1e9 / ds["mesh_stiffness"].values, color="k", lw=1.0, label="1/K, their sum")
    ax.set_ylabel("compliance (µm/kN)")
    ax.set_xlabel("pinion roll distance over one base pitch (mm)")
    ax.set_title("what is in series: 1/K = the sum of the terms' compliances (mean of each in the legend)", fontsize=9)
    handles, labels = ax.get_legend_handles_labels()
    means = {name: float(np.mean(c)) * 1e9 for name, c in terms.items()}
    ax.legend(handles, [f"{lab}: {number(means[lab])} µm/kN" if lab in means else lab for lab in labels], fontsize=7,
              loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(alpha=0.3)
    ax = axes[2]
    ax.plot(ds["pair_position"].values * MM, ds["pair_stiffness"].values * N_PER_UM, lw=1.5, color="tab:green",
            label="one tooth pair (teeth and contact)")
    ax.set_xlabel("one tooth pair: mid-face contact position on the line of action (mm)")
    ax.set_ylabel("k pair (N/µm)")
    ax.set_title(f"one tooth pair; the pairs in mesh in parallel: mean {number(float(np.mean(pairs)) * N_PER_UM)} N/µm"
                 + (f"; with the {' and the '.join(mesh_terms)} in series, K = "
                    f"{number(float(ds.mean_stiffness) * N_PER_UM)} N/µm" if mesh_terms else ""), fontsize=9)
    ax.grid(alpha=0.3)
    if n == 4:
        ax = axes[3]
        ax.plot(x, ds["lste"].values * UM, lw=1.5, color="tab:red")
        ax.set_xlabel("pinion roll distance over one base pitch (mm)")
        ax.set_ylabel("LSTE F/K (µm)")
        ax.set_title(f"pinion torque {float(ds.pinion_torque):.1f} N m: mean {float(ds.lste_mean) * UM:.2f} µm, "
                     f"peak-to-peak {float(ds.lste_peak_to_peak) * UM:.2f} µm", fontsize=9)
        ax.grid(alpha=0.3)
        plain_axis(ax, ds["lste"].values * UM, "µm", "LSTE")
    return save(fig, path)


def plot_stiffness_table(ds: xr.Dataset, path: str | Path) -> Path:
    """Mean K (bars, min–max whiskers) of every case and method, with the ISO value as a line
    across each case's bars; the legend beside the axes, clear of the bars.

    Parameters
    ----------
    ds : xarray.Dataset
        stiffness_table.nc: over (case, model) ``mean_stiffness``, ``min_stiffness``,
        ``max_stiffness`` and ``iso6336_mesh_stiffness`` (N/m).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.

    References
    ----------
    .. [1] *A Comprehensive Study on Meshing Characteristics of Helical Gear Pairs Using an Improved
       Potential Energy Method for Time-Varying Meshing Stiffness* (root-circle cases of the cantilever against ISO 6336-1).
    """
    cases, methods = ds["case"].values, ds["model"].values
    fig, ax = subplots(figsize=(min(16, 4 + 0.9 * len(cases) * max(1, len(methods) // 2)), 4.5), layout="constrained")
    width = 0.8 / len(methods)
    idx = np.arange(len(cases))
    for k, m in enumerate(methods):
        sel = ds.sel(model=m)
        mean = sel["mean_stiffness"].values * N_PER_UM
        err = np.stack([mean - sel["min_stiffness"].values * N_PER_UM, sel["max_stiffness"].values * N_PER_UM - mean])
        ax.bar(idx + (k - (len(methods) - 1) / 2) * width, mean, width, yerr=err, capsize=3, label=str(m))
    ax.hlines(ds["iso6336_mesh_stiffness"].isel(model=0).values * N_PER_UM, idx - 0.45, idx + 0.45, color="k", lw=1.8,
              zorder=5, label="ISO 6336-1 cγα·b")
    ax.set_xticks(idx, [str(c) for c in cases], rotation=20, ha="right", fontsize=8)
    ax.set_ylabel("mesh stiffness (N/µm): mean, whiskers min–max")
    ax.set_title("mesh stiffness by case and cantilever method (every model with a constant line contact, no load)",
                 fontsize=10)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), title="method", title_fontsize=8)
    ax.grid(alpha=0.3, axis="y")
    return save(fig, path)


#: The slice rules as a reader knows them (:mod:`gearmesh.stiffness`: 'centre' takes a whole slice
#: when its centre is on the active flank, 'clip' clips the end slices to it).
SLICE_RULES = {"centre": "whole slices (by their centre)", "clip": "end slices clipped"}


def plot_slice_convergence(ds: xr.Dataset, path: str | Path) -> Path:
    """|relative difference of the mean K| against the slice count, both slice rules.

    Parameters
    ----------
    ds : xarray.Dataset
        slice_convergence.nc: ``mean_relative_difference`` (1, against the finest clipped count) over
        (pair, rule, slices).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.

    References
    ----------
    .. [1] *A Comprehensive Study on Meshing Characteristics of Helical Gear Pairs Using an Improved
       Potential Energy Method for Time-Varying Meshing Stiffness* (slice-count convergence).
    """
    fig, ax = subplots(figsize=(6.5, 4))
    n = ds["slices"].values
    for pair in ds["pair"].values:
        for rule in ds["rule"].values:
            err = np.abs(ds["mean_relative_difference"].sel(pair=pair, rule=rule).values)
            keep = err > 0
            ax.loglog(n[keep], err[keep], "o-", label=f"{pair}, {SLICE_RULES.get(str(rule), str(rule))}")
    ax.set_xlabel("slices over the face width")
    ax.set_ylabel("|mean K / finest clipped − 1|")
    ax.set_title("slice-count convergence of the mean mesh stiffness")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return save(fig, path)


def stiffness_figures(inputs, outputs) -> None:
    """The figure of the ``stiffness`` rule.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["stiffness"]``, writes
        ``outputs["stiffness"]``.
    """
    plot_mesh_stiffness(inputs["stiffness"], outputs["stiffness"])


def stiffness_table_figures(inputs, outputs) -> None:
    """The figure of the ``stiffness_table`` rule.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["stiffness_table"]``, writes
        ``outputs["stiffness_table"]``.
    """
    plot_stiffness_table(inputs["stiffness_table"], outputs["stiffness_table"])


def slice_convergence_figures(inputs, outputs) -> None:
    """The figure of the ``slice_convergence`` rule.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["slice_convergence"]``, writes
        ``outputs["slice_convergence"]``.
    """
    plot_slice_convergence(inputs["slice_convergence"], outputs["slice_convergence"])

"""TCA/LTCA figures: TE and LTE against rotation for every torque, the loaded contact pattern
on the pinion flank, and the unloaded separations of the TCA.

The figure jobs (``tca_figures``, ``ltca_figures``, each ``(inputs, outputs)`` as every ``*_figures`` of
:mod:`gearmesh.plots`) take ``inputs``, a mapping of str to xarray.Dataset (the rule's netCDF inputs by
name), and ``outputs``, a mapping of str to the path of each PNG by name; they write them and return None.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.patches import Rectangle

from .common import coinciding, MM, number, palette, save as _save, subplots, title as _title, UM

__all__ = ["plot_te_lte", "plot_contact_pattern", "plot_tca", "tca_figures", "ltca_figures"]


def _angle_mrad(ds: xr.Dataset) -> np.ndarray:
    return ds["pinion_angle"].values * 1e3


#: The contact laws' names as a reader knows them (the attribute holds the code's name).
CONTACT_LAWS = {"palmgren": "Palmgren line", "linear": "linear Hertz"}


def plot_te_lte(ds: xr.Dataset, path: str | Path) -> Path:
    """Unloaded TE and the LTE of every torque over one mesh cycle (µm along the transverse
    line of action, + gear lags), with the start of engagement φ1A, LTE(φ1A) (dots), the teeth's
    part of it (open circles, where the gear bodies add a deflection in series) and the entering
    pair's separation TE(φ1A) (square): the mesh-in impact paper's criterion, the teeth's LTE at
    φ1A above that separation means the entering pair touches before A (the bodies turn the
    entering tooth with the loaded ones: :func:`gearmesh.datasets.ltca.teeth_approach_at_engagement`).

    Parameters
    ----------
    ds : xarray.Dataset
        ltca.nc: ``pinion_angle`` (rad) over position, ``te`` (m) over position and ``lte`` (m) over
        (torque, position) along the transverse line of action, ``pinion_angle_engagement`` (rad),
        ``te_next_pair_at_engagement`` (m), over torque ``lte_at_engagement``,
        ``lte_teeth_at_engagement``, ``lte_peak_to_peak`` (m) and ``touches_before_engagement``;
        attribute ``contact_law``.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    fig, ax = subplots(figsize=(7.5, 4.5))
    x = _angle_mrad(ds)
    xa = float(ds["pinion_angle_engagement"]) * 1e3
    separation = float(ds["te_next_pair_at_engagement"]) * UM
    ax.plot(x, ds["te"].values * UM, color="k", lw=1.6, label="TE (unloaded)")
    colors = palette(ds.sizes["torque"])
    at_a = ds["lte_at_engagement"].values * UM
    teeth = ds["lte_teeth_at_engagement"].values * UM
    early = ds["touches_before_engagement"].values.astype(bool)
    for k, color in enumerate(colors):
        sel = ds.isel(torque=k)
        ax.plot(x, sel["lte"].values * UM, color=color, lw=1.6,
                label=f"LTE, T1 = {number(float(sel.torque))} N m, p-p {number(float(sel.lte_peak_to_peak) * UM)} µm: "
                      f"entering pair touches {'before' if early[k] else 'after'} A")
    bodies = not np.allclose(teeth, at_a, rtol=0, atol=1e-3)
    for k, color in enumerate(colors):
        ax.plot([xa], [at_a[k]], "o", color=color, ms=5, label="LTE at φ1A" if k == 0 else None)
        if bodies:
            ax.plot([xa], [teeth[k]], "o", mfc="white", mec=color, mew=1.3, ms=6,
                    label="the teeth's part of LTE at φ1A: what closes the entering pair's gap\n"
                          "(the gear bodies' deflection turns the entering tooth too)" if k == 0 else None)
    ax.axvline(xa, color="0.4", ls=":", lw=1.0, label="start of engagement φ1A")
    ax.plot([xa], [separation], "s", color="k", ms=5,
            label=f"entering pair's unloaded separation TE(φ1A) = {number(separation)} µm")
    ax.set_xlabel("pinion rotation φ1 over one mesh cycle (mrad)")
    ax.set_ylabel("transmission error along the line of action (µm)")
    law = str(ds.attrs.get("contact_law", ""))
    ax.set_title(_title(ds, f"TE and LTE ({CONTACT_LAWS.get(law, law)} contact)"))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1))
    return _save(fig, path)


def _pattern(ds: xr.Dataset, k: int, bins: int = 80, name: str = "line_load", scale: float = 1e-3):
    """The largest value of ``name`` (default the line load, N/mm) times ``scale`` over the mesh cycle
    at each (pinion roll length, z) cell."""
    sel = ds.isel(torque=k)
    rho = ds["rho_pinion"].values
    # tip-edge points of the recess touch the pinion at its tip: plot them there
    load = sel[name].values * scale
    rho_sap, rho_eap = (float(v) for v in (ds["rho_sap"][0], ds["rho_eap"][0]))
    lo = min(rho_sap, np.nanmin(rho)) if np.isfinite(rho).any() else rho_sap
    edges = np.linspace(lo, rho_eap, bins + 1)
    ok = np.isfinite(rho) & (load > 0)
    cell = np.clip(np.searchsorted(edges, rho[ok], side="right") - 1, 0, bins - 1)
    col = np.broadcast_to(np.arange(ds.sizes["point"]), load.shape)[ok]
    grid = np.full((bins, ds.sizes["point"]), np.nan)
    np.fmax.at(grid, (cell, col), load[ok])
    return edges, grid


def plot_contact_pattern(ds: xr.Dataset, path: str | Path) -> Path:
    """The loaded contact pattern on the pinion flank for every torque: the largest line load
    (N/mm) over the mesh cycle against axial position z and pinion roll length ρ1, with the
    SAP and tip (EAP) marked; each panel on its own colour scale (its colour bar below it, so a
    light load is not drawn dark on the scale of the heaviest), cells the contact never
    reaches grey, shown at the low end of each colour bar (where there are any).

    Parameters
    ----------
    ds : xarray.Dataset
        ltca.nc: ``line_load`` (N/m) over (torque, position, line, point), ``rho_pinion`` (m) over
        (position, line, point), ``point``, ``point_width``, ``rho_sap``, ``rho_eap`` (m),
        ``max_line_load_cycle`` (N/m) over torque.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    n = ds.sizes["torque"]
    fig, axes = subplots(1, n, figsize=(4.2 * n, 5.4), squeeze=False, sharey=True, layout="constrained")
    fig.get_layout_engine().set(wspace=0.08)  # the panels' end tick labels apart
    z = ds["point"].values * MM
    dz = float(ds["point_width"]) * MM
    z_edges = np.append(z - 0.5 * dz, z[-1] + 0.5 * dz)
    cmap = colormaps["inferno"].with_extremes(under="0.8", bad="0.8")
    sap, eap = float(ds["rho_sap"][0]) * MM, float(ds["rho_eap"][0]) * MM
    for k, ax in enumerate(axes[0]):
        edges, grid = _pattern(ds, k)
        top = float(np.nanmax(grid)) if np.isfinite(grid).any() else 1.0
        mesh = ax.pcolormesh(z_edges, edges * MM, np.where(np.isfinite(grid), grid, -1.0), cmap=cmap, vmin=0,
                             vmax=top, shading="flat")
        for rho, ls in ((sap, "--"), (eap, "-")):
            ax.axhline(rho, color="tab:cyan", ls=ls, lw=1.5, zorder=3)
        sel = ds.isel(torque=k)
        ax.set_title(f"T1 = {number(float(sel.torque))} N m\nmax {number(float(sel.max_line_load_cycle) * 1e-3)} N/mm",
                     fontsize=9)
        ax.set_xlabel("z across the face (mm)")
        apart = bool(np.isnan(grid).any())  # cells the contact never reaches: on the bar only when there are any
        bar = fig.colorbar(mesh, ax=ax, location="bottom", extend="min" if apart else "neither", extendfrac=0.08,
                           aspect=30)
        bar.set_label("largest line load over the mesh cycle (N/mm)" + (";\ngrey (left end): no contact" if apart else ""),
                      fontsize=8)
    # the pattern spans SAP to tip: a margin beyond both, so their lines are not hidden by the frame
    axes[0][0].set_ylim(sap - 0.03 * (eap - sap), eap + 0.03 * (eap - sap))
    axes[0][0].set_ylabel("pinion roll length ρ1 (mm); dashed SAP, solid tip")
    fig.suptitle(_title(ds, "loaded contact pattern on the pinion flank"))
    return _save(fig, path)


def plot_tca(ds: xr.Dataset, path: str | Path) -> Path:
    """Unloaded TCA: the TE of the mesh and of each tooth pair over one mesh cycle, and the
    path of each pair's first-contact point on the pinion flank (z, ρ1).

    Parameters
    ----------
    ds : xarray.Dataset
        tca.nc: ``pinion_angle`` (rad), ``te`` (m) over position, over (position, line) ``te_pair``,
        ``contact_z``, ``contact_rho_pinion`` (m), ``separation`` (m) over (position, line, point),
        ``pinion_angle_engagement`` (rad), ``face_width``, ``rho_sap``, ``rho_eap``,
        ``te_peak_to_peak`` (m).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    fig, (ax1, ax2) = subplots(1, 2, figsize=(11, 4.6), layout="constrained")
    x = _angle_mrad(ds)
    ax1.plot(x, ds["te"].values * UM, color="0.75", lw=4.0, label="TE of the mesh", zorder=1)
    # a tooth pair whose whole contact line touches at once (perfect flanks) has no single
    # first-contact point: those positions are left out of the path instead of an arbitrary point
    sep = ds["separation"].values
    finite = np.isfinite(sep)
    spread = np.where(finite, sep, -np.inf).max(axis=2) - np.where(finite, sep, np.inf).min(axis=2)
    whole_line = (finite.sum(axis=2) >= 2) & (spread < 1e-9)  # (position, line)
    styles = ("--", "-.", ":", (0, (5, 1, 1, 1)))
    te_pairs = ds["te_pair"].transpose("line", ...).values * UM
    labelled = {group[0]: group for group in coinciding(te_pairs)}
    pair_colors = colormaps["tab10"](np.arange(ds.sizes["line"]) % 10)  # one colour per pair, both panels
    for j in range(ds.sizes["line"]):
        group = labelled.get(j)
        if group is not None:  # pairs whose curves coincide: one line, every pair named
            names = ", ".join(str(int(ds.line[i])) for i in group)
            note = " (0 over the cycle)" if np.nanmax(np.abs(te_pairs[j])) == 0 else ""
            ax1.plot(x, te_pairs[j], lw=1.3, ls=styles[j % len(styles)], color=pair_colors[j],
                     label=f"pair{'s' if len(group) > 1 else ''} j = {names}{note}", zorder=2)
        z = np.where(whole_line[:, j], np.nan, ds["contact_z"].isel(line=j).values) * MM
        ax2.plot(z, ds["contact_rho_pinion"].isel(line=j).values * MM, ".-", ms=3, lw=0.8, color=pair_colors[j],
                 label=f"pair j = {int(ds.line[j])}")
    ax1.axvline(float(ds["pinion_angle_engagement"]) * 1e3, color="0.4", ls=":", lw=1.0, label="φ1A")
    ax1.set_yscale("symlog", linthresh=1.0)  # the µm TE and the 100 µm separations of the other pairs
    ax1.set_ylim(bottom=-0.05)
    ax1.set_xlabel("pinion rotation φ1 over one mesh cycle (mrad)")
    ax1.set_ylabel("unloaded separation / TE (µm),\nlinear to 1 µm, logarithmic above")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=7)
    half = 0.5 * float(ds["face_width"]) * MM
    ax2.add_patch(Rectangle((-half, float(ds.rho_sap[0]) * MM), 2 * half,
                                float(ds.rho_eap[0] - ds.rho_sap[0]) * MM, fill=False, ec="0.4"))
    ax2.set_xlabel("z across the face (mm)")
    ax2.set_ylabel("pinion roll length ρ1 (mm)")
    ax2.legend(fontsize=7, loc="best")
    ax2.set_title("first-contact points of each pair" + ("\n(where a whole line touches at once, as on perfect "
                                                         "flanks,\nthere is no single point: not drawn)"
                                                         if whole_line.any() else ""), fontsize=8)
    fig.suptitle(_title(ds, f"unloaded TCA, TE p-p {number(float(ds.te_peak_to_peak) * UM)} µm"))
    return _save(fig, path)


def tca_figures(inputs, outputs) -> None:
    """The figure of the ``tca`` rule from its ``tca`` dataset.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["tca"]``, writes
        ``outputs["tca"]``.
    """
    plot_tca(inputs["tca"], outputs["tca"])


def ltca_figures(inputs, outputs) -> None:
    """The figures of the ``ltca`` rule from its ``ltca`` dataset.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["ltca"]``, writes
        ``outputs["te_lte"]`` and ``outputs["contact_pattern"]``.
    """
    plot_te_lte(inputs["ltca"], outputs["te_lte"])
    plot_contact_pattern(inputs["ltca"], outputs["contact_pattern"])

"""Load-capacity figures: the contact-pressure map over the pinion flank and the root stress along
the face, drawn from the variant's ltca.nc (its load-capacity variables) and rating.nc.

The figure job (``rating_figures(inputs, outputs)``, as every ``*_figures`` of :mod:`gearmesh.plots`)
takes ``inputs``, a mapping of str to xarray.Dataset (the rule's netCDF inputs by name), and ``outputs``, a
mapping of str to the path of each PNG by name; it writes them and returns None.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib import colormaps

from .common import MM, number, palette, save as _save, subplots, title as _title
from .ltca import _pattern

__all__ = ["plot_pressure_map", "plot_root_stress_face", "rating_figures"]

MPA = 1e-6


def plot_pressure_map(ltca: xr.Dataset, rating: xr.Dataset | None, path: str | Path) -> Path:
    """The largest Hertzian contact pressure (MPa) over the mesh cycle at each (z, pinion roll length)
    cell, one panel per torque, its colour scale ending at the flank's peak so that the flank stays
    legible: cells above it (tip-edge contacts, drawn where they touch the pinion: the gear's tip
    above the SAP, the pinion's own tip) are white. The overall peak is circled and said to sit on a
    flank or an edge; S_H of the weaker gear in the title when the rating is given.

    Parameters
    ----------
    ltca : xarray.Dataset
        ltca.nc: ``contact_pressure`` (Pa) over (torque, position, line, point), ``rho_pinion`` (m)
        and ``region`` (1 on the flank) over (position, line, point), ``point``, ``point_width``, ``rho_sap``,
        ``rho_eap``, ``tip_edge_radius`` (m), over torque ``peak_contact_pressure`` (Pa) and
        ``peak_contact_pressure_on_edge``.
    rating : xarray.Dataset or None
        rating.nc: ``S_H`` (1) over (torque, gear); None leaves S_H out of the titles.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    n = ltca.sizes["torque"]
    fig, axes = subplots(1, n, figsize=(4.2 * n, 5.6), squeeze=False, sharey=True, layout="constrained")
    z = ltca["point"].values * MM
    dz = float(ltca["point_width"]) * MM
    z_edges = np.append(z - 0.5 * dz, z[-1] + 0.5 * dz)
    cmap = colormaps["magma"].with_extremes(under="0.8", bad="0.8", over="white")
    flank = ltca["region"].values == 1
    for k, ax in enumerate(axes[0]):
        edges, grid = _pattern(ltca, k, name="contact_pressure", scale=MPA)
        p_flank = np.where(flank, ltca["contact_pressure"].isel(torque=k).values, 0.0).max() * MPA
        top = p_flank if p_flank > 0 else (float(np.nanmax(grid)) if np.isfinite(grid).any() else 1.0)
        above = bool(np.nanmax(grid) > top * (1 + 1e-9)) if np.isfinite(grid).any() else False
        mesh = ax.pcolormesh(z_edges, edges * MM, np.where(np.isfinite(grid), grid, -1.0), cmap=cmap, vmin=0,
                             vmax=top, shading="flat")
        sap, eap = (float(ltca[name][0]) * MM for name in ("rho_sap", "rho_eap"))
        # the SAP and tip in a colour no cell has (the map runs black to pale yellow, white and grey),
        # the frame a little beyond them and beyond the cells so neither the lines nor the peak's
        # circle lie on it
        ax.axhline(sap, color="tab:blue", ls="--", lw=1.5, zorder=3, label="start of active profile (SAP)")
        ax.axhline(eap, color="tab:blue", ls="-", lw=1.5, zorder=3, label="tip")
        low, high = min(sap, edges[0] * MM), max(eap, edges[-1] * MM)
        ax.set_facecolor("#e6edf5")  # off the flank (the margin): a tint no cell of the map has
        ax.set_ylim(low - 0.04 * (high - low), high + 0.04 * (high - low))
        sel = ltca.isel(torque=k)
        p = sel["contact_pressure"].values
        i = np.unravel_index(int(np.argmax(p)), p.shape)
        ax.plot(z[i[2]], float(ltca["rho_pinion"].values[i]) * MM, "o", mfc="none", mec="tab:green", ms=11, mew=2,
                zorder=4, clip_on=False, label="the largest pressure (title)")
        where = "tip edge" if int(sel["peak_contact_pressure_on_edge"]) else "flank"
        head = (f"T1 = {number(float(sel.torque))} N m\npeak {number(float(sel.peak_contact_pressure) * MPA)} MPa on a "
                f"{where}, flank {number(p_flank)} MPa")
        if rating is not None:
            head += f", S_H {number(float(rating['S_H'].isel(torque=k).min()))}"
        ax.set_title(head, fontsize=9)
        ax.set_xlabel("z across the face (mm)")
        apart = bool(np.isnan(grid).any())
        bar = fig.colorbar(mesh, ax=ax, location="bottom", extendfrac=0.08, aspect=30,
                           extend={(True, True): "both", (True, False): "min", (False, True): "max"}.get((apart, above),
                                                                                                         "neither"))
        keys = [k for k, show in (("grey: no contact", apart), ("white: above the flank's peak", above)) if show]
        bar.set_label("largest contact pressure over the cycle (MPa)" + ("\n" + "; ".join(keys) if keys else ""),
                      fontsize=8)
    axes[0][0].set_ylabel("pinion roll length ρ1 (mm)")
    fig.legend(handles=axes[0][0].get_legend_handles_labels()[0], loc="outside lower center", ncol=3, fontsize=9)
    r_e = float(ltca["tip_edge_radius"]) * MM
    fig.suptitle(_title(ltca, f"contact pressure on the pinion flank (Hertz; tip edges rounded r = {number(r_e)} mm)"))
    return _save(fig, path)


def plot_root_stress_face(ltca: xr.Dataset, rating: xr.Dataset | None, path: str | Path) -> Path:
    """The largest tooth-root stress (MPa, ISO 6336-3 local form per slice) over the mesh cycle along
    the face, pinion and gear, one line per torque; ISO method B's σ_F of the rating dotted beside.

    Parameters
    ----------
    ltca : xarray.Dataset
        ltca.nc: ``root_stress`` (Pa) over (torque, gear, position, line, point), ``point`` (m).
    rating : xarray.Dataset or None
        rating.nc: ``sigma_F`` (Pa) over (torque, gear); None draws no σ_F lines.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    fig, axes = subplots(1, 2, figsize=(10, 4.4), sharey=True, layout="constrained")
    z = ltca["point"].values * MM
    colors = palette(ltca.sizes["torque"])
    for g, ax in enumerate(axes):
        for k, color in enumerate(colors):
            sel = ltca.isel(torque=k)
            s = sel["root_stress"].isel(gear=g).max(("position", "line")).values * MPA
            ax.plot(z, s, color=color, lw=1.6, label=f"T1 = {number(float(sel.torque))} N m, peak {number(s.max())} MPa")
            if rating is not None:
                ax.axhline(float(rating["sigma_F"].isel(torque=k, gear=g)) * MPA, color=color, ls=":", lw=1.0)
        ax.set_title(str(ltca["gear"].values[g]), fontsize=10)
        ax.set_xlabel("z across the face (mm)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("largest root stress over the mesh cycle (MPa)")
    fig.suptitle(_title(ltca, "tooth-root stress along the face (lines: LTCA slices, ISO 6336-3 local form; "
                              "dotted: ISO method B sigma_F)"), fontsize=9)
    return _save(fig, path)


def rating_figures(inputs, outputs) -> None:
    """The figures of the ``rating`` rule from its ``ltca`` input and its ``rating`` dataset.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["ltca"]`` and
        ``inputs["rating"]`` (optional), writes ``outputs["pressure_map"]`` and
        ``outputs["root_stress_face"]``.
    """
    plot_pressure_map(inputs["ltca"], inputs.get("rating"), outputs["pressure_map"])
    plot_root_stress_face(inputs["ltca"], inputs.get("rating"), outputs["root_stress_face"])

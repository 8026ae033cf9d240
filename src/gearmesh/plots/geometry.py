"""Geometry-stage figures: tooth profile, contact lines, L(phi), the helix-angle V-curve.

The figure jobs (``geometry_figures``, ``contact_lines_figures``, ``helix_sweep_figures``, each
``(inputs, outputs)`` as every ``*_figures`` of :mod:`gearmesh.plots`) take ``inputs``, a mapping of str to
xarray.Dataset (the rule's netCDF inputs by name), and ``outputs``, a mapping of str to the path of each PNG
by name; they write them and return None.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.patches import Rectangle

from .common import coinciding, legend_below, MM, number, palette, plain_axis, save as _save, subplots, title as _title


def plot_tooth_profile(ds: xr.Dataset, path: str | Path) -> Path:
    """One tooth of each gear in its transverse section: the hob-generated fillet (trochoid)
    and the involute, with the root, base, form and tip circles.

    Parameters
    ----------
    ds : xarray.Dataset
        geometry.nc: per gear ``profile_x``, ``profile_y`` (m, gear centre at 0) and
        ``profile_segment`` (0 fillet, 1 involute) of one flank, ``root_radius``, ``base_radius``,
        ``form_radius``, ``tip_radius`` (m), ``teeth``, ``profile_shift`` (1), ``undercut``.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    fig, axes = subplots(1, 2, figsize=(10, 5))
    for g, ax in enumerate(axes):
        sel = ds.isel(gear=g)
        x, y = sel["profile_x"].values * MM, sel["profile_y"].values * MM
        seg = sel["profile_segment"].values
        for side in (1, -1):
            ax.plot(side * x[seg == 0], y[seg == 0], color="tab:red", lw=1.8,
                    label="fillet (hob trochoid)" if side == 1 else None)
            ax.plot(side * x[seg == 1], y[seg == 1], color="tab:blue", lw=1.8, label="involute" if side == 1 else None)
        half = 1.3 * np.nanmax(np.abs(x))
        bottom = float(sel["root_radius"]) * MM - 0.3 * half
        angles = np.linspace(-half / np.nanmax(y), half / np.nanmax(y), 200)
        below = []
        for name, ls in (("root_radius", ":"), ("base_radius", "--"), ("form_radius", "-."), ("tip_radius", "-")):
            r = float(sel[name]) * MM
            if r * np.cos(angles[0]) < bottom:  # below the view (a base circle inside the root circle)
                below.append(f"{name.replace('_', ' ')} {r:.3f} mm")
                continue
            ax.plot(r * np.sin(angles), r * np.cos(angles), color="0.5", ls=ls, lw=0.8,
                    label=f"{name.replace('_', ' ')} {r:.3f} mm")
        ax.set_aspect("equal")
        ax.set_xlim(-half, half)
        ax.set_ylim(bottom, float(sel["tip_radius"]) * MM + 0.2 * half)
        ax.set_title(f"{str(sel.gear.values)}: z = {int(sel.teeth)}, x = {number(float(sel.profile_shift))}"
                     + (", undercut" if int(sel.undercut) else "")
                     + "".join(f"\n{b}: below the root circle, out of view" for b in below), fontsize=10)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm), gear centre at 0")
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)  # below the x label
    fig.suptitle(_title(ds, "transverse tooth profile"))
    return _save(fig, path)


def plot_contact_length(ds: xr.Dataset, path: str | Path) -> Path:
    """Total contact-line length L(φ) over a mesh cycle with its closed-form mean/min/max.

    Parameters
    ----------
    ds : xarray.Dataset
        contact_lines.nc: ``total_length`` (m) over ``position`` (m of pinion roll r_b1·φ1),
        ``mean_length_closed_form``, ``min_length_closed_form``, ``max_length_closed_form`` (m),
        ``eps_alpha``, ``eps_beta``, ``length_fluctuation`` (1).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.

    References
    ----------
    .. [1] *Numerical Simulation of Meshing Line Position and Length for Helical Gears* (contact lines
       against rotation, total and mean contact length).
    """
    fig, ax = subplots(figsize=(7, 4))
    x = ds["position"].values * MM
    ax.plot(x, ds["total_length"].values * MM, lw=1.6, label="L(φ), sum of clipped lines")
    styles = {"mean": "-", "min": "--", "max": ":"}
    values = {key: float(ds[f"{key}_length_closed_form"]) * MM for key in styles}
    keys = list(styles)
    plain_axis(ax, ds["total_length"].values * MM, "mm", "L(φ)")
    lo, hi = ax.get_ylim()
    span = max(hi, *values.values()) - min(lo, *values.values())
    for group in coinciding([[values[key]] for key in keys], span):  # one line where they meet on the page
        names = [keys[k] for k in group]
        ax.axhline(values[names[0]], color="k", ls=styles[names[0]], lw=0.9, label=f"{' = '.join(names)}, closed form")
    ax.set_xlabel("pinion roll distance r_b1·φ1 over one base pitch (mm)")
    ax.set_ylabel("total contact-line length (mm)")
    ax.set_title(_title(ds, f"εα = {float(ds.eps_alpha):.3f}, εβ = {float(ds.eps_beta):.3f}, "
                            f"ε_l = {float(ds.length_fluctuation):.3f}"))
    ax.legend(fontsize=8, loc="best")
    ax.grid(alpha=0.3)
    return _save(fig, path)


def plot_contact_lines(ds: xr.Dataset, path: str | Path, snapshots: int = 4) -> Path:
    """Contact lines in the plane of action (s along the line of action, z across the face).

    Parameters
    ----------
    ds : xarray.Dataset
        contact_lines.nc: over (position, line) ``s_start``, ``s_end``, ``z_start``, ``z_end`` (m;
        NaN where a line is out of contact), ``total_length`` (m), ``path_of_contact``,
        ``face_width`` (m).
    path : str or Path
        The PNG to write.
    snapshots : int
        Mesh positions drawn, evenly over the cycle (default 4).

    Returns
    -------
    Path
        ``path``.

    References
    ----------
    .. [1] *Numerical Simulation of Meshing Line Position and Length for Helical Gears* (contact lines
       against rotation, total and mean contact length).
    """
    fig, ax = subplots(figsize=(7, 4.5))
    g = float(ds.path_of_contact) * MM
    half_b = 0.5 * float(ds.face_width) * MM
    ax.add_patch(Rectangle((0, -half_b), g, 2 * half_b, fill=False, ec="0.4", lw=1.2))
    n = ds.sizes["position"]
    colors = palette(snapshots, low=0, high=0.9)
    for color, k in zip(colors, np.linspace(0, n, snapshots, endpoint=False).astype(int)):
        sel = ds.isel(position=k)
        label = f"roll {float(sel.position) * MM:.2f} mm, L = {float(sel.total_length) * MM:.2f} mm"
        for j in range(ds.sizes["line"]):
            if np.isnan(sel.s_start[j]):
                continue
            ax.plot([sel.s_start[j] * MM, sel.s_end[j] * MM], [sel.z_start[j] * MM, sel.z_end[j] * MM],
                    color=color, lw=2, label=label)
            label = None
    ax.set_xlabel("s along the line of action from the\nstart of active profile (mm)")
    ax.set_ylabel("z: axial position (mm)")
    ax.set_title(_title(ds, "contact lines in the plane of action"))
    ax.set_aspect("equal")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1))
    return _save(fig, path)


def plot_helix_sweep(ds: xr.Dataset, path: str | Path) -> Path:
    """ε_l and mean contact length against helix angle for each pair (the V-curve, the low-fluctuation paper §5):
    the closed form solid, the sampled lines dashed where they differ from it visibly (where they
    do not, the legend gives their largest difference instead of a hidden curve).

    Parameters
    ----------
    ds : xarray.Dataset
        helix_sweep.nc: over (pair, helix angle) ``helix_angle_deg`` (deg), ``length_fluctuation``
        and ``length_fluctuation_sampled`` (1), ``mean_length``, ``min_length``, ``max_length`` (m),
        ``eps_beta`` (1; its integers dotted).
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.

    References
    ----------
    .. [1] [untitled] *Low mesh-stiffness fluctuation design of helical gears*, section 5.
    """
    fig, (ax1, ax2) = subplots(2, 1, figsize=(7, 6.8), sharex=True)
    for name in ds["pair"].values:
        sel = ds.sel(pair=name)
        beta = sel["helix_angle_deg"].values
        closed, sampled = sel["length_fluctuation"].values, sel["length_fluctuation_sampled"].values
        both = np.isfinite(closed) & np.isfinite(sampled)
        apart = float(np.max(np.abs(closed[both] - sampled[both]))) if both.any() else 0.0
        same = len(coinciding([closed, sampled])) == 1
        # ε_l is a ratio: its difference needs no unit; one at round-off is said in words
        agree = "identical to round-off" if apart < 1e-9 else f"within {number(apart)} in ε_l"
        label = f"{name} (sampled lines {agree})" if same else f"{name} (dashed: sampled lines)"
        line, = ax1.plot(beta, closed, lw=1.5, label=label)
        if not same:
            ax1.plot(beta, sampled, color=line.get_color(), lw=0.8, ls="--")
        ax2.plot(beta, sel["mean_length"].values * MM, color=line.get_color(), lw=1.5)
        ax2.fill_between(beta, sel["min_length"].values * MM, sel["max_length"].values * MM,
                         color=line.get_color(), alpha=0.15)
        eb = sel["eps_beta"].values
        for n in range(1, int(np.nanmax(eb)) + 1 if np.isfinite(eb).any() else 1):
            k = np.nanargmin(np.abs(eb - n))
            if abs(eb[k] - n) < 0.05:
                ax1.axvline(beta[k], color=line.get_color(), ls=":", lw=0.8)
    ax1.set_ylabel("ε_l = (Lmax − Lmin)/b")
    ax1.set_title("contact-line fluctuation against helix angle\n(closed form; dotted: integer overlap ratio εβ)",
                  fontsize=10)
    legend_below(ax1, ncol=1)
    ax1.tick_params(labelbottom=True)
    ax1.grid(alpha=0.3)
    ax2.set_xlabel("helix angle β (deg)")
    ax2.set_ylabel("contact length (mm): mean, band min–max")
    ax2.grid(alpha=0.3)
    fig.set_layout_engine("constrained")
    return _save(fig, path)


def geometry_figures(inputs, outputs) -> None:
    """The figure of the ``geometry`` rule from its ``geometry`` dataset: the tooth profile.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["geometry"]``, writes
        ``outputs["tooth_profile"]``.
    """
    plot_tooth_profile(inputs["geometry"], outputs["tooth_profile"])


def contact_lines_figures(inputs, outputs) -> None:
    """The figures of the ``contact_lines`` rule from its ``contact_lines`` dataset: L(phi) and the lines.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["contact_lines"]``,
        writes ``outputs["contact_length"]`` and ``outputs["contact_lines"]``.
    """
    plot_contact_length(inputs["contact_lines"], outputs["contact_length"])
    plot_contact_lines(inputs["contact_lines"], outputs["contact_lines"])


def helix_sweep_figures(inputs, outputs) -> None:
    """The V-curve figure of the ``helix_sweep`` rule.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["helix_sweep"]``, writes
        ``outputs["helix_sweep"]``.
    """
    plot_helix_sweep(inputs["helix_sweep"], outputs["helix_sweep"])

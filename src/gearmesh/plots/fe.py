"""FE-compliance figure: the finite-element tooth compliance of both gears along the active
profile, beside the three potential-energy cantilevers (from ``fe_compliance.nc``).

The figure job (``fe_compliance_figures(inputs, outputs)``, as every ``*_figures`` of :mod:`gearmesh.plots`)
takes ``inputs``, a mapping of str to xarray.Dataset (the rule's netCDF inputs by name), and ``outputs``, a
mapping of str to the path of each PNG by name; it writes them and returns None.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from .common import coinciding, MM, save, subplots, title

#: m²/N -> µm per N/mm (deflection in µm under 1 N per mm of face width)
UM_MM_PER_N = 1e9

STYLE = {"traditional": ("tab:orange", ":"), "improved": ("tab:green", "-."), "transition": ("tab:blue", "--")}



def _pem_lines(ax, x, ds, name: str, gear: int, label: str) -> None:
    """One line per potential-energy model of variable ``name`` (m²/N → µm per N/mm) of ``gear``;
    models whose curves coincide (the same root) drawn once and named together."""
    models = [str(m) for m in ds["model"].values]
    curves = [ds[name].sel(model=m).values[gear] * UM_MM_PER_N for m in models]
    lo, hi = ax.get_ylim()  # the FE lines' range, drawn before
    span = max(hi, np.nanmax(curves)) - min(lo, np.nanmin(curves))
    for group in coinciding(curves, span):
        c, ls = STYLE.get(models[group[0]], ("tab:red", "-"))
        ax.plot(x, curves[group[0]], ls=ls, color=c, lw=1.4, label=label.format(" and ".join(models[k] for k in group)))


def plot_fe_compliance(ds: xr.Dataset, path: str | Path) -> Path:
    """Top: total tooth compliance (no contact part) against roll length, FE in its plane and
    in plane stress, and the PEMs. Bottom: the body part, FE (root-section rigid motion)
    against Sainsot's fillet foundation of each PEM.

    Parameters
    ----------
    ds : xarray.Dataset
        fe_compliance.nc: over (gear, point) ``roll`` (m, SAP to EAP), ``fe_compliance``,
        ``fe_compliance_plane_stress``, ``fe_body``, ``fe_wind_up`` and over (model, gear, point)
        ``pem_compliance``, ``pem_fillet`` (m²/N: deflection per load per unit face width, drawn
        in µm per N/mm); attributes ``plane`` and ``size_normal_modules``.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.

    References
    ----------
    .. [1] Sainsot P., Velex P., Duverger O., "Contribution of gear body to tooth deflections — a new
       bidimensional analytical formula", J. Mech. Des. 126 (2004) 748–752.
    """
    fig, axes = subplots(2, 2, figsize=(10, 6.4), sharex="col")
    for g, gear in enumerate(ds["gear"].values):
        x = ds["roll"].values[g] * MM
        ax = axes[0, g]
        ax.plot(x, ds["fe_compliance"].values[g] * UM_MM_PER_N, "k-", lw=2, label=f"FE, plane {ds.attrs['plane']}")
        if ds.attrs["plane"] != "stress":
            ax.plot(x, ds["fe_compliance_plane_stress"].values[g] * UM_MM_PER_N, "-", color="0.55", lw=1.5,
                    label="FE, plane stress")
        _pem_lines(ax, x, ds, "pem_compliance", g, "PEM {}")
        ax.set_title(f"{gear}: bending + shear + axial + foundation", fontsize=9)
        ax.set_ylabel("compliance (µm per N/mm)")
        ax.grid(alpha=0.3)
        ax = axes[1, g]
        ax.plot(x, ds["fe_body"].values[g] * UM_MM_PER_N, "k-", lw=2, label="FE body (root-section rigid motion)")
        ax.plot(x, ds["fe_wind_up"].values[g] * UM_MM_PER_N, "k:", lw=1.2, label="FE body wind-up (torsion)")
        _pem_lines(ax, x, ds, "pem_fillet", g, "Sainsot, {} root")
        ax.set_title(f"{gear}: fillet foundation", fontsize=9)
        ax.set_xlabel("roll length of the load point (mm), SAP to EAP")
        ax.set_ylabel("compliance (µm per N/mm)")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    axes[1, 0].legend(fontsize=7)
    fig.suptitle(title(ds, f"tooth compliance per unit width, FE (element {ds.attrs['size_normal_modules']} m_n) "
                           "and potential-energy cantilevers"), fontsize=10)
    fig.tight_layout()
    return save(fig, path)


def fe_compliance_figures(inputs, outputs) -> None:
    """The figure of the ``fe_compliance`` rule.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["fe_compliance"]``,
        writes ``outputs["fe_compliance"]``.
    """
    plot_fe_compliance(inputs["fe_compliance"], outputs["fe_compliance"])

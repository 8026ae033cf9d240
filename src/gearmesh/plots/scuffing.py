"""Scuffing figure: the flash temperature over the path of contact, one line per torque, from
scuffing.nc (:func:`gearmesh.datasets.scuffing.scuffing_dataset`).

The figure job (``scuffing_figures(inputs, outputs)``, as every ``*_figures`` of :mod:`gearmesh.plots`)
takes ``inputs``, a mapping of str to xarray.Dataset (the rule's netCDF inputs by name), and ``outputs``, a
mapping of str to the path of each PNG by name; it writes them and returns None.
"""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from .common import MM, number, palette, save as _save, subplots, title as _title

__all__ = ["plot_flash_temperature", "scuffing_figures"]


def plot_flash_temperature(ds: xr.Dataset, path: str | Path) -> Path:
    """The largest flash temperature over the face (K, Blok, from the LTCA's load) along the path of
    contact from A, one line per torque, labelled with the largest contact temperature θ_B and the
    safety factors S_B (flash temperature method) and S_intS (integral temperature method); the
    mean over the path (θ_flaint) dashed in the same colour; the pitch point C, where the flanks
    roll without sliding, dotted. Where no point of the path carries load (a relief) the line is
    broken: no contact, not a flash temperature of zero. The pinion speed in the title.

    Parameters
    ----------
    ds : xarray.Dataset
        scuffing.nc: ``path`` (m from A), over (torque, path) ``flash_temperature_path`` (K), over
        torque ``flash_temperature_mean`` (K), ``contact_temperature_max`` (°C),
        ``scuffing_safety_flash`` and ``scuffing_safety_integral`` (1); ``pitch_point`` (m from A)
        and the attribute ``speed_rpm`` when present.
    path : str or Path
        The PNG to write.

    Returns
    -------
    Path
        ``path``.
    """
    fig, ax = subplots(1, 1, figsize=(7.5, 4.8), layout="constrained")
    s = ds["path"].values * MM
    for k, color in enumerate(palette(ds.sizes["torque"])):
        sel = ds.isel(torque=k)
        ax.plot(s, sel["flash_temperature_path"].values, color=color, lw=1.8,
                label=f"T1 = {number(float(sel.torque))} N m: θ_B,max {number(float(sel.contact_temperature_max))} °C, "
                      f"S_B {number(float(sel.scuffing_safety_flash))}, S_intS {number(float(sel.scuffing_safety_integral))}")
        ax.axhline(float(sel["flash_temperature_mean"]), color=color, ls="--", lw=1.0)
    if "pitch_point" in ds:
        ax.axvline(float(ds["pitch_point"]) * MM, color="0.4", ls=":", lw=1.0)
        ax.annotate("C", (float(ds["pitch_point"]) * MM, 0.0), xycoords=("data", "axes fraction"),
                    xytext=(3, 3), textcoords="offset points", fontsize=8, color="0.3")
    ax.set_xlim(0.0, float(s[-1] + s[0]))
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel("distance along the path of contact from A (mm)")
    ax.set_ylabel("flash temperature, largest over the face (K)\ndashed: mean over the path")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center")
    speed = f" at n1 = {number(float(ds.attrs['speed_rpm']))} r/min" if "speed_rpm" in ds.attrs else ""
    ax.set_title(_title(ds, f"flash temperature along the path of contact{speed} (Blok, LTCA load)", own_line=True), fontsize=9)
    return _save(fig, path)


def scuffing_figures(inputs, outputs) -> None:
    """The figure of the ``scuffing`` rule: output 'flash_temperature' from the scuffing.nc it wrote.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["scuffing"]``, writes
        ``outputs["flash_temperature"]``.
    """
    plot_flash_temperature(inputs["scuffing"], outputs["flash_temperature"])

"""The sign-off figure: each variant's sign-off quantities as ratios to the reference variant's at
every torque, with each criterion's limit, drawn from signoff_table.nc: the pressure, root-stress
and TE-order panels on the table's basis (the worst manufactured gear, or the nominal gear), the
nominal gear's ratios beside the population's as open markers.

The figure job (``signoff_figures(inputs, outputs)``, as every ``*_figures`` of :mod:`gearmesh.plots`)
takes ``inputs``, a mapping of str to xarray.Dataset (the rule's netCDF inputs by name), and ``outputs``, a
mapping of str to the path of each PNG by name; it writes them and returns None.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from matplotlib.lines import Line2D

from ..choices import IMPACT_INDEX
from .common import palette, plain_log_axis, save as _save, subplots

__all__ = ["plot_signoff", "signoff_figures"]


def _panels(table: xr.Dataset) -> list[tuple[str, str, float, str]]:
    """(variable, what, limit factor, comparison) of each panel, those the table holds."""
    a = table.attrs
    panels = [("pressure_ratio", "peak contact pressure\n(flank vs flank, tip edge vs tip edge)", a["pressure_factor"],
               "≤"),
              ("peak_root_stress", "peak root stress", a["root_stress_factor"], "≤")]
    panels += [(f"lte_order_{int(n)}", f"loaded TE, mesh order {int(n)}", a["harmonic_factor"], "≤")
               for n in np.atleast_1d(a["harmonic_orders"])]
    panels += [("impact_force", IMPACT_INDEX, a["impact_factor"], "<")]
    if "dynamic_mesh_force_peak" in table:
        panels += [("dynamic_mesh_force_peak", "swept peak dynamic mesh force", a["dynamic_factor"], "≤")]
    return panels


def _judged(table: xr.Dataset, name: str) -> str:
    """The table's variable of quantity ``name`` on its basis (the population's ``worst_`` columns)."""
    worst = f"worst_{name}"
    return worst if table.attrs.get("basis") == "population" and worst in table else name


def plot_signoff(table: xr.Dataset, path: str | Path) -> Path:
    """One panel per criterion: each variant's value over the reference's against torque on the table's basis, the
    limit dashed, met points filled circles, failing ones crosses; on the population basis the nominal gear's ratios
    as open markers, dotted (shown, not judged). Two panels a row, type of 10–11 pt (legible at the report's page
    width); one legend under the panels says what every colour, marker and line means. Worst-case F_s in the title.

    Parameters
    ----------
    table : xarray.Dataset
        signoff_table.nc over (variant, torque): ``pressure_ratio`` (1), ``peak_root_stress`` (Pa), ``lte_order_N``
        (m), ``impact_force``, ``dynamic_mesh_force_peak`` (N), ``worst_*``, ``meets_*``; ``reference``, ``*_factor``.
    path : str or Path
        The PNG to write (returned).

    Returns
    -------
    Path
    """
    ref = str(table.attrs["reference"])
    basis = str(table.attrs.get("basis", "nominal"))
    panels = _panels(table)
    ncol = 2
    nrow = -(-len(panels) // ncol)
    fig, axes = subplots(nrow, ncol, figsize=(4.6 * ncol, 3.1 * nrow + 1.2), squeeze=False, layout="constrained")
    torque = table["torque"].values
    others = [v for v in table["variant"].values.tolist() if v != ref]
    colors = palette(max(len(others), 1), "tab10", 0.0, 0.9)
    flag_of = {"pressure_ratio": "meets_pressure", "peak_root_stress": "meets_root_stress",
               "impact_force": "meets_impact", "dynamic_mesh_force_peak": "meets_dynamics"}

    def ratio_of(name: str, variant: str) -> np.ndarray:
        reference = 1.0 if name.endswith("pressure_ratio") else table[name].sel(variant=ref).values  # a ratio already
        return table[name].sel(variant=variant).values / reference

    for ax, (name, what, limit, op) in zip(axes.flat, panels):
        judged = _judged(table, name)
        flag = flag_of.get(name, "meets_te_harmonics")
        for color, variant in zip(colors, others):
            ratio = ratio_of(judged, variant)
            # the table's flag; a TE order's own (the table's flag holds the orders together)
            meets = table[flag].sel(variant=variant).values == 1 if flag != "meets_te_harmonics" \
                else ratio <= limit
            ax.plot(torque, ratio, "-", color=color, lw=1.2, label=variant)
            ax.plot(torque[meets], ratio[meets], "o", color=color, ms=5)
            ax.plot(torque[~meets], ratio[~meets], "x", color=color, ms=8, mew=2)
            if judged != name:  # the nominal gear beside the judged worst manufactured gear
                ax.plot(torque, ratio_of(name, variant), ":o", color=color, lw=0.8, ms=5, mfc="none")
        ax.axhline(limit, color="k", ls="--", lw=1)
        ax.axhline(1.0, color="0.6", lw=0.8)
        lo, hi = ax.get_ylim()
        if lo > 0 and hi / lo > 4:  # a wide spread of ratios: logarithmic, plain tick labels
            ax.set_yscale("log")
            plain_log_axis(ax)
        on = ", worst manufactured gear" if judged != name else ""
        ax.set_title(f"{what}{on}\n(limit {op} {limit:g} × {ref}'s)", fontsize=10)
        ax.set_xlabel("pinion torque (N m)", fontsize=10)
        ax.set_ylabel(f"over {ref}'s", fontsize=10)
        ax.tick_params(labelsize=9)
        ax.grid(alpha=0.3, which="both")
    basis_text = ("judged on the worst manufactured gear (the tolerance box's, searched);\nopen markers: nominal gear"
                  if basis == "population" else "judged on the nominal gear")
    title = f"sign-off against {ref}, {basis_text}"
    if "meets_worst_impact" in table:
        worst = {v: int(table["meets_worst_impact"].sel(variant=v).values[0]) for v in others}
        text = ", ".join(f"{v}: {'meets' if f == 1 else 'fails'}" for v, f in worst.items())
        title += (f"\nworst F_s over the torques at most {table.attrs['worst_impact_factor']:g} × {ref}'s: "
                  f"{text}")
    fig.suptitle(title, fontsize=11)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    key = [Line2D([], [], color="0.3", marker="o", ls="none", ms=6, label="meets the criterion"),
           Line2D([], [], color="0.3", marker="x", ls="none", ms=8, mew=2, label="fails it"),
           Line2D([], [], color="k", ls="--", lw=1, label="the criterion's limit"),
           Line2D([], [], color="0.6", lw=0.8, label=f"equal to {ref}'s")]
    if basis == "population":
        key.insert(2, Line2D([], [], color="0.3", marker="o", mfc="none", ls=":", lw=0.8, ms=6,
                             label="nominal gear (shown, not judged)"))
    variants = [Line2D([], [], color=c, lw=1.6, label=v) for c, v in zip(colors, others)]
    fig.legend(handles=variants + key, loc="outside lower center", ncol=3, fontsize=10)
    return _save(fig, path)


def signoff_figures(inputs, outputs) -> None:
    """The figure of the ``signoff_table`` rule: output 'signoff' from the table it wrote.

    Parameters
    ----------
    inputs, outputs : mapping
        The rule's datasets and PNG paths (module docstring): reads ``inputs["signoff_table"]``,
        writes ``outputs["signoff"]``.
    """
    plot_signoff(inputs["signoff_table"], outputs["signoff"])

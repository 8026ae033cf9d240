"""What drives the mesh of a dynamics model, from the stage's settings and upstream datasets: the
slice stiffness, a tabulated TE, the LTCA's loaded stiffness and error, the mesh force tables of
the real contact (:mod:`gearmesh.meshforce`); and how a result names them.
"""

from __future__ import annotations


import numpy as np
import xarray as xr

from ...errors import GearmeshInputError
from ...gear import PairGeometry
from ...limits import same_point
from ...ltca import contact_tangent_compliance
from ...deflection import mesh_misalignment
from ...deviation import with_misalignment
from ...contact_model import TABLE_CONTACT, ContactModel
from ...meshforce import MeshForceTable, table_layout, tabulate
from ...tca import pair_lead_slope
from ...stiffness import mesh_stiffness
from ...choices import pair_excitation
from .inputs import PAIR_EXCITATIONS, _table_settings

def _stiffness_curve(geom: PairGeometry, stiffness: xr.Dataset | None, method: str, slices: int,
                     positions: int, pinion_torque: float) -> np.ndarray:
    """Transverse TVMS K (N/m) at evenly spaced rolls over one base pitch: from the upstream
    stiffness dataset (``mesh_stiffness`` on ``position``; its contact term at its own torque) or
    computed here with the contact law's tangent at ``pinion_torque`` (N·m)."""
    if stiffness is not None:
        if "mesh_stiffness" not in stiffness:
            raise GearmeshInputError("stiffness", "dataset", "has no 'mesh_stiffness' variable")
        return np.asarray(stiffness["mesh_stiffness"].values, dtype=float)
    return mesh_stiffness(geom, n_positions=positions, n_slices=slices, method=method, components=False,
                          contact_compliance=contact_tangent_compliance(geom, pinion_torque)).K


def _transmission_error(transmission_error_um) -> np.ndarray | None:
    """A tabulated unloaded TE (µm, transverse, evenly over one mesh cycle) in m."""
    if transmission_error_um is None:
        return None
    te = np.asarray(transmission_error_um, dtype=float)
    if te.ndim != 1 or te.size < 2 or not np.all(np.isfinite(te)):
        raise GearmeshInputError("transmission_error_um", transmission_error_um,
                                 "must be a list of >= 2 finite values (µm) over one mesh cycle")
    return te * 1e-6


def ltca_excitation(geom: PairGeometry, ltca: xr.Dataset, pinion_torque: float) -> tuple[np.ndarray, np.ndarray]:
    """Mesh stiffness and equivalent error (both transverse, over one mesh cycle) from the LTCA.

    At the LTCA torque equal to ``pinion_torque`` (N m): k(t) = the loaded tangent mesh
    stiffness k_L and e(t) = LTE(t) − F/k_L(t), F = T1/r_b1, so that the static solution of
    F = k(δ − e) is δ = LTE: the quasi-static excitation of Velex & Ajmi (2006, J. Sound Vib.
    290:882) built from the loaded TE. Micro-geometry, edge contact and the nonlinear contact
    law thus enter the dynamics through the LTCA of each variant.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (its pinion base radius r_b1, m).
    ltca : xarray.Dataset
        The variant's LTCA: ``loaded_mesh_stiffness`` (N/m) and ``lte`` (m) on (``torque``, ``position``),
        ``torque`` the pinion torques (N m).
    pinion_torque : float
        Pinion torque of the dynamics run (N m); one of the LTCA's torques.

    Returns
    -------
    k_l, e : numpy.ndarray
        Loaded mesh stiffness k_L (N/m) and equivalent error e (m), each (positions,) over one mesh cycle.

    Raises
    ------
    GearmeshInputError
        ``ltca.torques_Nm`` when the LTCA has no torque equal to ``pinion_torque``.

    References
    ----------
    .. [1] Velex P., Ajmi M., "On the modelling of excitations in geared systems by transmission
       errors", J. Sound Vib. 290 (2006) 882–909.
    """
    torques = np.asarray(ltca["torque"].values, dtype=float)
    match = np.flatnonzero(same_point(torques, pinion_torque))
    if not match.size:
        raise GearmeshInputError("ltca.torques_Nm", torques.tolist(),
                                 f"must include the dynamics torque ({pinion_torque:.6g} N m on the pinion)")
    k_l = np.asarray(ltca["loaded_mesh_stiffness"].values[match[0]], dtype=float)
    lte = np.asarray(ltca["lte"].values[match[0]], dtype=float)
    force = pinion_torque / float(geom.base_radius[0])
    return k_l, lte - force / k_l


def resolve_excitation(excitation: str | None, ltca: xr.Dataset | None) -> str:
    """The excitation to run (:func:`gearmesh.choices.pair_excitation`): as given, or (None) 'ltca'
    when an LTCA dataset is at hand, else 'tvms'.

    Parameters
    ----------
    excitation : {'tvms', 'lste', 'ltca', 'contact'} or None
        The section's ``excitation``; None for the default.
    ltca : xarray.Dataset or None
        The variant's LTCA dataset, if the run has one.

    Returns
    -------
    str
        The excitation that runs.

    Raises
    ------
    GearmeshInputError
        ``excitation`` when it is none of the pair model's excitations.
    """
    if excitation is not None and excitation not in PAIR_EXCITATIONS:
        raise GearmeshInputError("excitation", excitation, f"must be one of {list(PAIR_EXCITATIONS)} or null")
    return pair_excitation(excitation, ltca is not None)


def contact_table(geom: PairGeometry, pinion_torques, contact: ContactModel = TABLE_CONTACT,
                  **settings) -> MeshForceTable:
    """The mesh force table of ``geom`` (its micro-geometry and deviations) for the ``contact``
    excitation at the first of ``pinion_torques`` (N m): every row reaches ``table_force_factor``
    times the largest static force F_bt = T1/r_b1 of them, the separations carry the mesh
    misalignment of the first (:func:`contact_tables`); ``contact`` its contact model
    (:class:`gearmesh.contact_model.ContactModel`), ``settings`` as :data:`_TABLE_KEYS`.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with its micro-geometry and deviations.
    pinion_torques : float or array_like
        Pinion torques (N m); the first is tabulated.
    contact : ContactModel
        The contact model of the table (default the table's declared one).
    **settings
        ``table_positions``, ``table_approaches``, ``table_force_factor`` (declared defaults when left out).

    Returns
    -------
    MeshForceTable
        The mesh force F(x, w) (N) over one mesh cycle (:class:`gearmesh.meshforce.MeshForceTable`).

    Raises
    ------
    GearmeshInputError
        Naming the table setting out of its declaration or the table over its work limit.
    """
    return contact_tables(geom, np.atleast_1d(pinion_torques)[:1], contact, **settings)[0]


def contact_tables(geom: PairGeometry, pinion_torques, contact: ContactModel = TABLE_CONTACT,
                   **settings) -> list[MeshForceTable]:
    """One mesh force table per pinion torque of ``pinion_torques`` (N m) (:mod:`gearmesh.meshforce`):
    every row of each reaches ``table_force_factor`` times the largest static force F_bt of them;
    each table's separations carry the mesh misalignment at its own static force (the stated f_ma
    and the system deflection's f_sh, :func:`gearmesh.deflection.mesh_misalignment`: the gearbox
    deflects with the mean load), so torques of one misalignment share one table.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with its micro-geometry and deviations.
    pinion_torques : float or array_like
        Pinion torques (N m), (T,).
    contact : ContactModel
        The contact model of the tables (default the table's declared one).
    **settings
        ``table_positions``, ``table_approaches``, ``table_force_factor`` (declared defaults when left out).

    Returns
    -------
    list of MeshForceTable
        One table per torque (N), in the order of ``pinion_torques``; equal misalignments share one object.

    Raises
    ------
    GearmeshInputError
        Naming the table setting out of its declaration or the table over its work limit.
    """
    t = _table_settings(contact, **settings)
    rb1 = float(geom.base_radius[0])
    torques = np.atleast_1d(np.asarray(pinion_torques, dtype=float))
    force = t["factor"] * float(np.max(torques)) / rb1
    layout = table_layout(geom, t["positions"], contact)
    lead = pair_lead_slope(geom)
    built: dict[float, MeshForceTable] = {}
    for m in mesh_misalignment(geom, torques / rb1):
        if float(m) not in built:
            built[float(m)] = tabulate(layout, layout.gaps(lead_slope=with_misalignment(lead, float(m))), force,
                                       t["approaches"])
    return [built[float(m)] for m in mesh_misalignment(geom, torques / rb1)]


def excitation_used(excitation: str, ltca: xr.Dataset | None = None, transmission_error_um=None,
                    table: MeshForceTable | None = None) -> str:
    """What excited the model, for the ``excitation`` attribute of the dataset.

    Parameters
    ----------
    excitation : {'tvms', 'lste', 'ltca', 'contact'}
        The excitation that ran (:func:`resolve_excitation`).
    ltca : xarray.Dataset, optional
        The LTCA behind ``ltca`` (its ``contact_law`` attribute is named).
    transmission_error_um : sequence of float, optional
        The tabulated unloaded TE (µm) of a ``tvms`` run, if any.
    table : MeshForceTable, optional
        The mesh force table behind ``contact`` (its positions and approaches are named).

    Returns
    -------
    str
        One sentence naming the excitation and its sources.
    """
    if excitation == "contact":
        return ("contact: the mesh force of the real tooth contact F(x, w) of every tooth pair (flanks and tip edges, "
                f"modifications and lead slopes; gearmesh.meshforce, {table.positions} positions x "
                f"{table.approach.size} approaches per mesh cycle)" if table is not None else "contact")
    if excitation == "ltca":
        return ("ltca: loaded mesh stiffness k_L(t) and equivalent error e = LTE - F/k_L of the variant's "
                f"LTCA ({ltca.attrs.get('contact_law', 'palmgren') if ltca is not None else 'palmgren'} contact)")
    if excitation == "lste":
        return "lste: slice-model stiffness K(t) and the low-fluctuation paper's error e = F/K(t)"
    te = " and the tabulated unloaded TE" if transmission_error_um is not None else " (unloaded TE zero)"
    return f"tvms: slice-model stiffness K(t){te}"


def model_choices(excitation: str, method: str, contact_law: str, stiffness: xr.Dataset | None = None,
                  ltca: xr.Dataset | None = None) -> dict[str, str]:
    """The tooth model and contact law behind a dynamics result (its ``tooth_model`` and
    ``contact_law`` attributes): the given stiffness dataset's tooth model or ``method`` for
    ``tvms``/``lste``; the LTCA's for ``ltca``; ``method`` and ``contact_law`` of the tabulated
    contact for ``contact``.

    Parameters
    ----------
    excitation : {'tvms', 'lste', 'ltca', 'contact'}
        The excitation that ran.
    method : str
        The section's tooth model (:data:`gearmesh.choices.TOOTH_METHODS`), the fallback.
    contact_law : str
        The section's contact law, the fallback.
    stiffness : xarray.Dataset, optional
        The upstream stiffness dataset (its ``tooth_model`` attribute).
    ltca : xarray.Dataset, optional
        The upstream LTCA dataset (its ``tooth_model`` and ``contact_law`` attributes).

    Returns
    -------
    dict of str to str
        ``tooth_model`` and, for ``ltca`` and ``contact``, ``contact_law``.
    """
    if excitation == "ltca" and ltca is not None:
        return {"tooth_model": str(ltca.attrs.get("tooth_model", method)),
                "contact_law": str(ltca.attrs.get("contact_law", contact_law))}
    if excitation == "contact":
        return {"tooth_model": method, "contact_law": contact_law}
    return {"tooth_model": str(stiffness.attrs.get("tooth_model", method)) if stiffness is not None else method}

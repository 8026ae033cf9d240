"""The model choices a result depends on, and their defaults, declared once for every door.

The study schema (:mod:`gearmesh.settings`), the stage functions (:mod:`gearmesh.datasets`),
the physics functions below them and the ``gearmesh`` command all take their defaults from
here, so a question asked through the CLI, the Python API at any level or the workflow gets
one answer. Every result names the choices it used (netCDF attributes and JSON keys
``tooth_model`` and ``contact_law``). Nothing is imported:
this module sits below every other.
"""

from __future__ import annotations

#: What the mesh-in impact paper's impact force F_s is, as every figure, table and caption names it
#: (Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears): an index of the
#: entering pair's impact by the energy method, the whole relative kinetic energy taken up by the
#: entering pair alone. A time integration of the engagement, where that pair shares the motion with
#: the pairs already in mesh, gives an excess force tens of times smaller (its ratio is stated beside
#: F_s wherever both are computed): F_s ranks and bounds, it is not a force the teeth carry.
IMPACT_INDEX = "mesh-in impact index F_s"

#: Slice models of the tooth compliance: the three potential-energy cantilevers (seeds 003/004:
#: ``traditional`` and ``improved`` root cases, ``transition`` with the hob-generated fillet)
#: and the 2-D plane-strain finite-element tooth (:mod:`gearmesh.fe`).
PEM_TOOTH_METHODS = ("traditional", "improved", "transition")
TOOTH_METHODS = (*PEM_TOOTH_METHODS, "fe")

#: How a figure or a message names each tooth model.
TOOTH_MODEL_NAMES = {
    "traditional": "potential-energy cantilever (traditional root)",
    "improved": "potential-energy cantilever (improved root)",
    "transition": "potential-energy cantilever (hob fillet)",
    "fe": "2-D finite-element tooth",
}

#: The tooth model of every stage and function unless a study or call says otherwise: the 2-D
#: finite-element tooth, within +3/−7 % of the 3-D reference on seven of the nine shipped pairs,
#: where the potential-energy cantilevers are 10–50 % too compliant (docs/validation.md,
#: "Which tooth stiffness to trust").
DEFAULT_TOOTH_METHOD = "fe"

#: Local contact laws of a slice: Palmgren's line-contact approach δ ∝ F^0.9 (F ∝ δ^1.11) or the
#: linear Hertz strip (:func:`gearmesh.ltca_model.contact_law`).
CONTACT_LAWS = ("palmgren", "linear")
DEFAULT_CONTACT_LAW = "palmgren"

#: Rotation positions over one mesh cycle of the loaded contact, declared once: the TCA and LTCA
#: stages, the rating, and the criteria of every manufactured gear (the optimisers' and the impact
#: stage's box worst and populations), so ``gearmesh ltca`` on any of those gears' pair files gives
#: the value they were judged by. Against 128 positions on the default study's relieved variant:
#: loaded-TE orders 1–2 within 0.3 %, pressures and root stress within 0.1 % (32 positions: 1 % and
#: 0.3 %).
DEFAULT_CYCLE_POSITIONS = 64

#: Candidate tip-edge contacts beyond the active zone, in transverse base pitches
#: (:func:`gearmesh.tca.candidate_grid`).
DEFAULT_CORNER_EXTENSION = 0.25

#: What drives the 8-DOF pair (:mod:`gearmesh.dynamics`).
PAIR_EXCITATIONS = ("tvms", "lste", "ltca", "contact")


def pair_excitation(excitation: str | None, ltca_available: bool) -> str:
    """The excitation a dynamics runs: as given, or (None) the LTCA's loaded stiffness and error
    when an LTCA of the variant is at hand (a study that runs the LTCA), else the slice-model
    stiffness. The one statement of "the LTCA drives the dynamics" for the API, the study checks
    and the workflow's inputs.

    Parameters
    ----------
    excitation : {'tvms', 'lste', 'ltca', 'contact'} or None
        The excitation asked for (:data:`PAIR_EXCITATIONS`); None for the default.
    ltca_available : bool
        Whether an LTCA of the variant is at hand.

    Returns
    -------
    str
        One of :data:`PAIR_EXCITATIONS`.
    """
    if excitation is None:
        return "ltca" if ltca_available else "tvms"
    return excitation


#: The lines a force is reported along; every force key ends in ``_transverse_N``, ``_normal_N``
#: or ``_tangential_N`` (JSON, CSV) and every force variable carries ``force_line`` (netCDF).
#: transverse: along the transverse line of action, F_bt = T1/r_b1 (the LTCA, the impact);
#: normal: normal to the flanks, F_bn = F_bt/cos(β_b) (the dynamics' mesh force);
#: tangential: tangential to the reference circle, ISO 6336's F_t = T1/r1 (the rating).
FORCE_LINES = {
    "transverse": "along the transverse line of action (F_bt = T1/r_b1)",
    "normal": "normal to the flanks (F_bn = F_bt/cos beta_b)",
    "tangential": "tangential to the reference circle (ISO 6336's F_t = T1/r1)",
}

#: Long-life conditions of the ISO 6336-2/-3:2019 life factors Z_NT and Y_NT (pair-file key
#: ``life_factor_conditions``): 'normal' takes the standards' line down to 0.85 at 10¹⁰ load
#: cycles, 'optimum' (optimum lubrication, material, manufacturing and experience) holds 1.0
#: beyond the knee (:func:`gearmesh.rating_factors.life_factor_contact`).
LIFE_FACTOR_CONDITIONS = ("normal", "optimum")
DEFAULT_LIFE_FACTOR_CONDITIONS = "normal"

#: The gear of a pair that is an idler (pair-file key ``idler_gear``): it meshes with a third gear
#: on its other flank, so its teeth bend both ways (the mean stress factor Y_M of ISO 6336-3:2019).
IDLER_GEARS = ("pinion", "gear")

#: Load stages of the FZG scuffing test A/8.3/90 (ISO 14635-1:2000, Table 2): 1..12, the stage
#: whose pinion torque first scuffs the test gears (pair-file key ``lubricant.fzg_load_stage``).
FZG_LOAD_STAGES = tuple(range(1, 13))

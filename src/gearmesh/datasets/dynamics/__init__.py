"""Dynamics-stage datasets: the speed sweep of the 8-DOF pair (the low-fluctuation paper §4–5) and the 9-DOF
plate–blanket–impression train (the improved potential-energy paper), from :mod:`gearmesh.dynamics`.

Engineering units at the boundary (rpm, N·m, µm, N·s/m), SI inside and in the datasets. Every
variable has ``units`` and ``long_name``. Statistics are over the steady-state record window
(whole mesh periods, :func:`gearmesh.dynamics.simulate`): ``*_rms`` is sqrt(mean(x²)) with the
mean included (as the low-fluctuation paper's RMS), ``*_std`` the fluctuation about the mean.

One module per topic: :mod:`.inputs` (the settings checked and converted), :mod:`.excitation`
(what drives the mesh), :mod:`.variables` (the variables the pair and the train share),
:mod:`.pair` (the 8-DOF pair), :mod:`.train` (the 9-DOF train), :mod:`.checks` (a study section
checked before any job runs), :mod:`.tables` (the comparison and engagement tables). The names
below are re-exported for users, docs/api.md and the stage declarations
(``"gearmesh.datasets.dynamics:dynamics_dataset"``); inside the package, import them from their
module.
"""

from .checks import check_dynamics_settings
from .excitation import contact_table, contact_tables, excitation_used, ltca_excitation, model_choices, resolve_excitation
from .inputs import (DEFAULT_SPEEDS, PAIR_EXCITATIONS, STEADY_STATES, parse_speeds, positive_quantity, speed_grid,
                     supports_note)
from .pair import build_pair_model, dynamics_dataset, dynamics_summary, resonance_refined
from .tables import dynamics_comparison_dataset, engagement_table_dataset
from .train import PRINTING_TRAIN_MESH_FREQUENCY_HZ, PRINTING_TRAIN_STATIC_FORCE_N, train_dataset
from .variables import DYNAMIC_TE, MESH_DEFLECTION

__all__ = [
    "DEFAULT_SPEEDS", "DYNAMIC_TE", "MESH_DEFLECTION", "PAIR_EXCITATIONS", "PRINTING_TRAIN_MESH_FREQUENCY_HZ",
    "PRINTING_TRAIN_STATIC_FORCE_N", "STEADY_STATES", "build_pair_model", "check_dynamics_settings", "contact_table",
    "contact_tables", "dynamics_comparison_dataset", "dynamics_dataset", "dynamics_summary", "engagement_table_dataset",
    "excitation_used", "ltca_excitation", "model_choices", "parse_speeds", "positive_quantity", "resolve_excitation",
    "resonance_refined", "speed_grid", "supports_note", "train_dataset",
]

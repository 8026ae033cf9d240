"""The variables of a dynamics dataset common to the pair and the train: mesh statistics,
vibration, modes, and the time series and spectra of the kept speeds, each with ``units`` and
``long_name``. Statistics are over the steady-state record window (whole mesh periods,
:func:`gearmesh.dynamics.simulate`): ``*_rms`` is sqrt(mean(x²)) with the mean included (as the
low-fluctuation paper's RMS), ``*_std`` the fluctuation about the mean.
"""

from __future__ import annotations


import numpy as np
import xarray as xr

from ...dynamics import GearModel, full_translations, SweepResult, mesh_energy_fraction, resonance_speeds
from ...io import variable

#: The two displacements of the mesh, both along the transverse line of action (normal values
#: of :mod:`gearmesh.dynamics` divided by cos βb), named so they cannot be mixed up.
DYNAMIC_TE = ("dynamic transmission error along the transverse line of action: relative displacement of the "
              "two gear bodies at the mesh (r_b1 theta_p - r_b2 theta_g plus the centre and axial motions "
              "projected on the line of action; what encoders on both gears measure when the bearings are "
              "rigid); statically the loaded TE (LTCA excitation) or F/K (stiffness excitation)")
MESH_DEFLECTION = ("mesh deflection delta_m along the transverse line of action: elastic approach of the flanks "
                   "(dynamic TE minus the excitation error e), statically F_bt/k with k the transverse mesh "
                   "stiffness (the low-fluctuation paper calls it the DTE)")


def _common_vars(model: GearModel, res: SweepResult, mesh_dim: bool, cos_beta_b: float) -> dict[str, xr.Variable]:
    """Mesh statistics of a sweep: (speed,) for one mesh, (speed, mesh) otherwise. The dynamic
    TE and the mesh deflection are converted from the model's normal direction to the
    transverse line of action (÷ cos βb), the direction of the LTCA's ``lte``."""
    dims = ("speed", "mesh") if mesh_dim else ("speed",)

    def v(a):
        return a.T if mesh_dim else a[0]

    fs = model.static_force[:, None]
    return {
        "mesh_frequency": variable(("speed",), res.mesh_frequency, "Hz", "mesh frequency"),
        "dynamic_te_mean": variable(dims, v(res.approach_mean) / cos_beta_b, "m", f"mean of the {DYNAMIC_TE}"),
        "dynamic_te_std": variable(dims, v(res.approach_std) / cos_beta_b, "m",
                                   f"standard deviation of the {DYNAMIC_TE}"),
        "mesh_deflection_mean": variable(dims, v(res.dte_mean) / cos_beta_b, "m", f"mean of the {MESH_DEFLECTION}"),
        "mesh_deflection_std": variable(dims, v(res.dte_std) / cos_beta_b, "m",
                                        f"standard deviation of the {MESH_DEFLECTION}"),
        "mesh_deflection_rms": variable(dims, v(res.dte_rms) / cos_beta_b, "m",
                                        f"RMS (mean included) of the {MESH_DEFLECTION}"),
        "mesh_deflection_min": variable(dims, v(res.dte_min) / cos_beta_b, "m",
                                        f"minimum (at the steps) of the {MESH_DEFLECTION}; below 0: teeth apart"),
        "mesh_deflection_max": variable(dims, v(res.dte_max) / cos_beta_b, "m",
                                        f"maximum (at the steps) of the {MESH_DEFLECTION}"),
        "mesh_force_mean": variable(dims, v(res.force_mean), "N", "mean dynamic mesh force (normal)"),
        "mesh_force_min": variable(dims, v(res.force_min), "N", "minimum dynamic mesh force (at the steps)"),
        "mesh_force_max": variable(dims, v(res.force_max), "N", "maximum dynamic mesh force (at the steps)"),
        "mesh_force_std": variable(dims, v(res.force_std), "N", "standard deviation of the dynamic mesh force"),
        "dynamic_factor": variable(dims, v(res.force_max / fs), "1", "dynamic factor: maximum over static mesh force"),
        "contact_loss_fraction": variable(dims, v(res.gap_fraction), "1",
                                          "fraction of time with the teeth apart (inside the backlash)"),
        "back_side_fraction": variable(dims, v(res.back_fraction), "1", "fraction of time in back-side contact"),
        "steady_state_change": variable(dims, v(res.steady_change), "1",
                                        "relative change of the mesh-deflection standard deviation between the "
                                        "halves of the record window (steady-state check)"),
        "steps_per_cycle": variable(("speed",), res.steps_per_cycle, "1", "RK4 steps per mesh period"),
        "transient_cycles": variable(("speed",), res.transient_cycles, "1",
                                     "mesh periods integrated and discarded before recording"),
        "time_step": variable(("speed",), res.dt, "s", "RK4 time step"),
        "static_mesh_force": variable(("mesh",) if mesh_dim else (), model.static_force if mesh_dim
                                      else model.static_force[0], "N", "static mesh force (normal) of the torque"),
        "mesh_stiffness_mean": variable(("mesh",) if mesh_dim else (),
                                        np.array([ml.k_mean for ml in model.meshes]) if mesh_dim
                                        else model.meshes[0].k_mean, "N m-1", "mean mesh stiffness along the normal"),
        "mesh_damping": variable(("mesh",) if mesh_dim else (), model.damping if mesh_dim else model.damping[0],
                                 "N s m-1", "mesh damping coefficient"),
    }


def _vibration_vars(res: SweepResult, model: GearModel, shape: tuple[int, int]) -> dict[str, xr.Variable]:
    """Displacement RMS/mean/std and velocity RMS per speed, gear and direction (m, m/s); zero in
    a rigidly supported direction (not a coordinate of the model)."""
    ym = full_translations(model, res.y_mean).T.reshape(-1, *shape)
    ys = full_translations(model, res.y_std).T.reshape(-1, *shape)
    dims = ("speed", "gear", "direction")
    return {
        "displacement_rms": variable(dims, np.sqrt(ym**2 + ys**2), "m", "RMS displacement (mean included)"),
        "displacement_mean": variable(dims, ym, "m", "mean displacement (static bearing deflection)"),
        "displacement_std": variable(dims, ys, "m", "standard deviation of the displacement (vibration)"),
        "velocity_rms": variable(dims, full_translations(model, res.v_rms).T.reshape(-1, *shape), "m s-1",
                                 "RMS velocity"),
    }


def _modal_vars(model: GearModel, harmonics=(1, 2, 3)) -> dict[str, xr.Variable]:
    md = model.modes()
    rs = resonance_speeds(model, harmonics)
    return {
        "mesh_energy_fraction": variable(("mode",), mesh_energy_fraction(model, md["shapes"]), "1",
                                         "fraction of the mode's strain energy in the mesh (mean stiffness)"),
        "natural_frequency": variable(("mode",), md["frequency_Hz"], "Hz",
                                      "natural frequencies of the linearised model (mean stiffness, in contact)"),
        "modal_damping_ratio": variable(("mode",), md["damping_ratio"], "1", "modal damping ratio"),
        "resonance_speed": variable(("harmonic", "mode"), rs["speed_rpm"], "rpm",
                                    "speed where harmonic j of the mesh frequency meets a natural frequency"),
    }


def _series_arrays(res: SweepResult, points_per_cycle: int, max_order: int, n_rec: int):
    """Resample each speed's record window on ``points_per_cycle`` points per mesh period;
    amplitude spectra (one-sided, FFT of the full-resolution periodic window) up to
    ``max_order`` mesh orders; peak-to-peak of y, ẏ and ÿ (central differences)."""
    S = res.speed_rpm.size
    n_s = n_rec * points_per_cycle
    n_o = max_order * n_rec + 1
    out = {k: [] for k in ("t", "delta", "F", "Fe", "y", "v", "F_spec", "delta_spec", "y_pp", "v_pp", "a_pp")}
    for s in range(S):
        st = res.series[s]
        t = st["t"]
        T = n_rec / res.mesh_frequency[s]
        tg = np.arange(n_s) * (T / n_s)
        out["t"].append(tg)
        for key in ("delta", "F", "Fe", "y", "v"):
            arr = st[key]
            out[key].append(np.stack([np.interp(tg, t, arr[:, j], period=T) for j in range(arr.shape[1])], axis=1))
        N = t.size
        for key in ("F", "delta"):
            X = np.fft.rfft(st[key], axis=0) / N
            amp = np.abs(X[:n_o])
            amp[1:] *= 2.0
            out[f"{key}_spec"].append(amp)
        dt = float(res.dt[s])
        acc = (np.roll(st["v"], -1, axis=0) - np.roll(st["v"], 1, axis=0)) / (2 * dt)
        out["y_pp"].append(np.ptp(st["y"], axis=0))
        out["v_pp"].append(np.ptp(st["v"], axis=0))
        out["a_pp"].append(np.ptp(acc, axis=0))
    return {k: np.stack(v) for k, v in out.items()}


def _series_vars(res: SweepResult, arr, n_rec: int, max_order: int, ppc: int, gear_dims: tuple[str, str],
                 trans_shape: tuple[int, int], mesh_dim: bool, cos_beta_b: float,
                 model: GearModel) -> dict[str, xr.Variable]:
    S = res.speed_rpm.size
    ms = ("sample_speed", "sample", "mesh") if mesh_dim else ("sample_speed", "sample")
    msp = ("sample_speed", "order", "mesh") if mesh_dim else ("sample_speed", "order")

    def mv(a):
        return a if mesh_dim else a[..., 0]

    gd = ("sample_speed", "sample") + gear_dims
    pd = ("sample_speed",) + gear_dims
    y = full_translations(model, arr["y"], axis=2).reshape(S, -1, *trans_shape)
    vv = full_translations(model, arr["v"], axis=2).reshape(S, -1, *trans_shape)
    orders = np.arange(max_order * n_rec + 1) / n_rec
    return {
        "time": variable(("sample_speed", "sample"), arr["t"], "s", "time within the record window"),
        "mesh_deflection_series": variable(ms, mv(arr["delta"]) / cos_beta_b, "m", MESH_DEFLECTION),
        "mesh_force_series": variable(ms, mv(arr["F"]), "N", "dynamic mesh force, normal to the flanks"),
        "displacement_series": variable(gd, y, "m", "bearing-point displacement"),
        "velocity_series": variable(gd, vv, "m s-1", "bearing-point velocity"),
        "frequency": variable(("sample_speed", "order"), orders[None, :] * res.mesh_frequency[:, None], "Hz",
                              "frequency of each spectral line"),
        "mesh_force_spectrum": variable(msp, mv(arr["F_spec"]), "N",
                                        "one-sided amplitude spectrum of the mesh force (normal)"),
        "mesh_deflection_spectrum": variable(msp, mv(arr["delta_spec"]) / cos_beta_b, "m",
                                             f"one-sided amplitude spectrum of the {MESH_DEFLECTION}"),
        "displacement_peak_to_peak": variable(pd, full_translations(model, arr["y_pp"], axis=1).reshape(S, *trans_shape), "m",
                                              "peak-to-peak displacement"),
        "velocity_peak_to_peak": variable(pd, full_translations(model, arr["v_pp"], axis=1).reshape(S, *trans_shape), "m s-1",
                                          "peak-to-peak velocity"),
        "acceleration_peak_to_peak": variable(pd, full_translations(model, arr["a_pp"], axis=1).reshape(S, *trans_shape), "m s-2",
                                              "peak-to-peak acceleration (central differences of the velocity)"),
    }

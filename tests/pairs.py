"""Gear pairs for the tests, as pair-file mappings in engineering units."""

from __future__ import annotations

STEEL = {"youngs_modulus_GPa": 210, "poisson_ratio": 0.3, "density_kg_m3": 7850}


def low_fluctuation_pair1(**changes) -> dict:
    """The low-fluctuation paper, Table 1, gear pair 1 (29/49, mn 1.75, 25°, β 10°, b 20; standard distance)."""
    data = {
        "name": "low_fluctuation_pair1", "teeth": [29, 49], "normal_module_mm": 1.75,
        "normal_pressure_angle_deg": 25, "helix_angle_deg": 10, "face_width_mm": 20,
        "addendum_coefficient": 1.0, "dedendum_coefficient": 1.25,
        "bore_radius_mm": [15, 25], "material": dict(STEEL),
        # the shipped file's bodies: rigid webs, the source's model
        "web_thickness_mm": "rigid",
        # the shipped file's supports: the low-fluctuation paper's bearings (N/µm)
        "bearing_radial_stiffness_N_per_um": 150, "bearing_axial_stiffness_N_per_um": 10,
    }
    data.update(changes)
    return data


def torsional_mesh_damping(geom, k_mean_normal: float, zeta: float = 0.07) -> float:
    """The mesh damper as it was before issue 28, 2ζ√(k̄ m_e) with m_e the torsional equivalent
    mass along the normal (N·s/m): tests of the solver and of the engagement physics written
    for that model keep it (the default now sizes the damper on the mesh mode)."""
    import math

    cb = math.cos(geom.base_helix_angle)
    m_e = 1.0 / (cb**2 * sum(float(r) ** 2 / float(j) for r, j in zip(geom.base_radius, geom.inertia)))
    return 2 * zeta * math.sqrt(k_mean_normal * m_e)

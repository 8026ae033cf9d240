"""Shared fixtures: the project root and pair dicts in engineering units."""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

STEEL = {"youngs_modulus_GPa": 210, "poisson_ratio": 0.3, "density_kg_m3": 7850}


def seed001_pair1(**changes):
    """Seed 001, Table 1, gear pair 1, as a pair-file mapping."""
    data = {
        "name": "seed001_pair1", "teeth": [29, 49], "normal_module_mm": 1.75,
        "normal_pressure_angle_deg": 25, "helix_angle_deg": 10, "face_width_mm": 20,
        "bore_radius_mm": [15, 25], "material": dict(STEEL),
    }
    data.update(changes)
    return data


@pytest.fixture
def root() -> Path:
    return ROOT

"""The tiny two-pulley scene shared by the runtime and robustness tests."""

from __future__ import annotations

import math

from beltrs import Belt, Pulley, Scene


def tiny_scene(**belt) -> Scene:
    """Two 0.5 m pulleys 2 m apart, 16 elements, pretensioned by a 0.2 % short belt: about
    1 µs per step, so 10^6 steps take about a second."""
    path = 2 * 2.0 + 2 * math.pi * 0.5
    kw = dict(axial_stiffness=1e6, mass_per_length=10.0, elements=16, length=path * 0.998, damping_ratio=0.05)
    kw.update(belt)
    return Scene(
        belt=Belt(**kw),
        pulleys=[
            Pulley(center=(0.0, 0.0), radius=0.5, contact_stiffness=1e7, name="tail"),
            Pulley(center=(2.0, 0.0), radius=0.5, contact_stiffness=1e7, name="head"),
        ],
    )

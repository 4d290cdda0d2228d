"""Built-in scenes."""

from __future__ import annotations

from typing import Optional

from .scene import Belt, Friction, Pulley, Scene, Solver, Takeup

__all__ = ["hustrulid_loop"]


def hustrulid_loop(
    elements: int = 89,
    *,
    contact_stiffness: float = 2e8,
    friction: Optional[Friction] = None,
    damping_ratio: float = 0.0,
    counterweight: float = 30_000.0,
    bending: bool = True,
    time_step: Optional[float] = None,
    time_step_fraction: float = 0.5,
) -> Scene:
    """Case H: Hustrulid's two-pulley vertical loop (thesis chapter 6, reference-cases.md).

    Upper pulley at (0, 100) m, radius 5 m, 600 kg, inertia 15 000 kg*m^2, fixed centre.
    Lower pulley at (0, 0), the same, as a vertical gravity takeup with a 30 000 kg
    counterweight. Belt E = 300 MPa, 1 m x 0.0254 m (EA = 7.62 MN, EI = 409.7 N*m^2),
    100 kg/m, placed unstretched on the 231.416 m path.

    Args:
        elements: number of belt elements (89 = 2.600 m, a 30 degree arc).
        contact_stiffness: belt-pulley penalty stiffness, N per metre of penetration.
            Default 2e8: the thesis code's KC = 1e9 N in its law f = KC (R - a)/R with
            R = 5 m. The largest nodal force (~0.13 MN at 89 elements) then penetrates
            0.65 mm, which moves the takeup by about 1 mm (0.03 % of the answer). Stiffer
            contact (the thesis text's 1e12) shrinks the step and slows the static
            relaxation (the contact/belt stiffness ratio sets its conditioning) for no gain
            in these answers.
        friction: pulley friction (both pulleys). Default None (frictionless, as in the
            exact statics).
        damping_ratio: axial damping, fraction of critical. Default 0.
        counterweight: takeup counterweight, kg. Default 30 000.
        bending: include EI. Default True.
        time_step: fixed step, s. Default None (automatic).
        time_step_fraction: fraction of the stability limit. Default 0.5.
    """
    e, w, t = 300e6, 1.0, 0.0254
    belt = Belt.from_material(e, w, t, 100.0, elements=elements, damping_ratio=damping_ratio)
    if not bending:
        belt.bending_stiffness = 0.0
    common = dict(radius=5.0, mass=600.0, inertia=15_000.0, contact_stiffness=contact_stiffness)
    return Scene(
        belt=belt,
        pulleys=[
            Pulley(name="upper", center=(0.0, 100.0), friction=friction, **common),  # type: ignore[arg-type]
            Pulley(
                name="takeup",
                center=(0.0, 0.0),
                friction=friction,
                takeup=Takeup(counterweight=counterweight),
                **common,  # type: ignore[arg-type]
            ),
        ],
        solver=Solver(time_step=time_step, time_step_fraction=time_step_fraction),
    )

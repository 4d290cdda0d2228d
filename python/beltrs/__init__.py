"""beltrs: transient dynamics of belt conveyors and belt drives.

A Rust engine (Hustrulid's discrete node model: Kelvin-Voigt elements, bending springs,
penalty contact, stick-force friction, central differences) driven from Python. SI units
everywhere.
"""

from . import analysis, analytic, scenes
from ._beltrs import BeltrsError, CheckpointError, DivergenceError, SceneError, TimeStepError
from ._beltrs import __version__
from .result import Result
from .scene import Belt, Brake, Drive, Friction, Idler, Pulley, Scene, Solver, Takeup
from .simulation import Simulation

__all__ = [
    "Belt",
    "BeltrsError",
    "Brake",
    "CheckpointError",
    "DivergenceError",
    "Drive",
    "Friction",
    "Idler",
    "Pulley",
    "Result",
    "Scene",
    "SceneError",
    "Simulation",
    "Solver",
    "Takeup",
    "TimeStepError",
    "__version__",
    "analysis",
    "analytic",
    "scenes",
]

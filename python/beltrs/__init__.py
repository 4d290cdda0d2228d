"""beltrs: transient dynamics of belt conveyors and belt drives.

A Rust engine (Hustrulid's discrete node model: Kelvin-Voigt elements, bending springs,
penalty contact, stick-force friction, central differences) driven from Python. SI units
everywhere.
"""

from . import analysis, analytic, scenes, study
from ._beltrs import BeltrsError, CheckpointError, DivergenceError, SceneError, TimeStepError
from ._beltrs import __version__
from .model import Model
from .model import compile as compile  # not in __all__: a star import would shadow the builtin
from .result import Result
from .scene import Belt, Brake, Drive, Friction, Idler, Load, Pulley, Recording, Scene, Solver, StartCurve, Takeup
from .scene_file import load_scene
from .simulation import CheckpointWarning, Simulation

__all__ = [
    "Belt",
    "BeltrsError",
    "Brake",
    "CheckpointError",
    "CheckpointWarning",
    "DivergenceError",
    "Drive",
    "Friction",
    "Idler",
    "Load",
    "Model",
    "Pulley",
    "Recording",
    "Result",
    "Scene",
    "SceneError",
    "Simulation",
    "Solver",
    "StartCurve",
    "Takeup",
    "TimeStepError",
    "__version__",
    "analysis",
    "analytic",
    "load_scene",
    "scenes",
    "study",
]

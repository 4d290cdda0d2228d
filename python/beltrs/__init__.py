"""beltrs: transient dynamics of belt conveyors and belt drives.

A Rust engine (Hustrulid's discrete node model: Kelvin-Voigt elements, bending springs,
penalty contact, stick-force friction, central differences) driven from Python. SI units
everywhere.
"""

from . import analysis, analytic, conveyor, design_start, plot, scenes, statics, study
from ._checks import BeltrsWarning, UndampedContactWarning
from ._beltrs import BeltrsError, CheckpointError, DivergenceError, SceneError, TimeStepError
from ._beltrs import DEFAULT_CONTACT_DAMPING_RATIO, __version__
from .model import Model
from .model import compile as compile  # not in __all__: a star import would shadow the builtin
from .diagnostics import AccuracyWarning, DriveDirectionWarning, IdlerContactWarning, NotRelaxedWarning
from .result import Result, load_result
from .scene import (
    Belt, Brake, Drive, Friction, Holdback, Idler, Initial, Load, NonlinearContact, Pulley, Recording, Scene, Solver,
    StartCurve, Takeup,
)
from .scene import FluidCoupling, Motor, SpeedController, TorqueFollow
from .scene_file import load_scene
from .simulation import CheckpointWarning, Simulation

__all__ = [
    "DEFAULT_CONTACT_DAMPING_RATIO",
    "AccuracyWarning",
    "Belt",
    "BeltrsError",
    "BeltrsWarning",
    "Brake",
    "CheckpointError",
    "CheckpointWarning",
    "DivergenceError",
    "DriveDirectionWarning",
    "Drive",
    "FluidCoupling",
    "Friction",
    "Holdback",
    "Idler",
    "IdlerContactWarning",
    "Initial",
    "Load",
    "Model",
    "NonlinearContact",
    "Motor",
    "NotRelaxedWarning",
    "Pulley",
    "Recording",
    "Result",
    "Scene",
    "SceneError",
    "Simulation",
    "Solver",
    "SpeedController",
    "StartCurve",
    "Takeup",
    "TimeStepError",
    "TorqueFollow",
    "UndampedContactWarning",
    "__version__",
    "analysis",
    "analytic",
    "conveyor",
    "design_start",
    "load_result",
    "load_scene",
    "plot",
    "scenes",
    "statics",
    "study",
]

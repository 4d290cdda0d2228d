"""One scene schema (rust/src/scene): the dataclasses take their defaults and keys from the
engine, and every public path (dataclasses, dicts, TOML) is checked by the engine's one
reader. Regression tests for issue 13 item 8: bad input on the dataclass path escaped as
bare TypeError/ValueError/AttributeError, a deeply nested TOML file as RecursionError, and
``counterweight=None`` became 0 kg."""

import dataclasses
import math

import numpy as np
import pytest

import beltrs
from beltrs import (Belt, Brake, Drive, Friction, Holdback, Idler, Initial, Load, NonlinearContact, Pulley, Recording,
                    Scene, SceneError, Solver, StartCurve, Takeup)
from beltrs._beltrs import scene_defaults
from beltrs.scenes import hustrulid_loop

TABLES = {
    "scene": Scene,
    "belt": Belt,
    "pulley": Pulley,
    "friction": Friction,
    "nonlinear_contact": NonlinearContact,
    "takeup": Takeup,
    "drive": Drive,
    "start_curve": StartCurve,
    "controller": beltrs.SpeedController,
    "follow": beltrs.TorqueFollow,
    "motor": beltrs.Motor,
    "coupling": beltrs.FluidCoupling,
    "brake": Brake,
    "holdback": Holdback,
    "idler": Idler,
    "load": Load,
    "solver": Solver,
    "recording": Recording,
    "initial": Initial,
}


def test_dataclass_fields_and_defaults_are_the_engines():
    defaults = scene_defaults()
    assert set(defaults) == set(TABLES)
    for table, cls in TABLES.items():
        obj = cls()
        assert {f.name for f in dataclasses.fields(cls)} == set(defaults[table]), table
        for key, engine in defaults[table].items():
            ours = getattr(obj, key)
            if dataclasses.is_dataclass(ours):
                assert ours.to_dict() == engine, (table, key)
            elif isinstance(ours, tuple):
                assert list(ours) == engine, (table, key)
            elif isinstance(engine, float) and math.isnan(engine):
                assert math.isnan(ours)
            else:
                assert ours == engine and type(ours) is type(engine), (table, key, ours, engine)


def test_a_scene_read_back_from_the_engine_is_the_same_scene():
    scene = hustrulid_loop(friction=Friction(static=0.4, kinetic=0.3))
    scene.pulleys[0].drive = Drive(time=[0.0, 1.0], torque=[0.0, 1e4], speed=[0.0, 1.0], speed_factor=[1.0, 0.5])
    scene.pulleys[1].brake = Brake(time=[0.0], capacity=[5.0])
    scene.recording = Recording(every=3, channels=("tension",))
    sim = beltrs.Simulation(scene)
    assert sim._core.scene_dict() == scene.to_dict()
    assert Scene.from_dict(sim._core.scene_dict()) == scene


# --- issue 13 item 8: wrong types on the dataclass path are SceneErrors -------------------
@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda s: setattr(s.pulleys[0], "center", 5.0), r"pulleys\[0\]\.center = 5\.0: expected \[x, y\]"),
        (lambda s: setattr(s.pulleys[0], "center", None), r"pulleys\[0\]\.center = None: expected \[x, y\]"),
        (lambda s: setattr(s.pulleys[0], "center", ("a", 1.0)), r"pulleys\[0\]\.center\[0\] = 'a': expected a number"),
        (
            lambda s: setattr(s.pulleys[0], "drive", Drive(time=3.0)),
            r"pulleys\[0\]\.drive\.time = 3\.0: expected a list of numbers",
        ),
        (
            lambda s: setattr(s.pulleys[0], "drive", Drive(torque=[object()])),
            r"pulleys\[0\]\.drive\.torque\[0\] = <object object at .*>: expected a number",
        ),
        (lambda s: setattr(s.pulleys[0], "friction", 0.3), r"pulleys\[0\]\.friction = 0\.3: expected a table"),
        (lambda s: setattr(s.pulleys[0], "takeup", "yes"), r"pulleys\[0\]\.takeup = 'yes': expected a table"),
        (lambda s: setattr(s, "pulleys", None), r"pulleys = None: expected a list of tables"),
        (lambda s: setattr(s, "pulleys", [1, 2]), r"pulleys\[0\] = 1: expected a table"),
        (lambda s: setattr(s, "belt", "steel cord"), r"belt = 'steel cord': expected a table"),
        (lambda s: setattr(s.recording, "channels", 5), r"recording\.channels = 5: expected a list of strings"),
        (lambda s: setattr(s.solver, "time_step", "1 ms"), r"solver\.time_step = '1 ms': expected a number"),
        (lambda s: setattr(s, "gravity", 10**400), r"gravity = 1000.*: expected a number"),
        (lambda s: setattr(s, "gravity", b"9.81"), r"gravity = b'9\.81': expected a number"),
        (lambda s: setattr(s.belt, "elements", 2**70), r"belt\.elements = 1\.1805916207174113e\+21: expected a whole"),
        # counterweight=None used to become 0 kg on the dataclass path.
        (
            lambda s: setattr(s.pulleys[1].takeup, "counterweight", None),
            r"pulleys\[1\]\.takeup\.counterweight = None: expected a number",
        ),
        (lambda s: setattr(s.pulleys[0], "mass", None), r"pulleys\[0\]\.mass = None: expected a number"),
    ],
)
def test_wrong_types_in_dataclasses_are_scene_errors_on_every_path(change, message, tmp_path):
    scene = hustrulid_loop()
    change(scene)
    with pytest.raises(SceneError, match=message):
        scene.to_dict() and beltrs.Simulation(scene)
    with pytest.raises(SceneError, match=message):
        scene.to_toml()
    with pytest.raises(SceneError, match=message):
        scene.save(tmp_path / "s.toml")
    with pytest.raises(SceneError, match=message):
        Scene.from_dict(scene.to_dict())


def test_a_scene_object_holding_itself_is_a_scene_error():
    scene = hustrulid_loop()
    scene.pulleys[0].drive = scene.pulleys[0]  # type: ignore[assignment]
    with pytest.raises(SceneError, match=r"pulleys\[0\]\.drive\.drive\..*: nested deeper than any scene key"):
        beltrs.Simulation(scene)
    loop = Drive()
    loop.start_curve = loop  # type: ignore[assignment]
    scene.pulleys[0].drive = loop
    with pytest.raises(SceneError, match=r"pulleys\[0\]\.drive\.start_curve"):
        beltrs.Simulation(scene)


def test_numpy_values_are_read_as_numbers():
    scene = hustrulid_loop()
    scene.pulleys[0].radius = np.float32(5.0)
    scene.belt.elements = np.int64(89)
    scene.pulleys[0].center = np.array([0.0, 100.0])
    assert beltrs.Simulation(scene).nodes == 89


# --- issue 13 item 8: deep nesting --------------------------------------------------------
@pytest.mark.parametrize(
    "text",
    [
        "gravity = " + "[" * 5000 + "]" * 5000,
        "gravity = " + "{a = " * 5000 + "1" + "}" * 5000,
        ".".join(["belt"] * 5000) + " = 1",
    ],
)
def test_toml_nested_5000_levels_is_a_scene_error(text):
    with pytest.raises(SceneError, match=r"^<string>: .*nested"):
        Scene.from_toml(text)


def test_a_dict_nested_5000_levels_is_a_scene_error():
    deep: dict = {}
    node = deep
    for _ in range(5000):
        node["belt"] = {}
        node = node["belt"]
    with pytest.raises(SceneError, match=r"nested deeper than any scene key"):
        Scene.from_dict(deep)
    with pytest.raises(SceneError, match=r"nested deeper than any scene key"):
        beltrs._beltrs.Simulation(deep)


def test_a_list_where_a_table_belongs_is_a_scene_error():
    # serde's derived structs also read a list of their fields in order, so `belt = []`
    # compiled as the default belt and later failed as an AttributeError (the campaign's
    # seed 5157); a table is written with its keys.
    good = hustrulid_loop(16).to_dict()
    for key, value in (("belt", []), ("solver", [0.5]), ("pulleys", [[], []])):
        bad = dict(good, **{key: value})
        with pytest.raises(SceneError, match=r"(belt|solver|pulleys\[0\]) = \[.*\]: expected a table"):
            beltrs._beltrs.Simulation(bad)
        with pytest.raises(SceneError, match=r"expected a table"):
            beltrs.Simulation(Scene.from_dict(bad))


def test_a_checkpoint_gives_back_every_table(tmp_path):
    scene = hustrulid_loop()
    scene.recording = Recording(duration=0.5, every=2, stabilise=False)
    scene.pulleys[1].friction = Friction(static=0.3)
    sim = beltrs.Simulation(scene)
    sim.step(3)
    path = tmp_path / "c.ck"
    sim.save_checkpoint(path)
    back = beltrs.Simulation.load_checkpoint(path)
    assert back.scene.recording == scene.recording
    # kinetic None means "equal to static": the engine stores the value it stands for.
    assert back.scene.pulleys[1].friction == Friction(static=0.3, kinetic=0.3)


def test_a_checkpoint_of_an_older_format_is_refused_naming_its_version(tmp_path):
    sim = beltrs.Simulation(hustrulid_loop())
    path = tmp_path / "c.ck"
    sim.save_checkpoint(path)
    data = bytearray(path.read_bytes())
    for old in (1, 2, 3):  # hand-written scene encodings, before the scene's serde form
        data[8:12] = old.to_bytes(4, "little")
        path.write_bytes(bytes(data))
        with pytest.raises(
            beltrs.CheckpointError, match=rf"format version {old}; this build of beltrs reads versions 4 to 5 \(.*older"
        ):
            beltrs.Simulation.load_checkpoint(path)

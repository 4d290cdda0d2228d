"""TOML scene files: lossless round trip, the builder and the loader agree, strict reading."""

import dataclasses
import difflib
import math
import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import beltrs
from beltrs import (Belt, Brake, Drive, Friction, Idler, Load, Pulley, Recording, Scene, SceneError, Solver,
                    Takeup)
from beltrs import scene_file
from beltrs.scenes import hustrulid_loop


def everything() -> Scene:
    """Case H with every kind of key set, several to awkward values."""
    scene = hustrulid_loop(89, friction=Friction(static=0.5, kinetic=0.4), damping_ratio=0.01)
    scene.pulleys[0].name = 'upper "U" \\ ünïcode\ttab'
    scene.pulleys[0].drive = Drive(
        time=[0.0, 0.07, 0.070000001],
        torque=[4e5, 4e5, 0.0],
        speed=[-10.0, 0.0, 10.0],
        speed_factor=[1.0, 1.0, 0.5],
        viscous=12.5,
        inertia=3.25,
    )
    scene.pulleys[0].brake = Brake(time=[0.0, 1.0], capacity=[0.0, 1e5])
    scene.pulleys[1].takeup = Takeup(counterweight=30_000.0, travel_min=-10.0, travel_max=0.1)
    scene.pulleys[1].friction = Friction(static=0.3)  # kinetic None: equal to static
    scene.pulleys[1].contact_damping = -0.0  # written as -0.0, not dropped as the default
    scene.idlers = [
        Idler(center=(5.2, 50.0), friction=Friction(0.3, 0.25), contact_damping=0.1),
        Idler(center=(-5.2, 50.0), radius=0.1, inertia=0.02),
    ]
    scene.belt.length = 231.5
    scene.belt.tension_only = True
    scene.gravity = 9.80665
    scene.solver = Solver(time_step=1e-4, time_step_fraction=0.3)
    scene.recording = Recording(duration=0.1, every=7, channels=("tension",), stabilise=False)
    return scene


def test_save_load_gives_an_equal_scene(tmp_path):
    for scene in (hustrulid_loop(89), everything(), beltrs.scenes.idler_conveyor(30.0)):
        path = tmp_path / "scene.toml"
        scene.save(path)
        loaded = beltrs.load_scene(path)
        assert loaded == scene
        # Equal text again: the writer is deterministic and the loaded scene canonical.
        assert loaded.to_toml() == scene.to_toml()
    # The awkward values survive exactly.
    loaded = Scene.from_toml(everything().to_toml())
    assert loaded.pulleys[0].name == everything().pulleys[0].name
    assert math.copysign(1.0, loaded.pulleys[1].contact_damping) == -1.0
    assert loaded.pulleys[1].friction.kinetic is None
    assert loaded.pulleys[1].takeup.travel_max == 0.1


def test_round_trip_compiles_and_runs_bit_for_bit(tmp_path):
    scene = everything()
    scene.solver = Solver()  # automatic step
    path = tmp_path / "s.toml"
    scene.save(path)
    # Pulley 1 has friction on contact damped by -0.0 (an awkward value for the writer).
    with pytest.warns(beltrs.UndampedContactWarning):
        a, b = beltrs.Simulation(scene), beltrs.Simulation(beltrs.load_scene(path))
    assert (a.dt, a.dt_limit, a.stages, a.nodes) == (b.dt, b.dt_limit, b.stages, b.nodes)
    assert np.array_equal(a.rest_length, b.rest_length) and np.array_equal(a.node_mass, b.node_mass)
    # From the placement, on purpose; the idlers (there to cover the format) sit 0.1 m
    # and more outside the belt.
    with pytest.warns(beltrs.IdlerContactWarning), pytest.warns(beltrs.NotRelaxedWarning):
        ra, rb = a.run(300 * a.dt, record_every=1), b.run(300 * b.dt, record_every=1)
    assert len(ra) == 301
    for f in dataclasses.fields(ra):
        x, y = getattr(ra, f.name), getattr(rb, f.name)
        if isinstance(x, np.ndarray):
            assert np.array_equal(x, y), f.name  # bit for bit: same scene, same arithmetic
    # The run did something: the drive turned the upper pulley (its brake, ramping up,
    # stops it again within the 300 steps).
    assert np.abs(ra.pulley_speed[:, 0]).max() > 0


def test_to_dict_from_dict_symmetry():
    for scene in (hustrulid_loop(), everything(), Scene()):
        assert Scene.from_dict(scene.to_dict()) == scene
        assert Scene.from_dict(scene.to_dict()).to_dict() == scene.to_dict()


def test_builder_normalises_to_what_the_loader_gives():
    built = Pulley(center=[0, 100], mass=600, radius=np.float64(5.0), drive=Drive(time=np.array([0, 1]), torque=[1, 2]))
    assert type(built.mass) is float and type(built.radius) is float
    assert built.center == (0.0, 100.0) and type(built.center[0]) is float
    assert built.drive.time == (0.0, 1.0) and built.drive.torque == (1.0, 2.0)
    loaded = Scene.from_toml(Scene(pulleys=[built]).to_toml()).pulleys[0]
    assert loaded == built and loaded.drive.time == built.drive.time
    # Drive.pulse builds lists; the scene holds tuples either way.
    assert Drive.pulse(1.0, 0.5).time == (0.0, 0.5, 0.5 + 1e-9)
    # A dict where a scene object goes is read strictly too.
    assert Pulley(friction={"static": 0.5}).friction == Friction(static=0.5)


finite = st.floats(allow_nan=False, allow_infinity=False)


@settings(max_examples=60, deadline=None)
@given(
    values=st.lists(st.one_of(finite, st.just(math.inf), st.just(-math.inf), st.just(-0.0)), min_size=7, max_size=7),
    name=st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=20),
    # A count: negative counts are refused when read (see test_negative_count_is_refused_when_read).
    elements=st.one_of(st.none(), st.integers(min_value=0, max_value=2**63 - 1)),
    table=st.lists(finite, min_size=1, max_size=6),
)
def test_any_values_round_trip_exactly(values, name, elements, table):
    scene = Scene(
        belt=Belt(axial_stiffness=values[0], damping_ratio=values[1], elements=elements),
        pulleys=[
            Pulley(
                name=name, center=(values[2], values[3]), mass=values[4], drive=Drive(time=table, torque=table[::-1])
            )
        ],
        idlers=[Idler(center=(values[5], 0.0), radius=values[6])],
        gravity=values[6],
    )
    loaded = Scene.from_toml(scene.to_toml())
    assert loaded == scene
    # Equality holds for -0.0 == 0.0; the text must keep the sign too.
    for x, y in zip(
        values,
        (
            loaded.belt.axial_stiffness,
            loaded.belt.damping_ratio,
            *loaded.pulleys[0].center,
            loaded.pulleys[0].mass,
            loaded.idlers[0].center[0],
            loaded.idlers[0].radius,
        ),
    ):
        assert repr(x) == repr(y)


def test_negative_count_is_refused_when_read():
    with pytest.raises(SceneError, match=r"belt\.elements = -1: expected a whole number ≥ 0"):
        Scene(belt=Belt(elements=-1)).to_toml()
    with pytest.raises(SceneError, match=r"<string>: belt\.elements = -1: expected a whole number ≥ 0"):
        Scene.from_toml("[belt]\nelements = -1\n")


def test_nan_round_trips():
    loaded = Scene.from_toml(Scene(gravity=math.nan).to_toml())
    assert math.isnan(loaded.gravity)


# --- strict reading --------------------------------------------------------------------
CASE_H = hustrulid_loop().to_toml()


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            CASE_H.replace("radius = 5.0", "radious = 5.0", 1),
            r"<string>: pulleys\[0\]\.radious = 'radious': unknown key, did you mean 'radius'\? "
            r"\(known keys here: bearing_damping, brake, ",
        ),
        (
            CASE_H.replace("counterweight =", "conterweight ="),
            r"pulleys\[1\]\.takeup\.conterweight = 'conterweight': unknown key, did you mean 'counterweight'\?",
        ),
        (
            CASE_H.replace("gravity =", "gravitation ="),
            r"^<string>: gravitation = 'gravitation': unknown key, did you mean 'gravity'\?",
        ),
        (
            CASE_H.replace("[solver]", "[solver]\nxyzzy = 1"),
            r"solver\.xyzzy = 'xyzzy': unknown key \(known keys here: absolute_tolerance, integrator, "
            r"relative_tolerance, time_step, time_step_fraction\)",
        ),
        (
            CASE_H.replace("stabilise = true", "stabilize = true"),
            r"recording\.stabilize = 'stabilize': unknown key, did you mean 'stabilise'\?",
        ),
        (
            CASE_H + "\n[[idlers]]\ncentre = [1.0, 2.0]\n",
            r"idlers\[0\]\.centre = 'centre': unknown key, did you mean 'center'\?",
        ),
    ],
)
def test_unknown_keys_name_the_path_and_suggest(text, message):
    with pytest.raises(SceneError, match=message):
        Scene.from_toml(text)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (CASE_H.replace("gravity = 9.81", 'gravity = "9.81"'), r"gravity = '9\.81': expected a number"),
        (CASE_H.replace("elements = 89", "elements = 89.0"), r"belt\.elements = 89\.0: expected a whole number"),
        (CASE_H.replace("tension_only = false", "tension_only = 0"), r"belt\.tension_only = 0: expected true or false"),
        (CASE_H.replace("mass = 600.0", "mass = true", 1), r"pulleys\[0\]\.mass = True: expected a number"),
        (
            CASE_H.replace("center = [0.0, 100.0]", "center = [0.0, 100.0, 1.0]"),
            r"pulleys\[0\]\.center = \[0\.0, 100\.0, 1\.0\]: expected \[x, y\]",
        ),
        (
            CASE_H.replace("center = [0.0, 100.0]", 'center = [0.0, "up"]'),
            r"pulleys\[0\]\.center\[1\] = 'up': expected a number",
        ),
        (CASE_H.replace('name = "upper"', "name = 7"), r"pulleys\[0\]\.name = 7: expected a string"),
        ("belt = 3\n", r"^<string>: belt = 3: expected a table$"),
        ("pulleys = 5\n", r"pulleys = 5: expected a list of tables"),
        ("pulleys = [5]\n", r"pulleys\[0\] = 5: expected a table"),
        (
            CASE_H.replace('channels = ["tension", "node_position", "node_velocity"]', 'channels = "tension"'),
            r"recording\.channels = 'tension': expected a list of strings",
        ),
        ("[pulleys]\n[pulleys.drive]\ntime = 1.0\n", r"pulleys = \{'drive'.*expected a list of tables"),
    ],
)
def test_wrong_types_name_field_value_and_type(text, message):
    with pytest.raises(SceneError, match=message):
        Scene.from_toml(text)


def test_invalid_toml_and_bad_files(tmp_path):
    with pytest.raises(SceneError, match=r"<string>: not valid TOML: .*line 1"):
        Scene.from_toml("[belt\n")
    bad = tmp_path / "latin1.toml"
    bad.write_bytes('[[pulleys]]\nname = "Stra\xdfe"\n'.encode("latin-1"))
    with pytest.raises(SceneError, match=r"latin1\.toml: not UTF-8 text"):
        beltrs.load_scene(bad)
    with pytest.raises(FileNotFoundError):
        beltrs.load_scene(tmp_path / "missing.toml")


def test_reader_missing_gives_a_clear_error(monkeypatch):
    """Python 3.9/3.10 without tomli: a clear message, not a NameError later."""
    monkeypatch.setattr(scene_file, "_toml", None)
    with pytest.raises(ImportError, match=r"Python >= 3\.11 \(tomllib\) or the 'tomli' package"):
        Scene.from_toml(CASE_H)


def test_saving_a_wrong_type_is_refused_and_leaves_no_file(tmp_path):
    scene = hustrulid_loop()
    scene.pulleys[1].mass = "heavy"  # type: ignore[assignment]
    path = tmp_path / "s.toml"
    with pytest.raises(SceneError, match=r"pulleys\[1\]\.mass = 'heavy': expected a number"):
        scene.save(path)
    assert os.listdir(tmp_path) == []
    # Saving over an existing file replaces it and leaves no temporary file behind.
    hustrulid_loop().save(path)
    everything().save(path)
    assert os.listdir(tmp_path) == ["s.toml"] and beltrs.load_scene(path) == everything()


# --- every form is read by the engine's one schema reader --------------------------------
def unknown_key_message(path: str, key: str, known: list) -> str:
    """The message expected for an unknown key, with difflib's suggestion."""
    known = sorted(set(known))
    close = difflib.get_close_matches(key, known, n=1)
    hint = f", did you mean {close[0]!r}?" if close else ""
    return f"{path} = {key!r}: unknown key{hint} (known keys here: {', '.join(known)})"

def engine_error(d) -> str:
    with pytest.raises(SceneError) as err:
        beltrs._beltrs.Simulation(d)
    return str(err.value)


def python_error(d) -> str:
    with pytest.raises(SceneError) as err:
        Scene.from_dict(d)
    return str(err.value)


@pytest.mark.parametrize(
    ("where", "typo"),
    [
        ((), "gravty"),
        (("belt",), "mass_per_lenght"),
        (("pulleys", 0), "contact_stifness"),
        (("pulleys", 1, "takeup"), "travel"),
        (("pulleys", 0, "friction"), "kinetik"),
        (("solver",), "dt"),
        (("recording",), "chanels"),
        (("idlers", 0), "raduis"),
    ],
)
def test_engine_and_python_readers_agree_on_unknown_keys(where, typo):
    d = everything().to_dict()
    target = d
    for k in where:
        target = target[k]
    target[typo] = 1.0
    assert engine_error(d) == python_error(d)


@settings(max_examples=80, deadline=None)
@given(st.sampled_from(sorted(Pulley().to_dict())), st.data())
def test_engine_suggestion_is_difflibs(key, data):
    """The Rust reader's "did you mean" (rust/src/suggest.rs) is difflib's choice."""
    i = data.draw(st.integers(0, len(key)))
    j = data.draw(st.integers(i, min(len(key), i + 3)))
    ins = data.draw(st.text(alphabet="abcdefghijklmnopqrstuvwxyz_", max_size=3))
    typo = key[:i] + ins + key[j:]
    known = list(Pulley().to_dict())
    if typo in known:
        return
    d = hustrulid_loop().to_dict()
    d["pulleys"][0][typo] = 1.0
    message = engine_error(d)
    assert message == unknown_key_message(f"pulleys[0].{typo}", typo, known)
    close = difflib.get_close_matches(typo, sorted(known), n=1)
    assert (f"did you mean {close[0]!r}?" in message) if close else ("did you mean" not in message)


def test_engine_checks_the_recording_table():
    d = hustrulid_loop().to_dict()
    d["recording"]["every"] = 10
    d["recording"]["interval"] = 0.01
    assert "recording.every = 10: give recording.interval (here 0.01) or recording.every, not both" in engine_error(d)
    scene = hustrulid_loop()
    scene.recording.channels = ("tension", "strain")
    with pytest.raises(SceneError, match=r'recording\.channels\[1\] = "strain": unknown channel \(known: tension'):
        beltrs.Simulation(scene)
    scene.recording = Recording(duration=-1.0)
    with pytest.raises(SceneError, match=r"recording\.duration = -1: must be ≥ 0"):
        beltrs.Simulation(scene)


def test_friction_model_none_refuses_coefficients():
    scene = hustrulid_loop(friction=Friction(static=0.5, model="none"))
    with pytest.raises(
        SceneError, match=r'pulleys\[0\]\.friction\.static = 0\.5: friction model "none" takes no coefficients'
    ):
        beltrs.Simulation(scene)
    # Without coefficients it is accepted and compiles no friction stage.
    sim = beltrs.Simulation(hustrulid_loop(friction=Friction(model="none")))
    assert not any("friction" in s for s in sim.stages)


def test_recording_run_kwargs():
    # No interval: Simulation.run's default (from the scene's wave physics, at most 0.01 s).
    assert Recording().run_kwargs() == dict(
        tension=True, node_position=True, node_velocity=True, contact_forces=False
    )
    assert Recording(every=5, channels=("tension", "contact_forces")).run_kwargs() == dict(
        tension=True, node_position=False, node_velocity=False, contact_forces=True, record_every=5
    )
    assert Recording(interval=0.5).run_kwargs()["record_interval"] == 0.5


def test_the_complete_example_in_the_docs():
    """docs/scene-format.md: its example loads, sets a key of every table, and runs."""
    doc = (Path(__file__).resolve().parent.parent / "docs" / "scene-format.md").read_text()
    text = doc.split("```toml\n", 1)[1].split("```", 1)[0]
    scene = Scene.from_toml(text)
    assert scene.pulleys[0].takeup and scene.pulleys[0].brake and scene.pulleys[1].drive and len(scene.idlers) == 6
    assert scene.pulleys[1].friction == Friction(0.35, 0.3) and scene.recording.channels == ("tension", "node_position")
    sim = beltrs.Simulation(scene)
    assert {"idler_contact", "drives", "brakes", "pulley_friction", "bending"} <= set(sim.stages)
    sim.step(300)
    assert all(np.all(np.isfinite(v)) for v in sim.state().values())
    # Every key the docs' tables list is a key of the format, and every key is listed.
    documented = {line.split("`")[1] for line in doc.splitlines() if line.startswith("| `")}
    keys = {"gravity"}
    for name in ("belt", "solver", "recording"):
        assert f"### `[{name}]`" in doc
    for name in ("pulleys", "idlers", "loads"):
        assert f"### `[[{name}]]`" in doc
    for obj in (Belt(), Pulley(), Friction(), Takeup(), Drive(), Brake(), Idler(), Load(), Solver(), Recording()):
        keys |= {f.name for f in dataclasses.fields(obj)}
    assert keys <= documented


def _doc_default(text: str):
    """A default as written in docs/scene-format.md, as a Python value (None for "—")."""
    import ast

    text = text.strip().strip("`").replace("−", "-")
    if text == "—":
        return None
    if "=" in text:  # "π/6 = 0.5235987755982988"
        text = text.split("=")[-1].strip()
    text = {"true": "True", "false": "False"}.get(text, text)
    text = text.replace("-inf", "-1e999").replace("inf", "1e999")
    return ast.literal_eval(text)


def test_every_key_of_every_table_has_unit_default_and_rule_in_the_docs():
    """docs/scene-format.md has one table per scene table (root, belt, pulleys, friction,
    takeup, drive, brake, idlers, solver, recording); each lists exactly the keys of that
    table, each with a unit, the default the code uses, and a rule."""
    doc = (Path(__file__).resolve().parent.parent / "docs" / "scene-format.md").read_text()
    keys_section = doc.split("## Keys", 1)[1].split("\n## ", 1)[0]
    sections: dict[str, dict[str, list[str]]] = {}
    title = None
    for line in keys_section.splitlines():
        if line.startswith("#"):
            title = line.lstrip("#").strip()
            sections[title] = {}
        elif line.startswith("| `") and title is not None:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            sections[title][cells[0].strip("`")] = cells[1:]
    # The keys and defaults are the engine's schema (rust/src/scene), the one source of both.
    engine = beltrs._beltrs.scene_defaults()
    tables = {
        "Root": ("scene", {"gravity"}),
        "`[belt]`": ("belt", None),
        "`start` and `end`": ("belt_end", None),
        "`[[pulleys]]`": ("pulley", None),
        "`friction`": ("friction", None),
        "`nonlinear_contact`": ("nonlinear_contact", None),
        "`takeup`": ("takeup", None),
        "`drive`": ("drive", None),
        "`start_curve`": ("start_curve", None),
        "`controller`": ("controller", None),
        "`follow`": ("follow", None),
        "`motor`": ("motor", None),
        "`coupling`": ("coupling", None),
        "`brake`": ("brake", None),
        "`holdback`": ("holdback", None),
        "`[[idlers]]`": ("idler", None),
        "`[[loads]]`": ("load", None),
        "`[solver]`": ("solver", None),
        "`[recording]`": ("recording", None),
        "`[initial]`": ("initial", None),
    }
    assert set(engine) == {t for t, _ in tables.values()}
    assert len(sections) == len(tables), list(sections)
    for prefix, (table, only) in tables.items():
        rows = next(rows for t, rows in sections.items() if t.startswith(prefix))
        fields = set(engine[table]) if only is None else only
        assert set(rows) == fields, (prefix, set(rows) ^ fields)
        for key, (unit, default, rule) in rows.items():
            where = f"{prefix} {key}"
            assert unit and default and len(rule) > 3, where
            value = engine[table][key]
            if isinstance(value, dict) or value is None and unit == "table":
                assert default == "—" and unit == "table", where  # a sub-table, absent by default
                continue
            documented = _doc_default(default)
            if isinstance(value, list):
                value, documented = tuple(value), tuple(documented)
            assert (
                documented == value
                and type(documented) is type(value)
                or (isinstance(value, float) and documented == value)
            ), (where, default, value)

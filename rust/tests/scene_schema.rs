//! The one scene schema (rust/src/scene): reading plain values strictly, with messages that
//! name the full path, the value and the rule; defaults from `Default`; the serde form
//! round-trips every bit (checkpoints store it).

use beltrs::presets::case_h;
use beltrs::scene::read::{from_value, python_float, Value};
use beltrs::scene::{FrictionModel, Scene, Wrap};

fn map(items: &[(&str, Value)]) -> Value {
    Value::Map(
        items
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect(),
    )
}

fn pulley(extra: &[(&str, Value)]) -> Value {
    let mut items = vec![(
        "center",
        Value::Seq(vec![Value::Float(0.0), Value::Int(100)]),
    )];
    items.extend_from_slice(extra);
    map(&items)
}

fn scene_with(pulleys: Vec<Value>) -> Value {
    map(&[("pulleys", Value::Seq(pulleys))])
}

fn error(v: &Value) -> String {
    from_value::<Scene>(v, "").unwrap_err().to_string()
}

#[test]
fn absent_keys_take_the_defaults() {
    let s: Scene = from_value(&scene_with(vec![pulley(&[])]), "").unwrap();
    let want = Scene {
        pulleys: vec![beltrs::scene::PulleySpec {
            center: [0.0, 100.0],
            ..Default::default()
        }],
        ..Default::default()
    };
    assert_eq!(s, want);
}

#[test]
fn unknown_keys_name_the_path_and_suggest() {
    let m = error(&scene_with(vec![pulley(&[("radious", Value::Float(5.0))])]));
    assert!(
        m.starts_with("pulleys[0].radious = 'radious': unknown key, did you mean 'radius'? (known keys here: bearing_damping, brake, center, "),
        "{m}"
    );
    let m = error(&map(&[("solver", map(&[("xyzzy", Value::Int(1))]))]));
    assert_eq!(
        m,
        "solver.xyzzy = 'xyzzy': unknown key (known keys here: absolute_tolerance, integrator, relative_tolerance, time_step, time_step_fraction)"
    );
}

#[test]
fn wrong_types_name_the_field_the_value_and_the_type() {
    let cases = [
        (
            map(&[("gravity", Value::Str("9.81".into()))]),
            "gravity = '9.81': expected a number",
        ),
        (
            map(&[("belt", map(&[("elements", Value::Float(89.0))]))]),
            "belt.elements = 89.0: expected a whole number",
        ),
        (
            map(&[("belt", map(&[("elements", Value::Int(-5))]))]),
            "belt.elements = -5: expected a whole number ≥ 0",
        ),
        (
            scene_with(vec![pulley(&[("mass", Value::Bool(true))])]),
            "pulleys[0].mass = True: expected a number",
        ),
        (
            scene_with(vec![map(&[(
                "center",
                Value::Seq(vec![
                    Value::Float(0.0),
                    Value::Float(1e16),
                    Value::Float(1.0),
                ]),
            )])]),
            "pulleys[0].center = [0.0, 1e+16, 1.0]: expected [x, y]",
        ),
        (
            scene_with(vec![pulley(&[(
                "takeup",
                map(&[("counterweight", Value::Null)]),
            )])]),
            "pulleys[0].takeup.counterweight = None: expected a number",
        ),
        (
            map(&[("belt", Value::Int(3))]),
            "belt = 3: expected a table",
        ),
        (
            map(&[("pulleys", Value::Int(5))]),
            "pulleys = 5: expected a list of tables",
        ),
        (
            scene_with(vec![pulley(&[("wrap", Value::Str("clockwise".into()))])]),
            "pulleys[0].wrap = \"clockwise\": expected \"ccw\" or \"cw\"",
        ),
        (
            scene_with(vec![pulley(&[("name", Value::Other("<object>".into()))])]),
            "pulleys[0].name = <object>: expected a string",
        ),
    ];
    for (value, want) in cases {
        assert_eq!(error(&value), want);
    }
}

#[test]
fn conversions_name_the_key_the_user_wrote() {
    let friction = |items: &[(&str, Value)]| scene_with(vec![pulley(&[("friction", map(items))])]);
    assert_eq!(
        error(&friction(&[
            ("model", Value::Str("none".into())),
            ("static", Value::Float(0.5))
        ])),
        "pulleys[0].friction.static = 0.5: friction model \"none\" takes no coefficients (use \"stick_force\")"
    );
    assert!(error(&friction(&[("model", Value::Str("stickforce".into()))]))
        .starts_with("pulleys[0].friction.model = \"stickforce\": unknown friction model, did you mean \"stick_force\"?"));
    let s: Scene = from_value(&friction(&[("static", Value::Float(0.3))]), "").unwrap();
    assert_eq!(
        s.pulleys[0].friction,
        FrictionModel::StickForce {
            static_coefficient: 0.3,
            kinetic_coefficient: 0.3
        }
    );
    let drive = |items: &[(&str, Value)]| scene_with(vec![pulley(&[("drive", map(items))])]);
    assert_eq!(
        error(&drive(&[("speed", Value::Seq(vec![Value::Float(1.0)]))])),
        "pulleys[0].drive.speed_factor = missing: needed with speed"
    );
    assert_eq!(
        error(&drive(&[(
            "start_curve",
            map(&[("ramp", Value::Float(1.0))])
        )])),
        "pulleys[0].drive.start_curve.speed = missing: required"
    );
    assert_eq!(
        error(&drive(&[(
            "start_curve",
            map(&[("ramp", Value::Float(1.0)), ("speed", Value::Null)])
        )])),
        "pulleys[0].drive.start_curve.speed = missing: required"
    );
}

#[test]
fn a_value_nested_too_deep_is_refused_by_name() {
    let mut v = Value::Float(1.0);
    for _ in 0..100 {
        v = Value::Seq(vec![v]);
    }
    let m = error(&map(&[("gravity", v)]));
    assert!(m.contains("nested deeper than any scene key"), "{m}");
}

#[test]
fn the_serde_form_round_trips_every_bit() {
    let mut s = case_h(89);
    s.pulleys[1].contact_damping = Some(-0.0);
    s.pulleys[0].wrap = Wrap::Clockwise;
    s.gravity = 0.1 + 0.2;
    let mut bytes = Vec::new();
    ciborium::into_writer(&s, &mut bytes).unwrap();
    let back: Scene = ciborium::from_reader(bytes.as_slice()).unwrap();
    assert_eq!(back, s);
    assert_eq!(
        back.pulleys[1].contact_damping.map(f64::to_bits),
        Some((-0.0f64).to_bits())
    );
    assert_eq!(back.gravity.to_bits(), (0.1f64 + 0.2).to_bits());
}

#[test]
fn python_float_text() {
    assert_eq!(python_float(1e-7), "1e-07");
    assert_eq!(python_float(123.0), "123.0");
}

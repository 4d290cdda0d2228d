//! The `[recording]` table of a scene file: defaults and the rules of each field.

use beltrs::scene::{RecordingParams, DEFAULT_RECORDING_CHANNELS, RECORDING_CHANNELS};
use beltrs::BeltError;

fn rule_of(p: &RecordingParams) -> String {
    match p.validate() {
        Err(BeltError::InvalidParameter { field, rule, .. }) => format!("{field}: {rule}"),
        other => panic!("expected an invalid parameter, got {other:?}"),
    }
}

#[test]
fn defaults_are_valid_and_record_every_channel_but_the_contact_forces() {
    let p = RecordingParams::default();
    p.validate().unwrap();
    assert_eq!(p.duration, 1.0);
    assert_eq!(p.channels, DEFAULT_RECORDING_CHANNELS.to_vec());
    assert_eq!(RECORDING_CHANNELS[..3], DEFAULT_RECORDING_CHANNELS);
    assert_eq!(RECORDING_CHANNELS[3], "contact_forces");
    // Opting in is valid.
    RecordingParams {
        channels: vec!["tension".into(), "contact_forces".into()],
        ..p
    }
    .validate()
    .unwrap();
    assert!(p.stabilise && !p.stabilise_friction);
}

#[test]
fn each_rule_names_its_field() {
    let base = RecordingParams::default();
    let cases = [
        (
            RecordingParams {
                duration: -1.0,
                ..base.clone()
            },
            "recording.duration: must be ≥ 0",
        ),
        (
            RecordingParams {
                duration: f64::INFINITY,
                ..base.clone()
            },
            "recording.duration: must be a finite number",
        ),
        (
            RecordingParams {
                interval: Some(0.0),
                ..base.clone()
            },
            "recording.interval: must be > 0",
        ),
        (
            RecordingParams {
                every: Some(0),
                ..base.clone()
            },
            "recording.every: must be ≥ 1",
        ),
        (
            RecordingParams {
                every: Some(10),
                interval: Some(0.01),
                ..base.clone()
            },
            "recording.every: give recording.interval (here 0.01) or recording.every, not both",
        ),
        (
            RecordingParams {
                stabilise: false,
                stabilise_friction: true,
                ..base.clone()
            },
            "recording.stabilise_friction: has no effect with recording.stabilise = false (set both, or neither)",
        ),
        (
            RecordingParams {
                channels: vec!["tension".into(), "tension".into()],
                ..base.clone()
            },
            "recording.channels[1]: listed twice",
        ),
        (
            RecordingParams {
                channels: vec!["node_positions".into()],
                ..base.clone()
            },
            "recording.channels[0]: unknown channel, did you mean \"node_position\"? \
             (known: tension, node_position, node_velocity, contact_forces)",
        ),
    ];
    for (p, want) in cases {
        assert_eq!(rule_of(&p), want);
    }
}

//! Issue 11, "right at default settings": contact damping as a ratio of critical (and its
//! absolute form), and the placement-strain rule.

use crate::common::case_h;
use beltrs::error::BeltError;
use beltrs::model::Model;
use beltrs::scene::{contact_damping, IdlerSpec, DEFAULT_CONTACT_DAMPING_RATIO};

fn field_of(err: BeltError) -> (String, String) {
    match err {
        BeltError::InvalidParameter { field, rule, .. } => (field, rule),
        other => panic!("expected InvalidParameter, got {other:?}"),
    }
}

#[test]
fn contact_damping_ratio_is_of_the_node_critical_damping() {
    let (k, m): (f64, f64) = (1e9, 8.1e-4);
    let critical = 2.0 * (k * m).sqrt();
    assert_eq!(
        contact_damping(None, None, k, m),
        DEFAULT_CONTACT_DAMPING_RATIO * critical
    );
    assert_eq!(contact_damping(None, Some(0.5), k, m), 0.5 * critical);
    assert_eq!(contact_damping(None, Some(0.0), k, m), 0.0);
    // The absolute form is taken as given.
    assert_eq!(contact_damping(Some(123.0), None, k, m), 123.0);
    assert_eq!(contact_damping(Some(0.0), None, k, m), 0.0);
}

#[test]
fn compiled_pulleys_and_idlers_get_the_default_ratio() {
    let mut scene = case_h(89);
    scene.pulleys[1].contact_damping_ratio = Some(0.5);
    scene.pulleys[0].contact_damping = Some(7.0);
    scene.idlers.push(IdlerSpec {
        center: [5.0 + 0.0635 + 0.01, 50.0],
        ..IdlerSpec::default()
    });
    let model = Model::compile(&scene).unwrap();
    let m_node = model.mass[0];
    let belt = &scene.belt;
    let length = belt.length.unwrap_or(model.path.length);
    assert!((m_node - belt.mass_per_length * length / model.nodes as f64).abs() < 1e-12 * m_node);
    let p = &model.pulleys[1];
    assert_eq!(
        p.contact_damping,
        2.0 * 0.5 * (p.contact_stiffness * m_node).sqrt()
    );
    assert_eq!(model.pulleys[0].contact_damping, 7.0);
    let d = &model.idlers[0];
    assert_eq!(
        d.contact_damping,
        2.0 * DEFAULT_CONTACT_DAMPING_RATIO * (d.contact_stiffness * m_node).sqrt()
    );
}

#[test]
fn contact_damping_in_both_forms_is_refused() {
    let mut scene = case_h(89);
    scene.pulleys[0].contact_damping = Some(10.0);
    scene.pulleys[0].contact_damping_ratio = Some(0.3);
    let (field, rule) = field_of(Model::compile(&scene).unwrap_err());
    assert_eq!(field, "pulleys[0].contact_damping");
    assert!(rule.contains("not both"), "{rule}");

    let mut scene = case_h(89);
    scene.pulleys[1].contact_damping_ratio = Some(-0.1);
    let (field, _) = field_of(Model::compile(&scene).unwrap_err());
    assert_eq!(field, "pulleys[1].contact_damping_ratio");

    let mut scene = case_h(89);
    scene.idlers.push(IdlerSpec {
        center: [5.0 + 0.0635 + 0.01, 50.0],
        contact_damping_ratio: Some(f64::NAN),
        ..IdlerSpec::default()
    });
    let (field, _) = field_of(Model::compile(&scene).unwrap_err());
    assert_eq!(field, "idlers[0].contact_damping_ratio");
}

/// The literature's benchmark drives are pre-strained 5.26 %: accepted by default; a
/// belt 12 % short is refused naming the rule, and accepted once the limit is raised.
#[test]
fn placement_strain_is_a_documented_overridable_rule() {
    let path = case_h(89);
    let path_length = Model::compile(&path).unwrap().path.length;
    let with_strain = |strain: f64| {
        let mut s = case_h(89);
        s.belt.length = Some(path_length / (1.0 + strain));
        s
    };
    assert!(Model::compile(&with_strain(0.0526)).is_ok());
    let (field, rule) = field_of(Model::compile(&with_strain(0.12)).unwrap_err());
    assert_eq!(field, "belt.length");
    assert!(rule.contains("belt.max_placement_strain = 10 %"), "{rule}");
    let mut raised = with_strain(0.12);
    raised.belt.max_placement_strain = 0.15;
    assert!(Model::compile(&raised).is_ok());
    let mut bad = case_h(89);
    bad.belt.max_placement_strain = 0.0;
    let (field, _) = field_of(Model::compile(&bad).unwrap_err());
    assert_eq!(field, "belt.max_placement_strain");
}

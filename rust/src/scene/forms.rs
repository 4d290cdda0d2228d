//! The serde form of the few scene parts whose keys differ from the engine's types: the
//! `friction` table (absent for none; `kinetic` defaults to `static`), a drive's and a
//! brake's tables (`time`/`torque`, `speed`/`speed_factor`, `time`/`capacity`), and the
//! names of enums (`wrap = "ccw"`). Each conversion is written once, here; its errors use
//! [`rule`] so that they name the key the user wrote.

use super::read::rule;
use super::{
    BrakeSpec, CreepFriction, Formulation, FrictionModel, IdlerContactKind, IntegratorKind,
    PulleyContact, Table, TakeupKind, Wrap,
};
use crate::start_curve::StartShape;
use crate::suggest::close_match;
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;
use std::marker::PhantomData;

/// An enum written in a scene as one of a few names.
pub(crate) trait Named: Sized + Copy + 'static {
    /// Every value with its name.
    const NAMES: &'static [(Self, &'static str)];
    /// What a value of the wrong type is told to be, e.g. `"ccw" or "cw"`.
    fn expected() -> String {
        let names: Vec<String> = Self::NAMES.iter().map(|(_, n)| format!("{n:?}")).collect();
        format!("one of {}", names.join(", "))
    }
    /// The rule broken by an unknown name.
    fn unknown(name: &str) -> String;
    /// The scene name of `self`.
    fn scene_name(self) -> &'static str
    where
        Self: PartialEq,
    {
        Self::NAMES
            .iter()
            .find(|(v, _)| *v == self)
            .map(|(_, n)| *n)
            .unwrap_or("?")
    }
}

/// `unknown {what}, did you mean "x"? (known: "a", "b")`.
fn unknown_name(what: &str, name: &str, known: &[&str]) -> String {
    let hint = match close_match(name, known.iter().copied()) {
        Some(s) => format!(", did you mean \"{s}\"?"),
        None => String::new(),
    };
    let list: Vec<String> = known.iter().map(|n| format!("{n:?}")).collect();
    format!("unknown {what}{hint} (known: {})", list.join(", "))
}

struct NameVisitor<T>(PhantomData<T>);

impl<T: Named> Visitor<'_> for NameVisitor<T> {
    type Value = T;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(&T::expected())
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<T, E> {
        T::NAMES
            .iter()
            .find(|(_, n)| *n == v)
            .map(|(t, _)| *t)
            .ok_or_else(|| E::custom(rule("", format!("{v:?}"), T::unknown(v))))
    }
}

macro_rules! named_serde {
    ($ty:ty) => {
        impl Serialize for $ty {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(Named::scene_name(*self))
            }
        }
        impl<'de> Deserialize<'de> for $ty {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                d.deserialize_str(NameVisitor::<$ty>(PhantomData))
            }
        }
    };
}

impl Named for Formulation {
    const NAMES: &'static [(Self, &'static str)] = &[
        (Formulation::NodeKelvinVoigt, "node_kelvin_voigt"),
        (Formulation::RigidBody, "rigid_body"),
    ];
    fn unknown(name: &str) -> String {
        unknown_name(
            "belt formulation",
            name,
            &["node_kelvin_voigt", "rigid_body"],
        )
    }
}
named_serde!(Formulation);

impl Named for PulleyContact {
    const NAMES: &'static [(Self, &'static str)] = &[
        (PulleyContact::Nodes, "nodes"),
        (PulleyContact::Wrap, "wrap"),
    ];
    fn expected() -> String {
        "\"nodes\" or \"wrap\"".into()
    }
    fn unknown(_: &str) -> String {
        format!("unknown pulley contact (known: {})", Self::expected())
    }
}
named_serde!(PulleyContact);

impl Named for IdlerContactKind {
    const NAMES: &'static [(Self, &'static str)] = &[
        (IdlerContactKind::Segment, "segment"),
        (IdlerContactKind::Wrap, "wrap"),
    ];
    fn expected() -> String {
        "\"segment\" or \"wrap\"".into()
    }
    fn unknown(_: &str) -> String {
        format!("unknown idler contact (known: {})", Self::expected())
    }
}
named_serde!(IdlerContactKind);
impl Named for IntegratorKind {
    const NAMES: &'static [(Self, &'static str)] = &[
        (IntegratorKind::CentralDifference, "central_difference"),
        (IntegratorKind::Rkf45, "rkf45"),
    ];
    fn unknown(name: &str) -> String {
        unknown_name("integrator", name, &["central_difference", "rkf45"])
    }
}
named_serde!(IntegratorKind);

impl Named for Wrap {
    const NAMES: &'static [(Self, &'static str)] =
        &[(Wrap::CounterClockwise, "ccw"), (Wrap::Clockwise, "cw")];
    fn expected() -> String {
        "\"ccw\" or \"cw\"".into()
    }
    fn unknown(_: &str) -> String {
        format!("expected {}", Self::expected())
    }
}
named_serde!(Wrap);

impl Named for super::EndHold {
    const NAMES: &'static [(Self, &'static str)] = &[
        (super::EndHold::Anchor, "anchor"),
        (super::EndHold::Force, "force"),
        (super::EndHold::Mass, "mass"),
    ];
    fn unknown(name: &str) -> String {
        unknown_name("hold of a belt end", name, &["anchor", "force", "mass"])
    }
}
named_serde!(super::EndHold);

impl Named for StartShape {
    const NAMES: &'static [(Self, &'static str)] = &[
        (StartShape::Harrison, "harrison"),
        (StartShape::Nordell, "nordell"),
        (StartShape::Cubic, "cubic"),
        (StartShape::Linear, "linear"),
    ];
    fn unknown(name: &str) -> String {
        unknown_name("starting curve", name, &StartShape::NAMES)
    }
}
named_serde!(StartShape);

impl Named for TakeupKind {
    const NAMES: &'static [(Self, &'static str)] = &[
        (TakeupKind::Gravity, "gravity"),
        (TakeupKind::Fixed, "fixed"),
        (TakeupKind::Winch, "winch"),
    ];
    fn unknown(name: &str) -> String {
        unknown_name("takeup kind", name, &["gravity", "fixed", "winch"])
    }
}
named_serde!(TakeupKind);

/// The friction model named in a scene's `friction` table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrictionKind {
    /// `"none"`: no friction (no coefficients allowed).
    None,
    /// `"stick_force"`: stick-force friction (thesis eq. 4.76–4.94).
    #[default]
    StickForce,
    /// `"creep"`: Kubas's creep-rate friction (eq. 12–19), `crate::friction::creep`.
    Creep,
}

impl Named for FrictionKind {
    const NAMES: &'static [(Self, &'static str)] = &[
        (FrictionKind::None, "none"),
        (FrictionKind::StickForce, "stick_force"),
        (FrictionKind::Creep, "creep"),
    ];
    fn unknown(name: &str) -> String {
        unknown_name("friction model", name, &["none", "stick_force", "creep"])
    }
}
named_serde!(FrictionKind);

/// The `friction` table of a pulley or idler; absent (or `None`) means frictionless.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FrictionKeys {
    /// Friction model. Default `"stick_force"`.
    pub model: FrictionKind,
    /// Static coefficient µs, dimensionless, ≥ `kinetic`. Default 0.
    #[serde(rename = "static")]
    pub static_coefficient: f64,
    /// Kinetic coefficient µk, dimensionless. `None`: equal to `static`. Default `None`.
    pub kinetic: Option<f64>,
    /// Creep model only: Δv, the relative speed up to which the contact creeps (µ rises
    /// to µs; µk from 1.5·Δv), m/s, > 0. `None`:
    /// [`crate::friction::creep::DEFAULT_TRANSITION_SPEED`] (10⁻³ m/s). Default `None`.
    pub transition_speed: Option<f64>,
    /// Creep model only: Δmax, the creep displacement at which the creep part of µ
    /// reaches µs, m, > 0. `None`: [`crate::friction::creep::DEFAULT_CREEP_LIMIT`]
    /// (10⁻⁴ m). Default `None`.
    pub creep_limit: Option<f64>,
}

impl Default for FrictionKeys {
    fn default() -> Self {
        FrictionKeys {
            model: FrictionKind::StickForce,
            static_coefficient: 0.0,
            kinetic: None,
            transition_speed: None,
            creep_limit: None,
        }
    }
}

impl TryFrom<FrictionKeys> for FrictionModel {
    type Error = String;
    fn try_from(k: FrictionKeys) -> Result<Self, String> {
        if k.model != FrictionKind::Creep {
            // Creep parameters with another model would be silently ignored.
            let creep = [
                ("transition_speed", k.transition_speed),
                ("creep_limit", k.creep_limit),
            ];
            if let Some((key, Some(v))) = creep.iter().find(|(_, v)| v.is_some()) {
                return Err(rule(
                    &format!(".{key}"),
                    v,
                    format!(
                        "belongs to the creep friction model only (model = \"creep\"; here \"{}\")",
                        k.model.scene_name()
                    ),
                ));
            }
        }
        match k.model {
            FrictionKind::None => {
                // Coefficients with no friction model would be silently ignored.
                let given = [
                    ("static", Some(k.static_coefficient)),
                    ("kinetic", k.kinetic),
                ];
                if let Some((key, Some(v))) =
                    given.iter().find(|(_, v)| v.is_some_and(|v| v != 0.0))
                {
                    return Err(rule(
                        &format!(".{key}"),
                        v,
                        "friction model \"none\" takes no coefficients (use \"stick_force\" or \"creep\")",
                    ));
                }
                Ok(FrictionModel::None)
            }
            FrictionKind::StickForce => Ok(FrictionModel::StickForce {
                static_coefficient: k.static_coefficient,
                kinetic_coefficient: k.kinetic.unwrap_or(k.static_coefficient),
            }),
            FrictionKind::Creep => Ok(FrictionModel::Creep(CreepFriction {
                static_coefficient: k.static_coefficient,
                kinetic_coefficient: k.kinetic.unwrap_or(k.static_coefficient),
                transition_speed: k
                    .transition_speed
                    .unwrap_or(crate::friction::creep::DEFAULT_TRANSITION_SPEED),
                creep_limit: k
                    .creep_limit
                    .unwrap_or(crate::friction::creep::DEFAULT_CREEP_LIMIT),
            })),
        }
    }
}

/// `#[serde(with)]` for a [`FrictionModel`] field: the `friction` table, or none.
pub(crate) mod friction {
    use super::*;

    pub fn serialize<S: Serializer>(f: &FrictionModel, s: S) -> Result<S::Ok, S::Error> {
        let keys = match *f {
            FrictionModel::None => None,
            FrictionModel::StickForce {
                static_coefficient,
                kinetic_coefficient,
            } => Some(FrictionKeys {
                model: FrictionKind::StickForce,
                static_coefficient,
                kinetic: Some(kinetic_coefficient),
                ..FrictionKeys::default()
            }),
            FrictionModel::Creep(c) => Some(FrictionKeys {
                model: FrictionKind::Creep,
                static_coefficient: c.static_coefficient,
                kinetic: Some(c.kinetic_coefficient),
                transition_speed: Some(c.transition_speed),
                creep_limit: Some(c.creep_limit),
            }),
        };
        keys.serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<FrictionModel, D::Error> {
        match Option::<FrictionKeys>::deserialize(d)? {
            None => Ok(FrictionModel::None),
            Some(k) => FrictionModel::try_from(k).map_err(de::Error::custom),
        }
    }
}

/// A list whose wrong-type message says what it holds ("a list of tables").
struct ListVisitor<T> {
    what: &'static str,
    item: PhantomData<T>,
}

impl<'de, T: Deserialize<'de>> Visitor<'de> for ListVisitor<T> {
    type Value = Vec<T>;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.what)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
        let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(1 << 16));
        while let Some(item) = seq.next_element()? {
            out.push(item);
        }
        Ok(out)
    }
}

fn list<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    d: D,
    what: &'static str,
) -> Result<Vec<T>, D::Error> {
    d.deserialize_seq(ListVisitor {
        what,
        item: PhantomData,
    })
}

/// `deserialize_with` for a list of tables (`pulleys`, `idlers`, `loads`).
pub(crate) fn tables<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    d: D,
) -> Result<Vec<T>, D::Error> {
    list(d, "a list of tables")
}

/// `deserialize_with` for a list of strings (`recording.channels`).
pub(crate) fn strings<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<String>, D::Error> {
    list(d, "a list of strings")
}

/// A list of numbers (one column of a drive's or brake's table).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
#[serde(transparent)]
pub struct Numbers(pub Vec<f64>);

impl<'de> Deserialize<'de> for Numbers {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        list(d, "a list of numbers").map(Numbers)
    }
}

/// A table from its two columns as given (`None`: the key is absent or `None`): both, or
/// the ordinates alone when they hold one value (a constant, abscissa 0).
pub(super) fn table(
    (xkey, x): (&str, Option<Numbers>),
    (ykey, y): (&str, Option<Numbers>),
) -> Result<Option<Table>, String> {
    match (x, y) {
        (None, None) => Ok(None),
        (Some(x), Some(y)) => Ok(Some(Table { x: x.0, y: y.0 })),
        (Some(_), None) => Err(rule(
            &format!(".{ykey}"),
            "missing",
            format!("needed with {xkey}"),
        )),
        (None, Some(y)) if y.0.len() == 1 => Ok(Some(Table {
            x: vec![0.0],
            y: y.0,
        })),
        (None, Some(_)) => Err(rule(
            &format!(".{xkey}"),
            "missing",
            format!("needed with {ykey}"),
        )),
    }
}

pub(super) fn columns(t: &Table) -> (Option<Numbers>, Option<Numbers>) {
    if t.x.is_empty() && t.y.is_empty() {
        (None, None)
    } else {
        (Some(Numbers(t.x.clone())), Some(Numbers(t.y.clone())))
    }
}

/// Declares [`DriveSpec`] and its scene form [`DriveKeys`] from one list of the keys they
/// share (every key but the two tables), with the conversions between them, so that a
/// new drive key is declared once (in `scene/mod.rs`). `#[serde(flatten)]` cannot share
/// them: it does not work with `deny_unknown_fields` (a misspelt key would pass silently),
/// and serde reads flattened keys from its own buffer, past the scene reader, whose
/// messages name the path and suggest the key.
macro_rules! drive_forms {
    (
        $(#[$spec_meta:meta])*
        pub struct DriveSpec {
            $(#[$torque_meta:meta])*
            pub torque: Table,
            $(#[$factor_meta:meta])*
            pub speed_factor: Table,
            $(
                $(#[$meta:meta])*
                pub $field:ident: $ty:ty,
            )*
        }
    ) => {
        $(#[$spec_meta])*
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
        #[serde(into = "DriveKeys", try_from = "DriveKeys")]
        pub struct DriveSpec {
            $(#[$torque_meta])*
            pub torque: Table,
            $(#[$factor_meta])*
            pub speed_factor: Table,
            $(
                $(#[$meta])*
                pub $field: $ty,
            )*
        }

        /// The `drive` table of a pulley, as written in a scene ([`DriveSpec`] in the
        /// engine): its two tables as their columns, every other key as in [`DriveSpec`].
        /// Defaults: those of [`DriveSpec::default`].
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
        #[serde(default, deny_unknown_fields)]
        pub struct DriveKeys {
            /// Abscissae of f, s, strictly increasing.
            pub time: Option<forms::Numbers>,
            /// f(t), N·m.
            pub torque: Option<forms::Numbers>,
            /// Abscissae of g, rad/s. `None`: g = 1.
            pub speed: Option<forms::Numbers>,
            /// g(ω), dimensionless.
            pub speed_factor: Option<forms::Numbers>,
            $(
                $(#[$meta])*
                pub $field: $ty,
            )*
        }

        impl Default for DriveKeys {
            fn default() -> Self {
                DriveSpec::default().into()
            }
        }

        impl From<DriveSpec> for DriveKeys {
            fn from(d: DriveSpec) -> Self {
                let (time, torque) = forms::columns(&d.torque);
                let (speed, speed_factor) = forms::columns(&d.speed_factor);
                DriveKeys {
                    time,
                    torque,
                    speed,
                    speed_factor,
                    $($field: d.$field,)*
                }
            }
        }

        impl TryFrom<DriveKeys> for DriveSpec {
            type Error = String;
            fn try_from(k: DriveKeys) -> Result<Self, String> {
                let d = DriveSpec::default();
                Ok(DriveSpec {
                    torque: forms::table(("time", k.time), ("torque", k.torque))?
                        .unwrap_or(d.torque),
                    speed_factor: forms::table(
                        ("speed", k.speed),
                        ("speed_factor", k.speed_factor),
                    )?
                    .unwrap_or_default(),
                    $($field: k.$field,)*
                })
            }
        }
    };
}
pub(super) use drive_forms;

/// The `brake` table of a pulley, as written in a scene ([`BrakeSpec`] in the engine).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BrakeKeys {
    /// Abscissae, s.
    pub time: Option<Numbers>,
    /// Capacity, N·m, ≥ 0.
    pub capacity: Option<Numbers>,
    /// Braking torque from `applied` on, N·m.
    pub torque: Option<f64>,
    /// Deceleration target, m/s².
    pub deceleration: Option<f64>,
    /// Time the brake is applied, s.
    pub applied: f64,
    /// Build-up time of the torque, s.
    pub rise: f64,
}

impl Default for BrakeKeys {
    fn default() -> Self {
        BrakeSpec::default().into()
    }
}

impl From<BrakeSpec> for BrakeKeys {
    fn from(b: BrakeSpec) -> Self {
        let (time, capacity) = columns(&b.capacity);
        BrakeKeys {
            time,
            capacity,
            torque: b.torque,
            deceleration: b.deceleration,
            applied: b.applied,
            rise: b.rise,
        }
    }
}

impl TryFrom<BrakeKeys> for BrakeSpec {
    type Error = String;
    fn try_from(k: BrakeKeys) -> Result<Self, String> {
        Ok(BrakeSpec {
            capacity: table(("time", k.time), ("capacity", k.capacity))?
                .unwrap_or_else(|| Table::constant(0.0)),
            torque: k.torque,
            deceleration: k.deceleration,
            applied: k.applied,
            rise: k.rise,
        })
    }
}

/// `deserialize_with` for a number without a default: absent or `None` is "missing: required".
pub(crate) fn required<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Option::<f64>::deserialize(d)?.ok_or_else(|| de::Error::custom(rule("", "missing", "required")))
}

//! The one error type of the core. Every message names the offending field, its value and
//! the rule it breaks, so that a user can find the line of the scene to change.

use thiserror::Error;

/// Errors raised by scene validation, compilation and time stepping.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BeltError {
    /// A scene parameter is out of range, non-finite, or inconsistent with another one.
    #[error("{field} = {value}: {rule}")]
    InvalidParameter {
        /// Dotted path of the field, e.g. `pulleys[1].radius`.
        field: String,
        /// The offending value as the user gave it.
        value: String,
        /// The rule it breaks.
        rule: String,
    },
    /// A requested time step is above the explicit stability limit.
    #[error("solver.time_step = {requested} s exceeds the stability limit {limit} s ({cause})")]
    TimeStepTooLarge {
        /// The step the user asked for, s.
        requested: f64,
        /// The estimated critical step, s.
        limit: f64,
        /// The stiffest term, e.g. "pulley contact at node 12".
        cause: String,
    },
    /// The state became non-finite during a run.
    #[error("the state became non-finite at t = {time} s (step {step}): {quantity} of {location}")]
    Diverged {
        /// Simulated time at which the non-finite value was found, s.
        time: f64,
        /// Step counter at that time.
        step: u64,
        /// What became non-finite, e.g. "position x".
        quantity: String,
        /// Where, e.g. "node 17" or "pulley 0".
        location: String,
    },
    /// A checkpoint file cannot be written, read or resumed (missing, corrupt, truncated,
    /// another format version, or another scene).
    #[error("checkpoint {path}: {problem}")]
    Checkpoint {
        /// The file.
        path: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A request that does not fit the compiled model (e.g. an unknown pulley index).
    #[error("{0}")]
    Usage(String),
    /// The caller's interrupt hook asked to stop ([`crate::interrupt`]); the state is
    /// consistent (whole steps only).
    #[error("interrupted")]
    Interrupted,
}

/// Shorthand result type.
pub type BeltResult<T> = Result<T, BeltError>;

impl BeltError {
    /// Build an [`BeltError::InvalidParameter`] from anything printable.
    pub fn invalid(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        rule: impl Into<String>,
    ) -> Self {
        BeltError::InvalidParameter {
            field: field.into(),
            value: value.to_string(),
            rule: rule.into(),
        }
    }
}

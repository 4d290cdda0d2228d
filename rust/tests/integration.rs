//! Rust integration tests: kernels and reference cases, without Python.
#![allow(clippy::needless_range_loop)]
mod common;

mod belt_drive_defaults;
mod case_h_statics;
mod checkpoint;
mod friction_contact;
mod kernels;
mod load_resistance;
mod recorder;
mod recording_params;
mod speed_drive;

//! Rust integration tests: kernels and reference cases, without Python.
#![allow(clippy::needless_range_loop)]
mod common;

mod bearing_drag;
mod belt_drive_defaults;
mod case_h_statics;
mod checkpoint;
mod contact_forces;
mod creep_friction;
mod friction_contact;
mod kernels;
mod kubas_kernels;
mod kubas_prototype;
mod load_resistance;
mod motor_start;
mod open_belts;
mod recorder;
mod recording_params;
mod relax_hold;
mod rigid_body;
mod rigid_wrap;
mod rkf45;
mod roll_wrap;
mod run_contract;
mod scene_schema;
mod speed_control;
mod speed_drive;
mod stops;
mod wrap_contact;
mod zener;

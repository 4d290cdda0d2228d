//! Integrators.
//!
//! - [`rkf45`]: adaptive Runge–Kutta–Fehlberg 4(5) over a flat state vector and a
//!   derivative callback (Kubas 2014's integrator).

pub mod rkf45;

//! What the explicit embedded Runge–Kutta methods (DOPRI5, DOP853) share of
//! Hairer's codes around their stages: the step-size loop ([`stepping`]), its
//! PI controller ([`controller`]) and the stiffness test ([`stiffness`]).

mod controller;
mod stepping;
mod stiffness;

pub(crate) use controller::PiController;
pub(crate) use stepping::{Stepping, first_step};
pub(crate) use stiffness::StiffnessTest;

//! Floating-base trees: a quadruped (a trunk on a free joint, four legs of
//! three joints), a satellite carrying a six-joint arm and a hub with a
//! two-joint arm (included by path
//! where used, not by the catalog's `mod.rs`, so the gallery does not build
//! them). Both are the
//! recursive route's floating bases (three sliding joints and a spherical one
//! at the root), checked against Pinocchio's free flyer in
//! `tests/floating_bases.rs` and timed beside it in `lagrange-bench`'s `free`
//! bench; the Pinocchio models are `lagrange-bench/peer/pinocchio/floating.py`
//! and `floating.cpp`.

#![allow(dead_code)]

use lagrange::Lagrangian;

/// A quadruped-like body: a 12 kg trunk, and per leg an abduction joint
/// (about x) at the hip, a hip joint (about y) and a knee (about y) 0.2 m
/// below; nv = 18, nq = 19.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z, a_fl, h_fl, k_fl, a_fr, h_fr, k_fr, a_hl, h_hl, k_hl, a_hr, h_hr, k_hr),
    orientation(base),
    body(trunk, mass = 12.0, inertia = [0.12, 0.35, 0.40], at = [x, y, z], rotation = base),
    point(hip_fl, on = trunk, at = [0.25, 0.12, 0]),
    body(pelvis_fl, mass = 0.6, inertia = [0.0008, 0.0012, 0.0010], com = [0, 0.03, 0],
         at = [hip_fl.x, hip_fl.y, hip_fl.z], rotation = base * rot_x(a_fl)),
    body(thigh_fl, mass = 1.0, inertia = [0.010, 0.011, 0.002], com = [0, 0, -0.1],
         at = [hip_fl.x, hip_fl.y, hip_fl.z], rotation = base * rot_x(a_fl) * rot_y(h_fl)),
    point(knee_fl, on = thigh_fl, at = [0, 0, -0.2]),
    body(shank_fl, mass = 0.3, inertia = [0.004, 0.004, 0.0004], com = [0, 0, -0.1],
         at = [knee_fl.x, knee_fl.y, knee_fl.z], rotation = base * rot_x(a_fl) * rot_y(h_fl) * rot_y(k_fl)),
    point(hip_fr, on = trunk, at = [0.25, -0.12, 0]),
    body(pelvis_fr, mass = 0.6, inertia = [0.0008, 0.0012, 0.0010], com = [0, -0.03, 0],
         at = [hip_fr.x, hip_fr.y, hip_fr.z], rotation = base * rot_x(a_fr)),
    body(thigh_fr, mass = 1.0, inertia = [0.010, 0.011, 0.002], com = [0, 0, -0.1],
         at = [hip_fr.x, hip_fr.y, hip_fr.z], rotation = base * rot_x(a_fr) * rot_y(h_fr)),
    point(knee_fr, on = thigh_fr, at = [0, 0, -0.2]),
    body(shank_fr, mass = 0.3, inertia = [0.004, 0.004, 0.0004], com = [0, 0, -0.1],
         at = [knee_fr.x, knee_fr.y, knee_fr.z], rotation = base * rot_x(a_fr) * rot_y(h_fr) * rot_y(k_fr)),
    point(hip_hl, on = trunk, at = [-0.25, 0.12, 0]),
    body(pelvis_hl, mass = 0.6, inertia = [0.0008, 0.0012, 0.0010], com = [0, 0.03, 0],
         at = [hip_hl.x, hip_hl.y, hip_hl.z], rotation = base * rot_x(a_hl)),
    body(thigh_hl, mass = 1.0, inertia = [0.010, 0.011, 0.002], com = [0, 0, -0.1],
         at = [hip_hl.x, hip_hl.y, hip_hl.z], rotation = base * rot_x(a_hl) * rot_y(h_hl)),
    point(knee_hl, on = thigh_hl, at = [0, 0, -0.2]),
    body(shank_hl, mass = 0.3, inertia = [0.004, 0.004, 0.0004], com = [0, 0, -0.1],
         at = [knee_hl.x, knee_hl.y, knee_hl.z], rotation = base * rot_x(a_hl) * rot_y(h_hl) * rot_y(k_hl)),
    point(hip_hr, on = trunk, at = [-0.25, -0.12, 0]),
    body(pelvis_hr, mass = 0.6, inertia = [0.0008, 0.0012, 0.0010], com = [0, -0.03, 0],
         at = [hip_hr.x, hip_hr.y, hip_hr.z], rotation = base * rot_x(a_hr)),
    body(thigh_hr, mass = 1.0, inertia = [0.010, 0.011, 0.002], com = [0, 0, -0.1],
         at = [hip_hr.x, hip_hr.y, hip_hr.z], rotation = base * rot_x(a_hr) * rot_y(h_hr)),
    point(knee_hr, on = thigh_hr, at = [0, 0, -0.2]),
    body(shank_hr, mass = 0.3, inertia = [0.004, 0.004, 0.0004], com = [0, 0, -0.1],
         at = [knee_hr.x, knee_hr.y, knee_hr.z], rotation = base * rot_x(a_hr) * rot_y(h_hr) * rot_y(k_hr)),
    gravity = [0, 0, -g],
    emit(articulated, inverse_dynamics, jacobians),
)]
pub struct Quadruped {
    pub g: f64,
}

/// A 100 kg satellite bus on a free joint with a six-joint arm (axes z, y,
/// y, x, y, x) mounted at (0.6, 0, 0.4), tilted by 0.3 rad about x; nv = 12,
/// nq = 13.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z, j1, j2, j3, j4, j5, j6),
    orientation(base),
    body(bus, mass = 100.0, inertia = [10.0, 12.0, 9.0], at = [x, y, z], rotation = base),
    point(mount, on = bus, at = [0.6, 0, 0.4]),
    body(link1, mass = 4.0, inertia = [0.05, 0.05, 0.02], com = [0, 0, 0.1],
         at = [mount.x, mount.y, mount.z], rotation = base * rot_x(0.3) * rot_z(j1)),
    point(shoulder, on = link1, at = [0, 0, 0.2]),
    body(link2, mass = 3.0, inertia = [0.01, 0.08, 0.08], com = [0.25, 0, 0],
         at = [shoulder.x, shoulder.y, shoulder.z],
         rotation = base * rot_x(0.3) * rot_z(j1) * rot_y(j2)),
    point(elbow, on = link2, at = [0.5, 0, 0]),
    body(link3, mass = 2.0, inertia = [0.005, 0.05, 0.05], com = [0.2, 0, 0],
         at = [elbow.x, elbow.y, elbow.z],
         rotation = base * rot_x(0.3) * rot_z(j1) * rot_y(j2) * rot_y(j3)),
    point(wrist, on = link3, at = [0.4, 0, 0]),
    body(link4, mass = 0.8, inertia = [0.002, 0.003, 0.003], com = [0.05, 0, 0],
         at = [wrist.x, wrist.y, wrist.z],
         rotation = base * rot_x(0.3) * rot_z(j1) * rot_y(j2) * rot_y(j3) * rot_x(j4)),
    point(palm, on = link4, at = [0.1, 0, 0]),
    body(link5, mass = 0.5, inertia = [0.001, 0.0012, 0.0011], com = [0.03, 0, 0],
         at = [palm.x, palm.y, palm.z],
         rotation = base * rot_x(0.3) * rot_z(j1) * rot_y(j2) * rot_y(j3) * rot_x(j4) * rot_y(j5)),
    point(flange, on = link5, at = [0.06, 0, 0]),
    body(link6, mass = 0.3, inertia = [0.0008, 0.001, 0.0009], com = [0.05, 0.01, 0],
         at = [flange.x, flange.y, flange.z],
         rotation = base * rot_x(0.3) * rot_z(j1) * rot_y(j2) * rot_y(j3) * rot_x(j4) * rot_y(j5)
             * rot_x(j6)),
    gravity = [0, 0, -g],
    emit(articulated, inverse_dynamics, jacobians),
)]
pub struct ArmedSatellite {
    pub g: f64,
}

/// A hub on a free-flyer joint with a two-joint arm: the same floating base
/// in Pinocchio (`lagrange-bench/peer/pinocchio/free_flyer_reference.py`,
/// `JointModelFreeFlyer`, q = (x, y, z, qx, qy, qz, qw, ..), v in the hub's
/// axes), its M and q̈ mapped to this description's convention (world-axis
/// ẋ, body-axis ω, the quaternion scalar first).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z, j1, j2),
    orientation(base),
    body(hub, mass = 5.0, inertia = [0.4, 0.5, 0.6], at = [x, y, z], rotation = base),
    point(shoulder, on = hub, at = [0.3, 0.1, 0.2]),
    body(upper, mass = 1.5, inertia = [0.01, 0.05, 0.05], com = [0.2, 0, 0],
         at = [shoulder.x, shoulder.y, shoulder.z], rotation = base * rot_z(j1)),
    point(elbow, on = upper, at = [0.4, 0, 0]),
    body(fore, mass = 1.0, inertia = [0.005, 0.02, 0.02], com = [0.15, 0, 0],
         at = [elbow.x, elbow.y, elbow.z], rotation = base * rot_z(j1) * rot_y(j2)),
    gravity = [0, 0, -g],
    emit(coriolis),
)]
pub struct FloatingArm {
    pub g: f64,
}

//! A legged robot read from its URDF with its feet on the ground: Solo 12
//! (example-robot-data's `solo12`) on a free root, a torque input at each
//! joint, each foot a point contact with the file's lateral friction 1.0,
//! held up by PD control to its standing posture. Run by the gallery and
//! `tests/contact_legged.rs`, which include it by path (not through the
//! catalog's `mod.rs`: the URDF's path is the facade crate's, which the
//! benches, reading the catalog from their own crate, would not find).

#![allow(dead_code)]

use lagrange::Lagrangian;
use lagrange::nalgebra::SVector;

/// Solo 12 with a torque input at each joint and its feet against the floor.
#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/solo12.urdf", base = floating),
    gravity = [0, 0, -9.81],
    inputs(u1, u2, u3, u4, u5, u6, u7, u8, u9, u10, u11, u12),
    generalized_force(
        FL_HAA = u1, FR_HAA = u2, HL_HAA = u3, HR_HAA = u4, FL_HFE = u5, FR_HFE = u6,
        HL_HFE = u7, HR_HFE = u8, FL_KFE = u9, FR_KFE = u10, HL_KFE = u11, HR_KFE = u12
    ),
    contact(front_left, on = FL_FOOT, normal = [0, 0, 1], restitution = 0, friction = 1.0),
    contact(front_right, on = FR_FOOT, normal = [0, 0, 1], restitution = 0, friction = 1.0),
    contact(hind_left, on = HL_FOOT, normal = [0, 0, 1], restitution = 0, friction = 1.0),
    contact(hind_right, on = HR_FOOT, normal = [0, 0, 1], restitution = 0, friction = 1.0),
    point(floor_back, mass = 0, at = [-0.4, 0, 0]),
    point(floor_front, mass = 0, at = [0.4, 0, 0]),
    point(floor_right, mass = 0, at = [0, -0.3, 0]),
    point(floor_left, mass = 0, at = [0, 0.3, 0]),
    shape(line(floor_back, floor_front)),
    shape(line(floor_right, floor_left)),
)]
pub struct Solo12Standing {}

/// The standing posture of example-robot-data's `solo12` (knees bent
/// forward in front, backward behind), joint by joint in the order of
/// `COORDINATES` after the base's x, y, z (the file's joints level by
/// level: the four HAA, then the HFE, then the KFE).
pub fn posture() -> [f64; 12] {
    let names = <Solo12Standing as Lagrangian<f64, 18, 19>>::COORDINATES;
    std::array::from_fn(|k| {
        let name = names[3 + k];
        let front = if name.starts_with('F') { 1.0 } else { -1.0 };
        match &name[3..] {
            "HFE" => 0.8 * front,
            "KFE" => -1.6 * front,
            _ => 0.0,
        }
    })
}

/// q = [x, y, z, the twelve joints, the base's quaternion (w, x, y, z)]
/// at `height`, level, in the posture.
pub fn dropped(height: f64) -> SVector<f64, 19> {
    let mut q = SVector::<f64, 19>::zeros();
    q[2] = height;
    q.fixed_rows_mut::<12>(3).copy_from_slice(&posture());
    q[15] = 1.0;
    q
}

/// u = kp (posture − q) − kd q̇ on each joint.
pub fn pd(q: &SVector<f64, 19>, v: &SVector<f64, 18>) -> [f64; 12] {
    let (kp, kd) = (6.0, 0.3);
    let rest = posture();
    std::array::from_fn(|k| kp * (rest[k] - q[3 + k]) - kd * v[3 + k])
}

//! `torque(body, [..])`: a torque on a body in world or body axes, against
//! the same torque written as forces on points of the body (a couple), and
//! against the closed form τ · ∂ω/∂q̇ for Euler angles.

use lagrange::prelude::*;
use lagrange::{Driven, Lagrangian};
use nalgebra::{SVector, Vector3};

/// A satellite turned by three body-axis torques, written with `torque`.
#[derive(Lagrangian)]
#[lagrange(
    orientation(attitude),
    inputs(t1, t2, t3),
    body(sat, mass = m, inertia = [a, b, c], at = [x, y, z], rotation = attitude),
    coordinates(x, y, z),
    torque(sat, [t1, t2, t3], axes = body),
)]
struct TorquedSatellite {
    m: f64,
    a: f64,
    b: f64,
    c: f64,
}

/// The same torques as couples: a force along the next body axis at the tip
/// of an arm, its opposite at the centre.
#[derive(Lagrangian)]
#[lagrange(
    orientation(attitude),
    inputs(t1, t2, t3),
    body(sat, mass = m, inertia = [a, b, c], at = [x, y, z], rotation = attitude),
    coordinates(x, y, z),
    point(arm_x, on = sat, at = [1, 0, 0]),
    point(arm_y, on = sat, at = [0, 1, 0]),
    point(arm_z, on = sat, at = [0, 0, 1]),
    point(centre, on = sat, at = [0, 0, 0]),
    force(arm_y, [t1 * sat.axis_z.x, t1 * sat.axis_z.y, t1 * sat.axis_z.z]),
    force(arm_z, [t2 * sat.axis_x.x, t2 * sat.axis_x.y, t2 * sat.axis_x.z]),
    force(arm_x, [t3 * sat.axis_y.x, t3 * sat.axis_y.y, t3 * sat.axis_y.z]),
    force(centre, [-t1 * sat.axis_z.x - t2 * sat.axis_x.x - t3 * sat.axis_y.x,
                   -t1 * sat.axis_z.y - t2 * sat.axis_x.y - t3 * sat.axis_y.y,
                   -t1 * sat.axis_z.z - t2 * sat.axis_x.z - t3 * sat.axis_y.z]),
)]
struct CoupledSatellite {
    m: f64,
    a: f64,
    b: f64,
    c: f64,
}

/// A top in z-x-z Euler angles, a constant torque in world axes on it.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(top, mass = m, inertia = [a, a, c], at = [0, 0, 0],
         rotation = euler_zxz(psi, theta, phi)),
    torque(top, [tx, ty, tz]),
)]
struct WorldTorqueTop {
    m: f64,
    a: f64,
    c: f64,
    tx: f64,
    ty: f64,
    tz: f64,
}

/// A pseudo-random sequence, for states.
fn samples(n: usize) -> impl Iterator<Item = f64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n).map(move |_| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    })
}

#[test]
fn a_body_axis_torque_is_the_couple_written_with_points() {
    let (m, a, b, c) = (40.0, 2.0, 3.0, 4.5);
    let torqued = TorquedSatellite { m, a, b, c };
    let coupled = CoupledSatellite { m, a, b, c };
    let mut r = samples(13 * 20);
    for _ in 0..20 {
        let mut s = [0.0; 13];
        s.iter_mut().for_each(|x| *x = r.next().unwrap());
        let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + s[3] * s[3]).sqrt();
        // q: the coordinates (x, y, z), then the quaternion; v: their rates, then ω.
        let q = SVector::<f64, 7>::from([s[4], s[5], s[6], s[0] / n, s[1] / n, s[2] / n, s[3] / n]);
        let v = SVector::<f64, 6>::from([s[7], s[8], s[9], s[10], s[11], s[12]]);
        let u = Vector3::new(0.7, -1.3, 0.4);
        let f = torqued.input_forces(&q, &v, &u, 0.0);
        let g = coupled.input_forces(&q, &v, &u, 0.0);
        assert!((f - g).amax() < 1e-12, "{f:?} vs {g:?}");
        // Body-axis torques on ω in body axes: the generalized forces are
        // the torques themselves, and no force moves the centre.
        assert!(f.fixed_rows::<3>(0).amax() < 1e-12);
        assert!((f.fixed_rows::<3>(3) - u).amax() < 1e-12);
    }
}

#[test]
fn a_world_axis_torque_on_euler_angles_is_its_closed_form() {
    let tau = Vector3::new(0.3, -0.8, 1.1);
    let top = WorldTorqueTop {
        m: 1.0,
        a: 0.4,
        c: 0.2,
        tx: tau.x,
        ty: tau.y,
        tz: tau.z,
    };
    let mut r = samples(6 * 10);
    for _ in 0..10 {
        let q = SVector::<f64, 3>::from_fn(|_, _| r.next().unwrap() * 3.0);
        let v = SVector::<f64, 3>::from_fn(|_, _| r.next().unwrap());
        let (psi, theta) = (q[0], q[1]);
        // ω = ψ̇ e_z + θ̇ R_z(ψ) e_x + φ̇ R_z(ψ) R_x(θ) e_z, so Q_i = τ · ∂ω/∂q̇_i.
        let columns = [
            Vector3::z(),
            Vector3::new(psi.cos(), psi.sin(), 0.0),
            Vector3::new(
                psi.sin() * theta.sin(),
                -psi.cos() * theta.sin(),
                theta.cos(),
            ),
        ];
        let q_force = top.generalized_forces(&q, &v, 0.0);
        for (i, e) in columns.iter().enumerate() {
            assert!(
                (q_force[i] - tau.dot(e)).abs() < 1e-12,
                "Q[{i}] = {} vs {}",
                q_force[i],
                tau.dot(e)
            );
        }
    }
}

/// A constant body-axis torque about a principal axis from rest turns the
/// body through ½ (τ/B) t² about it.
#[test]
fn a_constant_body_torque_turns_the_body_as_the_closed_form() {
    let sat = TorquedSatellite {
        m: 40.0,
        a: 2.0,
        b: 3.0,
        c: 4.5,
    };
    let tau = 0.6;
    let run = Simulation::new(&sat)
        .integrator(Dopri5::tol(1e-12))
        .open_loop(move |_| [0.0, tau, 0.0])
        .run([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0], [0.0; 6], 0.0..2.0)
        .unwrap();
    let (q, v) = run.trajectory().final_state();
    let angle = 0.5 * tau / sat.b * 4.0;
    let expected = [(angle / 2.0).cos(), 0.0, (angle / 2.0).sin(), 0.0];
    for k in 0..4 {
        assert!((q[3 + k] - expected[k]).abs() < 1e-9, "{q:?}");
    }
    assert!((v[4] - tau / sat.b * 2.0).abs() < 1e-9);
    assert!(q.fixed_rows::<3>(0).amax() < 1e-12); // the centre stays
}

//! Hamilton's form with free orientations (`emit(hamiltonian)` with
//! `orientation(..)`) and the symplectic Gauss method on it: ∂T/∂θ at fixed
//! ω against finite differences on the group, the order against a tight
//! DOP853 run, and what a symplectic method on the rotation group keeps:
//! unit quaternions without a projection, the angular momenta of the
//! symmetries to round-off, and a bounded energy error.

use crate::catalog;
use crate::common;

use catalog::free::flip_half_period;
use catalog::study::TumblingBody;
use common::numeric::Lcg;
use lagrange::numeric::orientation;
use lagrange::prelude::*;
use nalgebra::{Matrix3, SVector, Vector3};

/// A free body whose reference point is off its centre of mass: with ẋ in
/// world axes, T depends on the rotation, and ∂T/∂θ at fixed ω is not zero.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    orientation(turn),
    body(b, mass = m, inertia = [i1, i2, i3], about = [cx, cy, cz], com = [cx, cy, cz],
         at = [x, y, z], rotation = turn),
    emit(hamiltonian),
)]
struct OffCentre {
    m: f64,
    i1: f64,
    i2: f64,
    i3: f64,
    cx: f64,
    cy: f64,
    cz: f64,
}

/// The heavy symmetric top on its pivot.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    orientation(spin),
    body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
         at = [0, 0, 0], rotation = spin),
    gravity = [0, 0, -g],
    emit(hamiltonian),
)]
struct Top {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// Two bodies joined by spherical joints, hung from a pivot, with a hinged
/// rod at the lower one's tip: two orientations and an ordinary coordinate.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(hinge),
    orientation(upper, lower),
    body(arm, mass = m, inertia = [a, a, c], about = [0, 0, -l], com = [0, 0, -l],
         at = [0, 0, 0], rotation = upper),
    point(tip, on = arm, at = [0, 0, -2 * l]),
    body(hand, mass = m, inertia = [a, 1.5 * a, c], about = [0, 0.1, -l], com = [0, 0.1, -l],
         at = [tip.x, tip.y, tip.z], rotation = upper * lower),
    point(wrist, on = hand, at = [0, 0, -2 * l]),
    body(rod, mass = m / 2, inertia = [a / 4, a / 4, c / 4], about = [0, 0, -l / 2],
         com = [0, 0, -l / 2], at = [wrist.x, wrist.y, wrist.z],
         rotation = upper * lower * rot_x(hinge)),
    gravity = [0, 0, -g],
    emit(hamiltonian),
)]
struct Chain {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// A lone body turning freely (Euler's equations): the catalog's plate.
const TUMBLER: TumblingBody = TumblingBody::PLATE;
const OFF_CENTRE: OffCentre = OffCentre {
    m: 2.0,
    i1: 0.3,
    i2: 0.5,
    i3: 0.6,
    cx: 0.2,
    cy: -0.1,
    cz: 0.3,
};
const TOP: Top = Top {
    m: 1.5,
    a: 0.8,
    c: 0.5,
    l: 0.4,
    g: 9.81,
};
const CHAIN: Chain = Chain {
    m: 1.0,
    a: 0.05,
    c: 0.04,
    l: 0.3,
    g: 9.81,
};

fn rotation_of(q: &[f64]) -> Matrix3<f64> {
    let r = orientation::rotation_matrix([q[0], q[1], q[2], q[3]]);
    Matrix3::from_fn(|i, j| r[i][j])
}

fn unit_quaternion(rng: &mut Lcg) -> [f64; 4] {
    let q = [0; 4].map(|_| rng.next());
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    q.map(|x| x / n)
}

/// A random configuration: ordinary coordinates in [−1, 1], unit quaternions.
fn random_configuration<S: Lagrangian<f64, N, Q>, const N: usize, const Q: usize>(
    rng: &mut Lcg,
) -> SVector<f64, Q> {
    let mut q = SVector::<f64, Q>::from_fn(|_, _| rng.next());
    for o in S::ORIENTATIONS {
        let u = unit_quaternion(rng);
        q.as_mut_slice()[o.q..o.q + 4].copy_from_slice(&u);
    }
    q
}

/// ∂T/∂θ at fixed v (ω fixed in body axes) by central differences of T
/// along q ⊕ ε e_k, against the emitted `kinetic_gradient`.
fn gradient_matches_differences<S, const N: usize, const Q: usize>(system: &S, seed: u64)
where
    S: Lagrangian<f64, N, Q>,
{
    let mut rng = Lcg(seed);
    for _ in 0..10 {
        let q = random_configuration::<S, N, Q>(&mut rng);
        let v = rng.vector::<N>(3.0);
        let gradient = system.kinetic_gradient(&q, &v, 0.0).unwrap();
        let eps = 1e-5;
        for k in 0..N {
            let moved = |s: f64| {
                let mut delta = SVector::<f64, N>::zeros();
                delta[k] = s;
                let mut out = SVector::<f64, Q>::zeros();
                orientation::integrate(
                    S::ORIENTATIONS,
                    q.as_slice(),
                    delta.as_slice(),
                    out.as_mut_slice(),
                );
                system.kinetic_energy(&out, &v, 0.0)
            };
            let d = (moved(eps) - moved(-eps)) / (2.0 * eps);
            assert!(
                (gradient[k] - d).abs() < 1e-8 * (1.0 + d.abs()),
                "slot {k}: {} vs {d}",
                gradient[k]
            );
        }
    }
}

#[test]
fn the_kinetic_gradient_is_along_body_axis_turns_at_fixed_omega() {
    gradient_matches_differences(&OFF_CENTRE, 3);
    gradient_matches_differences(&CHAIN, 5);
    gradient_matches_differences(&TUMBLER, 7);
}

/// The largest distance between two runs' configurations at their common
/// times (each quaternion compared through its rotation matrix).
fn distance<const N: usize, const Q: usize>(
    layout: &[lagrange::Orientation],
    a: &Trajectory<f64, N, Q>,
    b: &Trajectory<f64, N, Q>,
    t: f64,
) -> f64 {
    let (qa, qb) = (a.state_at(t).unwrap().0, b.state_at(t).unwrap().0);
    let mut d = SVector::<f64, N>::zeros();
    orientation::difference(layout, qa.as_slice(), qb.as_slice(), d.as_mut_slice());
    d.amax()
}

/// Errors at t = 1 of Gauss with steps h and h/2 against DOP853 at 1e-13,
/// and their ratio.
fn order_of<S, const N: usize, const Q: usize>(
    system: &S,
    (q0, v0): (SVector<f64, Q>, SVector<f64, N>),
    method: fn(f64) -> Gauss,
    h: f64,
) -> (f64, f64, f64)
where
    S: Lagrangian<f64, N, Q>,
{
    let reference = Simulation::new(system)
        .integrator(Dop853::tol(1e-13))
        .run(q0, v0, 0.0..1.0)
        .unwrap();
    let error = |h: f64| {
        let run = Simulation::new(system)
            .integrator(method(h))
            .run(q0, v0, 0.0..1.0)
            .unwrap();
        distance(S::ORIENTATIONS, &run, &reference, 1.0)
    };
    let (coarse, fine) = (error(h), error(h / 2.0));
    (coarse, fine, coarse / fine)
}

fn chain_state() -> (SVector<f64, 9>, SVector<f64, 7>) {
    let lean = |a: f64| [(a / 2.0).cos(), (a / 2.0).sin(), 0.0, 0.0];
    let twist = |a: f64| [(a / 2.0).cos(), 0.0, (a / 2.0).sin(), 0.0];
    let (u, w) = (lean(0.7), twist(-0.5));
    let q = SVector::from([0.4, u[0], u[1], u[2], u[3], w[0], w[1], w[2], w[3]]);
    let v = SVector::from([1.0, 0.5, -1.0, 2.0, 1.5, 0.3, -0.8]);
    (q, v)
}

#[test]
fn gauss_on_the_group_has_orders_four_and_two() {
    let mut rng = Lcg(17);
    let mut q = random_configuration::<OffCentre, 6, 7>(&mut rng);
    q.as_mut_slice()[..3].copy_from_slice(&[0.0; 3]);
    let v = SVector::from([0.3, -0.2, 0.1, 2.0, -3.0, 1.5]);
    let cases = [
        (
            "off-centre body, 2 stages",
            order_of(&OFF_CENTRE, (q, v), Gauss::step, 0.05),
        ),
        (
            "off-centre body, midpoint",
            order_of(&OFF_CENTRE, (q, v), Gauss::midpoint, 0.02),
        ),
        (
            "chain, 2 stages",
            order_of(&CHAIN, chain_state(), Gauss::step, 0.02),
        ),
        (
            "chain, midpoint",
            order_of(&CHAIN, chain_state(), Gauss::midpoint, 0.005),
        ),
    ];
    for (name, (coarse, fine, ratio)) in cases {
        let expected = if name.ends_with("midpoint") {
            4.0
        } else {
            16.0
        };
        println!("{name}: errors {coarse:.3e}, {fine:.3e}, ratio {ratio:.2}");
        assert!(
            (ratio / expected - 1.0).abs() < 0.15,
            "{name}: ratio {ratio} (errors {coarse:e}, {fine:e}), expected {expected}"
        );
    }
}

/// World angular momentum of the lone body, R I ω.
fn tumbler_momentum(q: &SVector<f64, 4>, v: &SVector<f64, 3>) -> Vector3<f64> {
    let i = Vector3::new(TUMBLER.i1, TUMBLER.i2, TUMBLER.i3);
    rotation_of(q.as_slice()) * i.component_mul(&Vector3::new(v[0], v[1], v[2]))
}

/// The largest change of `f` along a run, relative to its start.
fn largest_change<const N: usize, const Q: usize>(
    traj: &Trajectory<f64, N, Q>,
    f: impl Fn(&SVector<f64, Q>, &SVector<f64, N>) -> Vector3<f64>,
) -> f64 {
    let start = f(&traj.positions()[0], &traj.velocities()[0]);
    (traj.positions().iter().zip(traj.velocities()))
        .map(|(q, v)| (f(q, v) - start).norm() / start.norm())
        .fold(0.0, f64::max)
}

/// Through 50 intermediate-axis flips with a fixed step: the world
/// angular momentum to round-off, the quaternion unit without projection,
/// the energy error bounded (the same in the last quarter as in the first).
#[test]
fn the_tumbling_body_keeps_its_momentum_and_a_bounded_energy_error() {
    let omega = [0.02, 1.0, 0.02];
    let half = flip_half_period([1.0, 2.0, 3.0], omega);
    let span = 50.0 * half;
    let traj = Simulation::new(&TUMBLER)
        .integrator(Gauss::step(0.05))
        .run([1.0, 0.0, 0.0, 0.0], omega, 0.0..span)
        .unwrap();
    let momentum = largest_change(&traj, tumbler_momentum);
    let unit = traj.max_unit_error();
    let energies = traj.integrals();
    let e0 = energies[0];
    let quarter = energies.len() / 4;
    let worst = |xs: &[f64]| xs.iter().map(|e| (e - e0).abs() / e0).fold(0.0, f64::max);
    let (first, last) = (worst(&energies[..quarter]), worst(&energies[3 * quarter..]));
    println!(
        "{} steps over {span:.1} s: momentum {momentum:.2e}, unit {unit:.2e}, energy {first:.2e} / {last:.2e}",
        traj.len()
    );
    assert!(
        momentum < 1e-12,
        "world angular momentum moved by {momentum:e}"
    );
    assert!(unit < 1e-13, "unit-norm error {unit:e}");
    assert!(
        last < 1e-5 && last < 2.0 * first,
        "energy {first:e} then {last:e}"
    );
}

/// The top, started tilted and started exactly upright: its vertical
/// angular momentum (e_z · R I ω about the pivot) and axial momentum c ω₃
/// to round-off, the energy error bounded.
#[test]
fn the_top_keeps_its_vertical_and_axial_momenta() {
    let inertia = Vector3::new(TOP.a, TOP.a, TOP.c);
    let about_vertical = |q: &SVector<f64, 4>, v: &SVector<f64, 3>| {
        let l = rotation_of(q.as_slice()) * inertia.component_mul(&Vector3::new(v[0], v[1], v[2]));
        Vector3::new(l.z, TOP.c * v[2], 0.0)
    };
    let tilted = [(0.3f64).cos(), (0.3f64).sin(), 0.0, 0.0];
    for (name, q0, v0) in [
        ("tilted", tilted, [0.5, 0.0, 20.0]),
        ("upright", [1.0, 0.0, 0.0, 0.0], [0.3, -0.2, 15.0]),
    ] {
        let traj = Simulation::new(&TOP)
            .integrator(Gauss::step(0.002))
            .run(q0, v0, 0.0..10.0)
            .unwrap();
        let momenta = largest_change(&traj, about_vertical);
        let unit = traj.max_unit_error();
        let drift = traj.integral_drift();
        println!("{name}: momenta {momenta:.2e}, unit {unit:.2e}, energy {drift:.2e}");
        assert!(momenta < 1e-12, "{name}: momenta moved by {momenta:e}");
        assert!(unit < 1e-13, "{name}: unit-norm error {unit:e}");
        assert!(drift < 1e-7, "{name}: energy drift {drift:e}");
    }
}

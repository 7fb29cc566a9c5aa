//! Linearisation of constrained systems with orientations
//! (`Linearizer::constrained_tangent`): the rolling disk with a quaternion
//! against the Euler-angle disk's symbolic linearisation (`constrained`) and
//! the closed form of its critical spin, the rolling sphere's neutral
//! stability and its input matrix against the closed form, and A against
//! central differences of the nonlinear dynamics on the constraints.

use crate::catalog;

use catalog::constrained::RollingDisk;
use catalog::rolling::{QuaternionDisk, QuaternionSphere};
use lagrange::linear::{Linear, Linearizer, OperatingPoint, Verdict, sweep};
use lagrange::nalgebra::{DMatrix, Matrix3, Quaternion, SVector, UnitQuaternion, Vector3};
use lagrange::prelude::*;

const M: f64 = 1.0;
const A: f64 = 0.5;
const G: f64 = 9.81;

const DISK_COORDINATES: [&str; 5] = ["x", "y", "disk_q.θx", "disk_q.θy", "disk_q.θz"];
const DISK_SPEEDS: [&str; 3] = ["disk_q.wx", "disk_q.wy", "disk_q.wz"];

/// The quaternion disk rolling upright along x at spin ω about its axle
/// (body y, here world y): centre (0, 0, a), identity orientation.
fn upright(spin: f64) -> OperatingPoint<f64, 6, 0, 7> {
    OperatingPoint::on_group(
        SVector::from([0.0, 0.0, A, 1.0, 0.0, 0.0, 0.0]),
        SVector::from([A * spin, 0.0, 0.0, 0.0, spin, 0.0]),
    )
}

fn disk_linear(spin: f64) -> Result<Linear, lagrange::Error> {
    Linearizer::new()
        .coordinates(&DISK_COORDINATES)
        .speeds(&DISK_SPEEDS)
        .constrained_tangent(&QuaternionDisk::thin(M, A, G), &upright(spin))
}

/// The chart disk's states (x, y, ψ, θ, φ, ψ', θ', φ') to the quaternion
/// disk's (x, y, θx, θy, θz, wx, wy, wz) about upright rolling at spin ω:
/// the centre is the contact point less a θ in y; the rotation
/// rot_z(ψ) rot_x(θ) rot_y(ωt + φ) is the fixed-axes turn (θ, φ, ψ) of the
/// reference; its angular velocity in space axes changes by
/// (θ' − ω ψ, φ', ψ' + ω θ).
fn chart_to_group(spin: f64) -> DMatrix<f64> {
    let mut t = DMatrix::zeros(8, 8);
    for (row, entries) in [
        (0, vec![(0, 1.0)]),
        (1, vec![(1, 1.0), (3, -A)]),
        (2, vec![(3, 1.0)]),
        (3, vec![(4, 1.0)]),
        (4, vec![(2, 1.0)]),
        (5, vec![(6, 1.0), (2, -spin)]),
        (6, vec![(7, 1.0)]),
        (7, vec![(5, 1.0), (3, spin)]),
    ] {
        for (col, x) in entries {
            t[(row, col)] = x;
        }
    }
    t
}

fn chart_linear(spin: f64) -> Linear {
    let v = SVector::from([A * spin, 0.0, 0.0, 0.0, spin]);
    Linearizer::new()
        .coordinates(&["x", "y", "psi", "theta", "phi"])
        .speeds(&["psi", "theta", "phi"])
        .constrained(
            &RollingDisk::thin(M, A, G),
            &OperatingPoint::new(SVector::zeros(), v),
        )
        .unwrap()
}

/// Eigenvalues with a non-zero imaginary part or a real part above `floor`,
/// sorted: what the two models must share (their zero eigenvalues sit in
/// Jordan chains, which a numerical eigen-solver spreads by √ε).
fn moving(lin: &Linear, floor: f64) -> Vec<(f64, f64)> {
    let mut ev: Vec<(f64, f64)> = lin
        .eigenvalues()
        .iter()
        .filter(|z| z.norm() > floor)
        .map(|z| (z.re, z.im))
        .collect();
    ev.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0)));
    ev
}

/// Upright rolling at spins below, near and above the critical one: the
/// quaternion disk's A is the chart disk's in the quaternion's states,
/// T A_chart T⁻¹, entry by entry, and the eigenvalues agree.
#[test]
fn the_quaternion_disk_linearises_as_the_chart_disk() {
    for spin in [1.0, 2.0, 2.6, 5.0] {
        let lin = disk_linear(spin).unwrap();
        assert_eq!(
            lin.states(),
            [
                "x",
                "y",
                "disk_q.θx",
                "disk_q.θy",
                "disk_q.θz",
                "disk_q.wx",
                "disk_q.wy",
                "disk_q.wz"
            ]
        );
        let chart = chart_linear(spin);
        let t = chart_to_group(spin);
        let want = &t * chart.a() * t.clone().try_inverse().unwrap();
        let gap = (lin.a() - &want).amax() / want.amax();
        let (ours, theirs) = (moving(&lin, 1e-6), moving(&chart, 1e-6));
        assert_eq!(ours.len(), theirs.len(), "{ours:?} vs {theirs:?}");
        let eig_gap = ours
            .iter()
            .zip(&theirs)
            .map(|(a, b)| (a.0 - b.0).abs().max((a.1 - b.1).abs()))
            .fold(0.0, f64::max);
        eprintln!(
            "disk upright at ω = {spin}: A gap {gap:.1e} (relative), eigenvalue gap {eig_gap:.1e}, \
             eigenvalues {ours:?}"
        );
        assert!(gap < 1e-8, "{}\nvs\n{want}", lin.a());
        assert!(eig_gap < 1e-8);
    }
}

/// The critical spin of upright rolling, found on the quaternion disk where
/// the largest real part of its eigenvalues falls to the tolerance, against
/// the closed form Ω² = m g a B / (C (C + m a²)) = g / 3a for a thin uniform
/// disk (B = m a²/4, C = m a²/2; `tests/stability.rs` finds it on the chart
/// disk).
///
/// At Ω_c a neutral pair meets the zero eigenvalue of the conserved heading
/// momentum, so an error ε in A moves the eigenvalues there by about ε^⅓.
/// The differences' ε ≈ 1e-11 (relative) leaves real parts up to ~1e-5
/// just above Ω_c (measured: a threshold τ = 1e-6 lands 4.9e-4 above it,
/// 1e-5 2.0e-7 above); below it Re λ = √(κ (Ω_c − Ω)), so τ moves the
/// crossing by only τ²/κ: τ = 1e-4 locates Ω_c to 3.2e-8 (1e-3: 3.1e-8).
/// The symbolic chart disk, with round-off only, gets 2.3e-10 with 1e-6.
#[test]
fn the_quaternion_disk_has_the_critical_spin_of_the_closed_form() {
    let d = QuaternionDisk::thin(M, A, G);
    let exact = (G / (3.0 * A)).sqrt();
    let general = (d.m * d.g * d.a * d.b / (d.c * (d.c + d.m * d.a * d.a))).sqrt();
    assert!((exact - general).abs() < 1e-15);
    let tol = 1e-4;
    let spins: Vec<f64> = (1..=20).map(|i| 0.25 * i as f64).collect();
    let mut eigen = sweep(&spins, disk_linear).unwrap();
    let found = eigen.boundaries(tol, 1e-14).unwrap();
    assert_eq!(found.len(), 1, "{found:?}");
    let rel = (found[0].parameter - exact).abs() / exact;
    eprintln!(
        "quaternion disk: critical spin {:.12} rad/s, √(g/3a) = {exact:.12}: rel. error {rel:.1e}",
        found[0].parameter
    );
    assert!(rel < 1e-7);
    assert!(!found[0].destabilising);
    // About the tilt and its rates (the heading and position left out).
    let verdict = |w: f64| (disk_linear(w).unwrap().stability(tol).unwrap()).without_structural;
    assert_eq!(verdict(0.9 * exact), Verdict::Unstable);
    assert_eq!(verdict(1.1 * exact), Verdict::Marginal);
}

/// The homogeneous sphere of the catalog pushed at its centre by a
/// horizontal force `fx` (an input).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    orientation(ball_q),
    inputs(fx),
    body(ball, mass = m, inertia = [j, j, j], at = [x, y, z], rotation = ball_q),
    point(centre, on = ball, at = [0, 0, 0]),
    force(centre, [fx, 0, 0]),
    gravity = [0, 0, -g],
    holonomic(height = ball.z - a),
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
)]
struct PushedSphere {
    m: f64,
    j: f64,
    a: f64,
    g: f64,
}

const J: f64 = 0.4 * M * A * A;

fn straight(spin: f64) -> OperatingPoint<f64, 6, 0, 7> {
    OperatingPoint::on_group(
        SVector::from([0.3, -0.2, A, 1.0, 0.0, 0.0, 0.0]),
        SVector::from([A * spin, 0.0, 0.0, 0.0, spin, 0.0]),
    )
}

/// A homogeneous sphere rolling straight: every eigenvalue on the imaginary
/// axis (its angular velocity is constant, and a turn of its orientation is
/// carried round by the spin: ±iω), the verdict marginal; the catalog's
/// sphere and the pushed one (input zero) give the same A; B is the closed
/// form of a force at the centre of a rolling ball: ẍ = F / (m + j/a²),
/// ω̇_y = ẍ / a, nothing else.
#[test]
fn the_rolling_sphere_is_neutrally_stable_and_its_push_is_the_closed_form() {
    let spin = 3.0;
    let ball = QuaternionSphere {
        m: M,
        j1: J,
        j2: J,
        j3: J,
        a: A,
        g: G,
    };
    let lin = Linearizer::new()
        .constrained_tangent(&ball, &straight(spin))
        .unwrap();
    let stability = lin.stability(1e-9).unwrap();
    let ev = lin.eigenvalues();
    let largest_re = ev.iter().map(|z| z.re.abs()).fold(0.0, f64::max);
    eprintln!(
        "sphere rolling straight at ω = {spin}: states {:?}, eigenvalues {ev:?}",
        lin.states()
    );
    assert_eq!(stability.without_structural, Verdict::Marginal);
    assert!(largest_re < 1e-9, "{largest_re:e}");
    assert!(ev.iter().any(|z| (z.im - spin).abs() < 1e-9));
    let pushed = PushedSphere {
        m: M,
        j: J,
        a: A,
        g: G,
    };
    let driven = Linearizer::new()
        .constrained_tangent(&pushed, &straight(spin).input(SVector::from([0.0])))
        .unwrap();
    assert_eq!(driven.states(), lin.states());
    let gap = (driven.a() - lin.a()).amax();
    assert!(gap < 1e-12, "{gap:e}");
    let xdd = 1.0 / (M + J / (A * A));
    let mut want = DMatrix::zeros(8, 1);
    let wy = driven.state_index("ball_q.wy'").unwrap();
    want[(wy, 0)] = xdd / A;
    let b_gap = (driven.b() - &want).amax();
    eprintln!(
        "pushed sphere: B {:?}, closed form ω̇_y = {:.12}: gap {b_gap:.1e}",
        driven.b().as_slice(),
        xdd / A
    );
    assert!(b_gap < 1e-9 * xdd, "{}", driven.b());
}

/// J_r⁻¹(φ), the inverse right Jacobian of SO(3): d/dt log(E) = J_r⁻¹(φ) ξ
/// when Ė = E [ξ]× and E = exp(φ).
fn inverse_right_jacobian(phi: &Vector3<f64>) -> Matrix3<f64> {
    let (angle, hat) = (phi.norm(), phi.cross_matrix());
    let c = if angle < 1e-4 {
        1.0 / 12.0 + angle * angle / 720.0
    } else {
        1.0 / (angle * angle) - (1.0 + angle.cos()) / (2.0 * angle * angle.sin())
    };
    Matrix3::identity() + 0.5 * hat + c * hat * hat
}

/// The disk's state from the model's states x = (δx, δy, δθ, δω) about
/// (q0, v0), on the constraints, as this file reads the fixed axes: the
/// orientation q0 ⊗ exp(δθ), the angular velocity R0 (ω0 + δω) in space
/// axes, the centre's height from the holonomic row, its velocity from the
/// three velocity rows.
fn disk_state(
    disk: &QuaternionDisk,
    (q0, v0): (&SVector<f64, 7>, &SVector<f64, 6>),
    x: &[f64],
) -> (SVector<f64, 7>, SVector<f64, 6>) {
    let start = UnitQuaternion::from_quaternion(Quaternion::new(q0[3], q0[4], q0[5], q0[6]));
    let turn = start * UnitQuaternion::from_scaled_axis(Vector3::new(x[2], x[3], x[4]));
    let r = turn.to_rotation_matrix();
    let nz = r[(2, 1)];
    let c = turn.quaternion();
    let q = SVector::from([
        q0[0] + x[0],
        q0[1] + x[1],
        disk.a * (1.0 - nz * nz).sqrt(),
        c.w,
        c.i,
        c.j,
        c.k,
    ]);
    let w0 = Vector3::new(v0[3], v0[4], v0[5]);
    let omega = start.to_rotation_matrix() * (w0 + Vector3::new(x[5], x[6], x[7]));
    let body = r.transpose() * omega;
    let (g, g0) = disk.constraint_jacobian(&q, 0.0);
    let gl = Matrix3::from_fn(|i, j| g[(i, j)]);
    let rest =
        Vector3::from_fn(|i, _| (0..3).map(|j| g[(i, 3 + j)] * body[j]).sum::<f64>() + g0[i]);
    let centre = gl.lu().solve(&-rest).unwrap();
    let v = SVector::from([centre[0], centre[1], centre[2], body[0], body[1], body[2]]);
    (q, v)
}

/// The rates of the model's states at x (the nonlinear dynamics): δẋ, δẏ
/// the centre's velocity, δθ̇ = J_r⁻¹(δθ) (ω − ω0) in body axes (the
/// reference turning on at ω0), δω̇ = R0ᵀ R ω̇.
fn disk_rates(
    disk: &QuaternionDisk,
    (q0, v0): (&SVector<f64, 7>, &SVector<f64, 6>),
    x: &[f64],
) -> Vec<f64> {
    let (q, v) = disk_state(disk, (q0, v0), x);
    let a = ConstrainedDynamics::<_, f64, 3>::new(disk)
        .solve(0.0, &q, &v)
        .unwrap()
        .accelerations;
    let start = UnitQuaternion::from_quaternion(Quaternion::new(q0[3], q0[4], q0[5], q0[6]));
    let turn = start * UnitQuaternion::from_scaled_axis(Vector3::new(x[2], x[3], x[4]));
    let phi = Vector3::new(x[2], x[3], x[4]);
    let slip = Vector3::new(v[3] - v0[3], v[4] - v0[4], v[5] - v0[5]);
    let turning = inverse_right_jacobian(&phi) * slip;
    let spin = start.to_rotation_matrix().transpose()
        * (turn.to_rotation_matrix() * Vector3::new(a[3], a[4], a[5]));
    let mut out = vec![v[0], v[1]];
    out.extend(turning.iter());
    out.extend(spin.iter());
    out
}

/// A tilted, turning, wobbling disk (not a steady motion: the ω̇ and the
/// [a*]× terms count): A against central differences (step 1e-6) of the
/// nonlinear rates of its states, each perturbed state completed on the
/// constraints exactly (the height from the holonomic row, the centre's
/// velocity from the velocity rows), entry by entry.
#[test]
fn linearisation_of_a_wobbling_disk_matches_central_differences() {
    let disk = QuaternionDisk::thin(M, A, G);
    let tilt = UnitQuaternion::from_euler_angles(0.3, 0.0, 0.4);
    let c = tilt.quaternion();
    let q = SVector::from([0.1, -0.2, A, c.w, c.i, c.j, c.k]);
    let v = SVector::from([0.0, 0.0, 0.0, 0.7, 5.0, -0.4]);
    let (q0, v0) = lagrange::project_consistent(&disk, q, v, 0.0).unwrap();
    let a0 = ConstrainedDynamics::<_, f64, 3>::new(&disk)
        .solve(0.0, &q0, &v0)
        .unwrap();
    assert!(
        a0.accelerations.rows(3, 3).amax() > 0.1,
        "steady: {}",
        a0.accelerations
    );
    let lin = Linearizer::new()
        .coordinates(&DISK_COORDINATES)
        .speeds(&DISK_SPEEDS)
        .constrained_tangent(&disk, &OperatingPoint::on_group(q0, v0))
        .unwrap();
    let h = 1e-6;
    let mut fd = DMatrix::zeros(8, 8);
    for j in 0..8 {
        let (mut xp, mut xm) = (vec![0.0; 8], vec![0.0; 8]);
        xp[j] = h;
        xm[j] = -h;
        let (fp, fm) = (
            disk_rates(&disk, (&q0, &v0), &xp),
            disk_rates(&disk, (&q0, &v0), &xm),
        );
        for i in 0..8 {
            fd[(i, j)] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    let err = (lin.a() - &fd).amax() / lin.a().amax();
    eprintln!(
        "wobbling disk: A vs central differences of the nonlinear rates {err:.1e} (relative to max |A| = {:.3})",
        lin.a().amax()
    );
    assert!(err < 1e-7, "{}\nvs\n{fd}", lin.a());
}

/// Bad input gives typed errors: a quaternion off unit norm, a state off
/// the constraints, a name that is no tangent direction, a choice of
/// dependent coordinates the constraints cannot solve for, a disk lying
/// flat (its rolling rows have no contact point), a NaN.
#[test]
fn bad_operating_points_and_partitions_are_typed_errors() {
    use lagrange::{Error, LinearError};
    let disk = QuaternionDisk::thin(M, A, G);
    let lz = Linearizer::new();
    let mut op = upright(3.0);
    op.q[4] = 0.1;
    let err = lz.constrained_tangent(&disk, &op).unwrap_err();
    assert!(
        matches!(&err, Error::NonUnitQuaternion { orientation, .. } if orientation == "disk_q"),
        "{err}"
    );
    let mut op = upright(3.0);
    op.v[0] += 0.01;
    let err = lz.constrained_tangent(&disk, &op).unwrap_err();
    assert!(
        matches!(&err, Error::Linear(LinearError::InconsistentOperatingPoint { worst, .. }) if worst.contains("roll_x")),
        "{err}"
    );
    let err = lz
        .clone()
        .coordinates(&["disk_q.w"])
        .constrained_tangent(&disk, &upright(3.0))
        .unwrap_err();
    assert!(
        matches!(&err, Error::Linear(LinearError::InvalidPartition { .. })),
        "{err}"
    );
    let all_but_heading = ["x", "y", "z", "disk_q.θx", "disk_q.θy"];
    let err = lz
        .clone()
        .coordinates(&all_but_heading)
        .constrained_tangent(&disk, &upright(3.0))
        .unwrap_err();
    assert!(
        matches!(&err, Error::Linear(LinearError::SingularPartition { dependent, .. }) if dependent == &["disk_q.θz"]),
        "{err}"
    );
    let flat = UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 0.0);
    let c = flat.quaternion();
    let op = OperatingPoint::on_group(
        SVector::from([0.0, 0.0, 0.0, c.w, c.i, c.j, c.k]),
        SVector::zeros(),
    );
    let err = lz.constrained_tangent(&disk, &op).unwrap_err();
    assert!(matches!(&err, Error::NonFiniteState { .. }), "{err}");
    let mut op = upright(3.0);
    op.v[4] = f64::NAN;
    let err = lz.constrained_tangent(&disk, &op).unwrap_err();
    assert!(matches!(&err, Error::NonFiniteState { .. }), "{err}");
}

/// Without orientations (Q = N) the same entry point reads the Euler-angle
/// disk by central differences: about steady turning (tilted 0.3 rad,
/// heading rate 2 rad/s) its A and states are those of the symbolic
/// `constrained`.
#[test]
fn without_orientations_it_agrees_with_the_symbolic_linearisation() {
    let d = RollingDisk::thin(M, A, G);
    let (q0, v0) = d.steady_circle(0.3, 2.0);
    let lz = Linearizer::new()
        .coordinates(&["x", "y", "psi", "theta", "phi"])
        .speeds(&["psi", "theta", "phi"]);
    let (q0, v0) = lz
        .complete_state(&d, SVector::from(q0), SVector::from(v0), 0.0)
        .unwrap();
    let op = OperatingPoint::new(q0, v0);
    let symbolic = lz.constrained(&d, &op).unwrap();
    let numeric = lz.constrained_tangent(&d, &op).unwrap();
    assert_eq!(numeric.states(), symbolic.states());
    let gap = (numeric.a() - symbolic.a()).amax() / symbolic.a().amax();
    eprintln!("chart disk turning steadily: central differences vs symbolic A {gap:.1e}");
    assert!(gap < 1e-8, "{}\nvs\n{}", numeric.a(), symbolic.a());
}

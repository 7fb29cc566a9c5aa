//! Generated vs hand-written: M and h (and the joint M, Q − h the integrators call)
//! of the planar double pendulum, evaluated in the same run, so the ratio is
//! meaningful on a shared machine.

#[path = "../../examples/catalog/mod.rs"]
mod catalog;

use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::Lagrangian;
use nalgebra::{Matrix2, Vector2};
use std::hint::black_box;

/// The textbook double pendulum, collected by hand (absolute angles):
/// M = [(m1+m2) l1², m2 l1 l2 cos(θ1−θ2); ·, m2 l2²],
/// h = m2 l1 l2 sin(θ1−θ2) (θ̇2², −θ̇1²), Q = −g sinθ (( m1+m2) l1, m2 l2).
struct HandWritten {
    m1: f64,
    m2: f64,
    l1: f64,
    l2: f64,
    g: f64,
}

impl HandWritten {
    #[inline]
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
    ) -> (Matrix2<f64>, Vector2<f64>) {
        let (s1, c1) = q[0].sin_cos();
        let (s2, c2) = q[1].sin_cos();
        // cos(θ1−θ2) and sin(θ1−θ2) from the sines and cosines already computed.
        let c12 = c1 * c2 + s1 * s2;
        let s12 = s1 * c2 - c1 * s2;
        let m12 = self.m1 + self.m2;
        let k = self.m2 * self.l1 * self.l2;
        let m = Matrix2::new(
            m12 * self.l1 * self.l1,
            k * c12,
            k * c12,
            self.m2 * self.l2 * self.l2,
        );
        let rhs = Vector2::new(
            -k * s12 * v[1] * v[1] - self.g * m12 * self.l1 * s1,
            k * s12 * v[0] * v[0] - self.g * self.m2 * self.l2 * s2,
        );
        (m, rhs)
    }
}

/// The generic 10-link planar pendulum (distinct masses and lengths): the workload
/// the issue compares against CasADi (~8,800 instructions, ~2.8 µs for M + bias)
/// and a hand-collected form (~1,100 instructions, ~0.3 µs).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(th1, th2, th3, th4, th5, th6, th7, th8, th9, th10),
    define(
        x1 = l1 * sin(th1), y1 = -l1 * cos(th1),
        x2 = x1 + l2 * sin(th2), y2 = y1 - l2 * cos(th2),
        x3 = x2 + l3 * sin(th3), y3 = y2 - l3 * cos(th3),
        x4 = x3 + l4 * sin(th4), y4 = y3 - l4 * cos(th4),
        x5 = x4 + l5 * sin(th5), y5 = y4 - l5 * cos(th5),
        x6 = x5 + l6 * sin(th6), y6 = y5 - l6 * cos(th6),
        x7 = x6 + l7 * sin(th7), y7 = y6 - l7 * cos(th7),
        x8 = x7 + l8 * sin(th8), y8 = y7 - l8 * cos(th8),
        x9 = x8 + l9 * sin(th9), y9 = y8 - l9 * cos(th9),
        x10 = x9 + l10 * sin(th10), y10 = y9 - l10 * cos(th10),
    ),
    point(b1, mass = m1, at = [x1, y1]),
    point(b2, mass = m2, at = [x2, y2]),
    point(b3, mass = m3, at = [x3, y3]),
    point(b4, mass = m4, at = [x4, y4]),
    point(b5, mass = m5, at = [x5, y5]),
    point(b6, mass = m6, at = [x6, y6]),
    point(b7, mass = m7, at = [x7, y7]),
    point(b8, mass = m8, at = [x8, y8]),
    point(b9, mass = m9, at = [x9, y9]),
    point(b10, mass = m10, at = [x10, y10]),
    gravity = [0, -g],
)]
struct Chain10 {
    m1: f64,
    l1: f64,
    m2: f64,
    l2: f64,
    m3: f64,
    l3: f64,
    m4: f64,
    l4: f64,
    m5: f64,
    l5: f64,
    m6: f64,
    l6: f64,
    m7: f64,
    l7: f64,
    m8: f64,
    l8: f64,
    m9: f64,
    l9: f64,
    m10: f64,
    l10: f64,
    g: f64,
}

/// The generated double pendulum against the hand-written one.
fn double_pendulum(c: &mut Criterion) {
    let (m1, m2, l1, l2, g) = (1.0, 1.5, 1.0, 0.7, 9.81);
    let generated = catalog::DoublePendulum { m1, m2, l1, l2, g };
    let hand = HandWritten { m1, m2, l1, l2, g };
    let q = Vector2::new(0.7, -1.9);
    let v = Vector2::new(1.3, 0.4);

    // Same numbers before timing anything.
    let (mg, rg) = generated.mass_matrix_and_rhs(&q, &v, 0.0);
    let (mh, rh) = hand.mass_matrix_and_rhs(&q, &v);
    assert!(
        (mg - mh).norm() < 1e-12 && (rg - rh).norm() < 1e-12,
        "generated and hand-written disagree"
    );

    let mut group = c.benchmark_group("double_pendulum_M_and_rhs");
    group.bench_function("generated", |b| {
        b.iter(|| generated.mass_matrix_and_rhs(black_box(&q), black_box(&v), black_box(0.0)))
    });
    group.bench_function("hand_written", |b| {
        b.iter(|| hand.mass_matrix_and_rhs(black_box(&q), black_box(&v)))
    });
    group.finish();

    let mut group = c.benchmark_group("double_pendulum_M_then_h");
    group.bench_function("generated", |b| {
        b.iter(|| {
            let m = generated.mass_matrix(black_box(&q), 0.0);
            let h = generated.bias(black_box(&q), black_box(&v), 0.0);
            (m, h)
        })
    });
    group.finish();
}

/// The 10-link chain: M and Q − h, and the accelerations.
fn chain10(c: &mut Criterion) {
    let chain = Chain10 {
        m1: 1.0,
        l1: 0.5,
        m2: 1.1,
        l2: 0.6,
        m3: 0.9,
        l3: 0.4,
        m4: 1.2,
        l4: 0.5,
        m5: 1.0,
        l5: 0.7,
        m6: 0.8,
        l6: 0.5,
        m7: 1.3,
        l7: 0.3,
        m8: 1.0,
        l8: 0.6,
        m9: 0.7,
        l9: 0.5,
        m10: 1.1,
        l10: 0.4,
        g: 9.81,
    };
    let q = nalgebra::SVector::<f64, 10>::from_fn(|i, _| 0.3 * (i as f64 + 1.0).sin());
    let v = nalgebra::SVector::<f64, 10>::from_fn(|i, _| 0.5 * (i as f64 + 2.0).cos());
    let mut group = c.benchmark_group("chain10");
    group.bench_function("M_and_rhs", |b| {
        b.iter(|| chain.mass_matrix_and_rhs(black_box(&q), black_box(&v), black_box(0.0)))
    });
    group.bench_function("accelerations", |b| {
        b.iter(|| lagrange::accelerations(&chain, black_box(&q), black_box(&v), black_box(0.0)))
    });
    group.finish();
}

fn rolling_sphere(c: &mut Criterion) {
    // C5, the rolling sphere: accelerations from the multiplier form (6 coordinates,
    // 3 constraint rows, saddle point by the range-space method) vs the reduced
    // form (5 coordinates, 3 speeds, one 3×3 Cholesky), at the same state.
    let (m, a) = (2.0, 0.3);
    let full = catalog::constrained::RollingSphere {
        m,
        j: 0.4 * m * a * a,
        a,
        g: 9.81,
    };
    let reduced = catalog::constrained::RollingSphereReduced {
        m,
        j: full.j,
        a,
        g: 9.81,
    };
    let rd = lagrange::ReducedDynamics::<_, f64, 3>::new(&reduced);
    let q5 = nalgebra::SVector::<f64, 5>::from([0.1, 0.2, 0.2, 0.9, 0.1]);
    let u = nalgebra::SVector::<f64, 3>::from([1.5, -0.7, 4.0]);
    let v5 = rd.velocities(0.0, &q5, &u).expect("regular rows");
    let q6 = nalgebra::SVector::<f64, 6>::from([q5[0], q5[1], a, q5[2], q5[3], q5[4]]);
    let v6 = nalgebra::SVector::<f64, 6>::from([v5[0], v5[1], 0.0, v5[2], v5[3], v5[4]]);
    let cd = lagrange::ConstrainedDynamics::new(&full);
    let mut group = c.benchmark_group("rolling_sphere_accelerations");
    group.bench_function("multipliers", |b| {
        b.iter(|| cd.solve(black_box(0.0), black_box(&q6), black_box(&v6)))
    });
    group.bench_function("reduced", |b| {
        b.iter(|| rd.solve(black_box(0.0), black_box(&q5), black_box(&v5)))
    });
    group.finish();
}

criterion_group!(benches, double_pendulum, chain10, rolling_sphere);
criterion_main!(benches);

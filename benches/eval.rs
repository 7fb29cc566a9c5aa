//! Generated vs hand-written: M and h (and the joint M, Q − h the integrators call)
//! of the planar double pendulum, evaluated in the same run, so the ratio is
//! meaningful on a shared machine.

#[path = "../examples/catalog/mod.rs"]
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

fn eval(c: &mut Criterion) {
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

criterion_group!(benches, eval);
criterion_main!(benches);

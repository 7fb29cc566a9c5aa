//! 3×3 matrices and 3-vectors of expressions, shared by the rotations of the
//! lowering, the generic derivation and the tree recursions (so no stage
//! imports another for them): one copy of each product, in the order of
//! operations the derivation has always used (node order shows in the emitted
//! code).

use lagrange_symbolic::{Context, Expr as Sym};

/// A 3×3 matrix of expressions, row-major.
pub type Mat3 = [[Sym; 3]; 3];

/// cos and sin of an angle: exactly 0 and ±1 at a constant that is a
/// multiple of π/2 to within a few ulp. `pi / 2` in a description is a float
/// whose cosine is 6e-17, not 0; the exact zeros let the products they enter
/// vanish at construction (a robot's quarter-turn placements). Any other
/// constant angle gives two floats.
pub fn cos_sin(ctx: &mut Context, angle: Sym) -> (Sym, Sym) {
    if let Some(v) = ctx.as_f64(angle) {
        let k = (v / std::f64::consts::FRAC_PI_2).round();
        let off = (v - k * std::f64::consts::FRAC_PI_2).abs();
        if off <= 4.0 * f64::EPSILON * v.abs().max(1.0) {
            let (c, s) = match (k as i64).rem_euclid(4) {
                0 => (1, 0),
                1 => (0, 1),
                2 => (-1, 0),
                _ => (0, -1),
            };
            return (ctx.int(c), ctx.int(s));
        }
        // Any other constant angle (the Panda hand's π/4, the xArm7's
        // 1.5708) evaluated here, not per call: the placement's products
        // with other constants fold.
        return (ctx.float(v.cos()), ctx.float(v.sin()));
    }
    (ctx.cos(angle), ctx.sin(angle))
}

/// The axial vector of the skew part of `w`, ½(w₂₁ − w₁₂, w₀₂ − w₂₀,
/// w₁₀ − w₀₁), each entry simplified: ω from Rᵀ Ṙ, an axis from R₀ᵀ R′.
pub fn vee(ctx: &mut Context, w: &Mat3) -> [Sym; 3] {
    let half = ctx.rational(1, 2);
    [(2, 1), (0, 2), (1, 0)].map(|(a, b)| {
        let d = ctx.sub(w[a][b], w[b][a]);
        let d = ctx.mul(half, d);
        ctx.simplify(d)
    })
}

/// Aᵀ (no new nodes: entries are only moved).
pub fn transpose(a: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[j][i]))
}

/// a · b, the products summed in order.
pub fn dot(ctx: &mut Context, a: &[Sym], b: &[Sym]) -> Sym {
    let terms: Vec<Sym> = a.iter().zip(b).map(|(&x, &y)| ctx.mul(x, y)).collect();
    ctx.sum(&terms)
}

/// a × b.
pub fn cross(ctx: &mut Context, a: [Sym; 3], b: [Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| {
        let j = (i + 1) % 3;
        let k = (i + 2) % 3;
        let p = ctx.mul(a[j], b[k]);
        let m = ctx.mul(a[k], b[j]);
        ctx.sub(p, m)
    })
}

/// A v.
pub fn mat_vec(ctx: &mut Context, a: &Mat3, v: [Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| dot(ctx, &a[i], &v))
}

/// A B.
pub fn mat_mul(ctx: &mut Context, a: &Mat3, b: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| dot(ctx, &a[i], &[b[0][j], b[1][j], b[2][j]])))
}

/// \[v\]×, the matrix of v × ·.
pub fn skew(ctx: &mut Context, [x, y, z]: [Sym; 3]) -> Mat3 {
    let zero = ctx.zero();
    let nx = ctx.neg(x);
    let ny = ctx.neg(y);
    let nz = ctx.neg(z);
    [[zero, nz, y], [z, zero, nx], [ny, x, zero]]
}

/// R(θ) = 1 + \[θ\]× + ½\[θ\]×², the exponential map to the second order: a free
/// orientation's chart as the lowering writes it and the tree reads it.
pub fn second_order_turn(ctx: &mut Context, theta: [Sym; 3]) -> Mat3 {
    let k = skew(ctx, theta);
    let k2 = mat_mul(ctx, &k, &k);
    let half = ctx.rational(1, 2);
    let zero = ctx.zero();
    let one = ctx.one();
    [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let id = if i == j { one } else { zero };
            let s2 = ctx.mul(half, k2[i][j]);
            ctx.sum(&[id, k[i][j], s2])
        })
    })
}

/// m(|d|² E − d dᵀ): the inertia about the origin of a point mass m at d,
/// which is what the parallel-axis theorem adds to an inertia tensor moved
/// from a body's centre of mass to a point at −d from it (and subtracts
/// moving it back).
pub fn parallel_axis(ctx: &mut Context, mass: Sym, d: [Sym; 3]) -> Mat3 {
    let squares: Vec<Sym> = d.iter().map(|&x| ctx.mul(x, x)).collect();
    let norm = ctx.sum(&squares);
    [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let outer = ctx.mul(d[i], d[j]);
            let e = if i == j {
                ctx.sub(norm, outer)
            } else {
                ctx.neg(outer)
            };
            ctx.mul(mass, e)
        })
    })
}

/// R(q) of a unit quaternion (w, x, y, z), body axes to the parent's.
pub fn quaternion_matrix(ctx: &mut Context, [w, x, y, z]: [Sym; 4]) -> Mat3 {
    let two = ctx.int(2);
    let one = ctx.one();
    let mut product = |a: Sym, b: Sym| {
        let p = ctx.mul(a, b);
        ctx.mul(two, p)
    };
    let xx = product(x, x);
    let yy = product(y, y);
    let zz = product(z, z);
    let xy = product(x, y);
    let xz = product(x, z);
    let yz = product(y, z);
    let wx = product(w, x);
    let wy = product(w, y);
    let wz = product(w, z);
    let diagonal = |ctx: &mut Context, a: Sym, b: Sym| {
        let s = ctx.add(a, b);
        ctx.sub(one, s)
    };
    [
        [diagonal(ctx, yy, zz), ctx.sub(xy, wz), ctx.add(xz, wy)],
        [ctx.add(xy, wz), diagonal(ctx, xx, zz), ctx.sub(yz, wx)],
        [ctx.sub(xz, wy), ctx.add(yz, wx), diagonal(ctx, xx, yy)],
    ]
}

/// Whether an inertia tensor [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] is that of some
/// rigid body: S = tr(I)/2·E − I (the second moments ∫ r rᵀ dm) positive
/// semidefinite, by all its principal minors, to `round_off` relative.
pub fn second_moments_psd(v: &[f64], round_off: f64) -> bool {
    let h = 0.5 * (v[0] + v[1] + v[2]);
    let s = [
        [h - v[0], -v[3], -v[4]],
        [-v[3], h - v[1], -v[5]],
        [-v[4], -v[5], h - v[2]],
    ];
    let tol = round_off * h.abs().max(f64::MIN_POSITIVE);
    let minor = |i: usize, j: usize| s[i][i] * s[j][j] - s[i][j] * s[j][i];
    let det = s[0][0] * minor(1, 2) - s[0][1] * (s[1][0] * s[2][2] - s[1][2] * s[2][0])
        + s[0][2] * (s[1][0] * s[2][1] - s[1][1] * s[2][0]);
    (0..3).all(|i| s[i][i] >= -tol)
        && [(0, 1), (0, 2), (1, 2)]
            .iter()
            .all(|&(i, j)| minor(i, j) >= -tol * h.abs())
        && det >= -tol * h * h
}

//! Helpers shared by the symbolic-model tests: parsing a description, random
//! states, and evaluation of model expressions at them.
#![allow(dead_code)]

use lagrange_codegen::mechanics::Model;
use lagrange_symbolic::{Symbol, SymbolKind};

/// A deterministic pseudo-random sequence (no dependency needed for a handful of points).
pub struct Lcg(pub u64);
impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    }
}

pub struct Point {
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub t: f64,
    pub params: Vec<f64>,
    /// Values for the reduced form's speeds, if any.
    pub u: Vec<f64>,
    /// A unit quaternion (w, x, y, z) per free orientation.
    pub quaternions: Vec<[f64; 4]>,
}

/// The value of a free orientation's quaternion symbol `s`, if it is one.
fn quaternion_value(model: &Model, p: &Point, s: Symbol) -> Option<f64> {
    model
        .variables
        .orientations
        .iter()
        .enumerate()
        .find_map(|(k, o)| {
            let c = o
                .quaternion
                .iter()
                .position(|&e| model.ctx.as_symbol(e) == Some(s))?;
            Some(p.quaternions[k][c])
        })
}

pub fn env<'a>(model: &'a Model, p: &'a Point) -> impl Fn(Symbol) -> f64 + 'a {
    move |s| match model.ctx.symbol_kind(s) {
        SymbolKind::Coordinate(i) => p.q[i],
        SymbolKind::Velocity(i) => p.v[i],
        SymbolKind::Time => p.t,
        SymbolKind::Parameter(i) => p.params[i],
        SymbolKind::Free => quaternion_value(model, p, s).unwrap_or(f64::NAN),
        SymbolKind::Acceleration(_) | SymbolKind::Input(_) => f64::NAN,
    }
}

pub fn model(src: &str) -> Model {
    let input: syn::DeriveInput = syn::parse_str(src).expect("test input parses");
    match lagrange_codegen::model(&input) {
        Ok(m) => m,
        Err(e) => panic!("derivation failed: {e}"),
    }
}

pub fn random_point(model: &Model, rng: &mut Lcg) -> Point {
    let n = model.dof();
    Point {
        q: (0..n).map(|_| 1.5 * rng.next()).collect(),
        v: (0..n).map(|_| 2.0 * rng.next()).collect(),
        t: 1.5 + rng.next(),
        params: model
            .variables
            .parameters
            .iter()
            .map(|_| 1.0 + 0.5 * rng.next())
            .collect(),
        u: model
            .constraints
            .reduced
            .as_ref()
            .map_or(Vec::new(), |r| r.names.iter().map(|_| rng.next()).collect()),
        quaternions: model
            .variables
            .orientations
            .iter()
            .map(|_| {
                let q = [0; 4].map(|_| rng.next());
                let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
                q.map(|x| x / norm)
            })
            .collect(),
    }
}

pub fn eval(model: &Model, e: lagrange_symbolic::Expr, p: &Point) -> f64 {
    model.ctx.eval(e, &env(model, p))
}

pub fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

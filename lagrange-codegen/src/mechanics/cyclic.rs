//! Which coordinates are cyclic (ignorable): read by none of the derived
//! expressions — M, h, Q, Q − h, the energies and the integral, the inputs'
//! terms, every constraint row and the reduced form's rows, and the optional
//! outputs — so that they enter the motion only through their rates.
//!
//! A coordinate whose symbol appears in none of them is cyclic outright. One
//! whose symbol appears may still cancel: an axisymmetric wheel's spin
//! contributes a(c ω₁ − s ω₃)² + a(s ω₁ + c ω₃)² to T, which the engine does
//! not fold to a(ω₁² + ω₃²), so its angle stays in M though M does not depend
//! on it. For those the expressions are evaluated, as one program, at a few
//! pseudo-random states and again with only that coordinate moved: equal values
//! everywhere (to rounding) are a zero test in the Schwartz–Zippel manner, the
//! way computer algebra tests identities it cannot simplify. The states are
//! fixed, so the answer (and the emitted code) is the same on every build.

use std::collections::HashSet;

use lagrange_symbolic::{Context, Expr as Sym, Program, Symbol, SymbolKind};

use super::model::Model;

/// `cyclic[j]`: no derived expression depends on q_j.
pub(super) fn cyclic(model: &Model) -> Vec<bool> {
    let mut cyclic = read_nowhere(model);
    // θ is zero in every output, but an orientation's angular velocity is no
    // cyclic coordinate's rate.
    for c in cyclic.iter_mut().skip(model.variables.coordinates.len()) {
        *c = false;
    }
    cyclic
}

/// Which coordinates no output reads (or reads only in terms that cancel).
fn read_nowhere(model: &Model) -> Vec<bool> {
    let ctx = &model.ctx;
    let outputs = model.expressions();
    let read = reached(ctx, outputs.clone());
    let q = ctx.coordinates();
    let appears: Vec<bool> = q.iter().map(|x| read.contains(x)).collect();
    if !appears.iter().any(|&a| a) {
        return vec![true; q.len()];
    }
    let program = Program::new(ctx, &outputs);
    let states: Vec<Vec<f64>> = (0..STATES)
        .map(|k| program.eval(ctx, &|s| state(ctx, s, k, None)))
        .collect();
    (0..q.len())
        .map(|j| {
            !appears[j] || (0..STATES).all(|k| cancels(ctx, &program, &states[k as usize], j, k))
        })
        .collect()
}

/// How many states the values are compared at.
const STATES: u64 = 3;

/// Whether the outputs at state `k` with q_j moved equal `base`, those at state
/// `k`. A value that is not a number in both is no evidence either way; in one
/// only, it is a difference.
fn cancels(ctx: &Context, program: &Program, base: &[f64], j: usize, k: u64) -> bool {
    let moved = program.eval(ctx, &|s| state(ctx, s, k, Some(j)));
    base.iter()
        .zip(&moved)
        .all(|(&a, &b)| match (a.is_nan(), b.is_nan()) {
            (true, true) => true,
            (false, false) => (a - b).abs() <= 1e-8 * a.abs().max(b.abs()).max(1.0),
            _ => false,
        })
}

/// The value of symbol `s` at state `k`, with coordinate `moved` (if any)
/// moved by a step of its own: coordinates in (−1.5, 1.5), everything else in
/// (0.5, 1.5) so that square roots and divisions of physical quantities stay
/// defined.
fn state(ctx: &Context, s: Symbol, k: u64, moved: Option<usize>) -> f64 {
    let unit = |salt: u64| {
        let mut h: u64 = 0xcbf2_9ce4_8422_2325 ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        for b in ctx.symbol_name(s).bytes().chain(k.to_le_bytes()) {
            h = (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
        (h >> 11) as f64 / (1u64 << 53) as f64
    };
    match ctx.symbol_kind(s) {
        SymbolKind::Coordinate(i) => {
            let x = 3.0 * unit(0) - 1.5;
            if moved == Some(i) {
                x + 0.5 + unit(1)
            } else {
                x
            }
        }
        _ => 0.5 + unit(2),
    }
}

/// Every node reachable from `roots`.
fn reached(ctx: &Context, roots: Vec<Sym>) -> HashSet<Sym> {
    let mut seen = HashSet::new();
    let mut stack = roots;
    while let Some(x) = stack.pop() {
        if seen.insert(x) {
            stack.extend(ctx.node(x).children());
        }
    }
    seen
}

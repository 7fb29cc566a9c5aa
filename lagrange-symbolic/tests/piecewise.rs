//! The piecewise form `select(test, a, b)` and what is built from it (sign,
//! min, max): values at and around the switch, folding, derivatives against
//! central differences away from the switch, and the straight-line program
//! agreeing with the tree.

use lagrange_symbolic::{Context, Expr, Program, Symbol};
use proptest::prelude::*;

/// x, y as coordinates; the environment maps them to the given values.
fn setup() -> (Context, Expr, Expr) {
    let mut cx = Context::new();
    let x = cx.coordinate("x");
    let y = cx.coordinate("y");
    (cx, x, y)
}

/// e at x = xv, y = yv (x and y are the first two symbols made).
fn eval_at(cx: &Context, e: Expr, xv: f64, yv: f64) -> f64 {
    cx.eval(e, &|s: Symbol| match cx.symbol_name(s) {
        "x" => xv,
        "y" => yv,
        _ => f64::NAN,
    })
}

#[test]
fn ties_and_signs() {
    let (mut cx, x, y) = setup();
    let s = cx.sign(x);
    let (mn, mx) = (cx.min(x, y), cx.max(x, y));
    assert_eq!(eval_at(&cx, s, 0.0, 0.0), 0.0);
    assert_eq!(eval_at(&cx, s, -2.0, 0.0), -1.0);
    assert_eq!(eval_at(&cx, s, 3.0, 0.0), 1.0);
    assert_eq!(eval_at(&cx, mn, 1.0, 2.0), 1.0);
    assert_eq!(eval_at(&cx, mx, 1.0, 2.0), 2.0);
    // At a tie both give the first argument.
    assert_eq!(eval_at(&cx, mn, 1.5, 1.5), 1.5);
    assert_eq!(eval_at(&cx, mx, 1.5, 1.5), 1.5);
}

#[test]
fn constant_tests_and_equal_branches_fold() {
    let (mut cx, x, y) = setup();
    let two = cx.int(2);
    let minus = cx.int(-1);
    assert_eq!(cx.select(two, x, y), x);
    assert_eq!(cx.select(minus, x, y), y);
    assert_eq!(cx.select(x, y, y), y);
    // d sign(x)/dx = 0 folds away entirely.
    let s = cx.sign(x);
    let d = cx.diff(s, x);
    assert!(cx.is_zero(d), "{}", cx.display(d));
    // d|x|/dx = sign(x): 0 at 0, not 0/0.
    let a = cx.func(lagrange_symbolic::Func::Abs, x);
    let da = cx.diff(a, x);
    assert_eq!(eval_at(&cx, da, 0.0, 0.0), 0.0);
    assert_eq!(eval_at(&cx, da, -0.5, 0.0), -1.0);
}

#[test]
fn display_and_program_listing_show_the_condition() {
    let (mut cx, x, y) = setup();
    let m = cx.max(x, y);
    let text = cx.display(m);
    assert!(text.contains("if") && text.contains("> 0"), "{text}");
    let latex = cx.latex(m);
    assert!(latex.contains("\\begin{cases}"), "{latex}");
}

proptest! {
    /// A piecewise expression with nonlinear branches: the program equals the
    /// tree everywhere, and the derivative equals central differences away
    /// from the switching surface.
    #[test]
    fn derivative_and_program_agree(xv in -3.0f64..3.0, yv in -3.0f64..3.0) {
        let (mut cx, x, y) = setup();
        let xy = cx.mul(x, y);
        let sx = cx.sin(x);
        let sq = cx.mul(y, y);
        let test = cx.sub(sx, y);
        let e = cx.select(test, xy, sq);
        let clamp_lo = cx.int(-1);
        let clamp_hi = cx.int(1);
        let low = cx.max(x, clamp_lo);
        let clamped = cx.min(low, clamp_hi);
        let f = cx.add(e, clamped);
        let prog = Program::new(&cx, &[f]);
        let tree = eval_at(&cx, f, xv, yv);
        let run = prog.eval(&cx, &|s| if cx.symbol_name(s) == "x" { xv } else { yv })[0];
        prop_assert_eq!(tree.to_bits(), run.to_bits());
        // Away from the switches (sin x = y, x = ±1): derivatives.
        let h = 1e-6;
        prop_assume!((xv.sin() - yv).abs() > 1e-3 && (xv.abs() - 1.0).abs() > 1e-3);
        for (wrt, (dx, dy)) in [(x, (h, 0.0)), (y, (0.0, h))] {
            let d = cx.diff(f, wrt);
            let fd = (eval_at(&cx, f, xv + dx, yv + dy) - eval_at(&cx, f, xv - dx, yv - dy)) / (2.0 * h);
            let exact = eval_at(&cx, d, xv, yv);
            prop_assert!((exact - fd).abs() < 1e-6 * (1.0 + exact.abs()), "{} vs {}", exact, fd);
        }
    }
}

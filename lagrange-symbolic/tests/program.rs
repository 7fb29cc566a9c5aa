//! Straight-line programs: cost model, sharing, emission, and the target
//! workload (the n-link planar pendulum).

use lagrange_symbolic::{Context, EmitConfig, Expr, Program, Symbol};
use proc_macro2::TokenStream;
use quote::quote;

/// Mass matrix (upper triangle, row-major) and bias `h = Σ m Jᵀ κ + ∂V/∂q`
/// of an n-link planar pendulum with absolute angles, built the way the
/// mechanics stage does (Jacobians by `diff`, κ by `time_derivative`).
fn pendulum(cx: &mut Context, n: usize) -> (Vec<Expr>, Vec<Expr>) {
    let q: Vec<Expr> = (0..n)
        .map(|i| cx.coordinate(&format!("theta{i}")))
        .collect();
    let m: Vec<Expr> = (0..n).map(|i| cx.parameter(&format!("m{i}"))).collect();
    let l: Vec<Expr> = (0..n).map(|i| cx.parameter(&format!("l{i}"))).collect();
    let g = cx.parameter("g");
    let accel_zero: Vec<(Expr, Expr)> = {
        let z = cx.zero();
        cx.accelerations().into_iter().map(|a| (a, z)).collect()
    };
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    let (mut x, mut y) = (cx.zero(), cx.zero());
    for i in 0..n {
        let s = cx.sin(q[i]);
        let c = cx.cos(q[i]);
        let ls = cx.mul(l[i], s);
        let lc = cx.mul(l[i], c);
        x = cx.add(x, ls);
        y = cx.sub(y, lc);
        xs.push(x);
        ys.push(y);
    }
    let mut mass = Vec::new();
    for i in 0..n {
        for j in i..n {
            let mut terms = Vec::new();
            for nu in 0..n {
                let (jxi, jxj) = (cx.diff(xs[nu], q[i]), cx.diff(xs[nu], q[j]));
                let (jyi, jyj) = (cx.diff(ys[nu], q[i]), cx.diff(ys[nu], q[j]));
                let a = cx.mul(jxi, jxj);
                let b = cx.mul(jyi, jyj);
                let s = cx.add(a, b);
                terms.push(cx.mul(m[nu], s));
            }
            let e = cx.sum(&terms);
            mass.push(e);
        }
    }
    let mut bias = Vec::new();
    for &qi in &q {
        let mut terms = Vec::new();
        for nu in 0..n {
            for pos in [xs[nu], ys[nu]] {
                let v = cx.time_derivative(pos);
                let a = cx.time_derivative(v);
                let kappa = cx.substitute(a, &accel_zero);
                let jac = cx.diff(pos, qi);
                let t = cx.product(&[m[nu], jac, kappa]);
                terms.push(t);
            }
            let dy = cx.diff(ys[nu], qi);
            terms.push(cx.product(&[m[nu], g, dy]));
        }
        bias.push(cx.sum(&terms));
    }
    (mass, bias)
}

fn env(s: Symbol) -> f64 {
    0.3 + 0.17 * (s.index() as f64 * 1.3).sin() + 0.05 * s.index() as f64
}

fn assert_close(a: f64, b: f64) {
    assert!(
        (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs())),
        "{a} vs {b}"
    );
}

fn optimised(cx: &mut Context, exprs: &[Expr]) -> Vec<Expr> {
    exprs
        .iter()
        .map(|&e| {
            let t = cx.expand_trig(e);
            let s = cx.simplify(t);
            cx.collect(s)
        })
        .collect()
}

fn check_chain(n: usize) -> (usize, usize, usize) {
    let mut cx = Context::new();
    let (mass, bias) = pendulum(&mut cx, n);
    let raw: Vec<Expr> = mass.iter().chain(&bias).copied().collect();
    let naive = Program::new(&cx, &raw).op_count();
    let opt = optimised(&mut cx, &raw);
    let mass_prog = Program::new(&cx, &opt[..mass.len()]);
    let prog = Program::new(&cx, &opt);
    let want: Vec<f64> = raw.iter().map(|&e| cx.eval(e, &env)).collect();
    for (a, b) in prog.eval(&cx, &env).into_iter().zip(want) {
        assert_close(a, b);
    }
    let ops = prog.op_count();
    assert_eq!(
        ops.call,
        2 * n,
        "one sin and one cos per coordinate: {ops:?}"
    );
    (mass_prog.op_count().total(), ops.total(), naive.total())
}

#[test]
fn three_link_pendulum_is_cheap_and_exact() {
    let (mass, all, naive) = check_chain(3);
    eprintln!("3-link: M {mass} ops, M + h {all} ops (uncollected {naive})");
    assert!(mass <= 40, "M: {mass}");
    assert!(all <= 100, "M + h: {all}");
}

#[test]
fn ten_link_pendulum_lands_near_target() {
    let (mass, all, naive) = check_chain(10);
    eprintln!("10-link: M {mass} ops, M + h {all} ops (uncollected {naive})");
    assert!(mass <= 400, "M: {mass}");
    assert!(all <= 700, "M + h: {all}");
}

#[test]
fn cost_model() {
    let mut cx = Context::new();
    let x = cx.free_symbol("x");
    let y = cx.free_symbol("y");
    let x4 = cx.powi(x, 4);
    let x3 = cx.powi(x, 3);
    let x2 = cx.powi(x, 2);
    // x^2, x^3, x^4 share the square: 3 multiplications in all
    let p = Program::new(&cx, &[x2, x3, x4]);
    assert_eq!(p.op_count().mul, 3);
    // x - y is one subtraction, -x one negation, x/y one division
    let d = cx.sub(x, y);
    let n = cx.neg(x);
    let q = cx.div(x, y);
    let p = Program::new(&cx, &[d, n, q]);
    let c = p.op_count();
    assert_eq!((c.add, c.mul, c.div, c.call), (2, 0, 1, 0));
    // 3·x·y: one multiply by the literal; y - 3xy shares 3xy
    let three = cx.int(3);
    let t = cx.product(&[three, x, y]);
    let u = cx.sub(y, t);
    let p = Program::new(&cx, &[t, u]);
    assert_eq!(p.op_count().total(), 3);
    // sqrt and its reciprocal
    let r = cx.sqrt(x);
    let ri = cx.powi(r, -1);
    let p = Program::new(&cx, &[r, ri]);
    let c = p.op_count();
    assert_eq!((c.call, c.div), (1, 1));
    let vals = p.eval(&cx, &|_| 4.0);
    assert_eq!(vals, vec![2.0, 0.5]);
    // constants and symbols cost nothing
    let p = Program::new(&cx, &[x, three]);
    assert_eq!(p.op_count().total(), 0);
}

/// The latency-weighted depth follows the longest dependent chain: a sum of
/// products is one multiplication and one fused multiply–add per further
/// term in a row; a division and a function call cost more than a product.
#[test]
fn latency_depth_follows_the_longest_chain() {
    let mut cx = Context::new();
    let xs: Vec<Expr> = (0..6).map(|i| cx.free_symbol(&format!("x{i}"))).collect();
    let p = Program::new(&cx, &[xs[0]]);
    assert_eq!(p.latency_depth(), 0);
    // x0 x1: one multiplication.
    let prod = cx.mul(xs[0], xs[1]);
    assert_eq!(Program::new(&cx, &[prod]).latency_depth(), 4);
    // x0 x1 + x2 x3 + x4 x5: a product, then two fused additions.
    let terms: Vec<Expr> = (0..3).map(|i| cx.mul(xs[2 * i], xs[2 * i + 1])).collect();
    let sum = cx.sum(&terms);
    assert_eq!(Program::new(&cx, &[sum]).latency_depth(), 4 + 4 + 4);
    // sin(x0 x1) / x2: a product, a call and a division.
    let s = cx.sin(prod);
    let q = cx.div(s, xs[2]);
    assert_eq!(Program::new(&cx, &[q]).latency_depth(), 4 + 40 + 14);
    // The deepest output sets the depth; the others run beside it.
    assert_eq!(Program::new(&cx, &[prod, q, sum]).latency_depth(), 58);
}

#[test]
fn emission_is_deterministic_and_reads_well() {
    let build = || {
        let mut cx = Context::new();
        let th = cx.coordinate("theta");
        let l = cx.parameter("l");
        let m = cx.parameter("m");
        let s = cx.sin(th);
        let c = cx.cos(th);
        let ls = cx.mul(l, s);
        let half = cx.rational(1, 2);
        let e1 = cx.product(&[half, m, ls, ls]);
        let e2 = cx.sub(ls, c);
        let e3 = cx.neg(c);
        let prog = Program::new(&cx, &[e1, e2, e3, m]);
        let symbol = |s: Symbol| match s.index() {
            0 => quote!(q[0]),
            i => {
                let id = proc_macro2::Ident::new(&format!("p{i}"), proc_macro2::Span::call_site());
                quote!(self.#id)
            }
        };
        emitted(&cx, &prog, &symbol, quote!(::lagrange::__private::func))
    };
    let (body, outs) = build();
    assert_eq!(build(), (body.clone(), outs.clone()));
    // Three reused variables: a value's variable is free after its last read.
    assert_eq!(
        body,
        "let mut _t0 ; let mut _t1 ; let mut _t2 ; \
         _t0 = self . p3 * self . p3 ; _t1 = :: lagrange :: __private :: func :: sin (q [0]) ; \
         _t2 = _t1 * _t1 ; _t0 = self . p4 * _t0 ; _t0 = _t2 * _t0 ; _t0 = 0.5f64 * _t0 ; \
         _t1 = self . p3 * _t1 ; _t2 = :: lagrange :: __private :: func :: cos (q [0]) ; \
         _t1 = _t1 - _t2 ; _t2 = - _t2 ;"
    );
    assert_eq!(outs, vec!["_t0", "_t1", "_t2", "self . p4"]);
}

/// A fused product's operands give their registers back at the sum that
/// reads them, so a running sum of products needs no more variables fused
/// than apart.
#[test]
fn fused_products_release_their_operands() {
    let registers = |fused_multiply_add: bool| {
        let mut cx = Context::new();
        let x = cx.coordinate("x");
        // x ← sin x · cos x + x, eight times: each product is read by the
        // sum right after it.
        let mut sum = x;
        for _ in 0..8 {
            let s = cx.sin(sum);
            let c = cx.cos(sum);
            let term = cx.mul(s, c);
            sum = cx.add(sum, term);
        }
        let prog = Program::new(&cx, &[sum]);
        let body = with_one_symbol(fused_multiply_add, |cfg| prog.emit(&cx, cfg).0);
        let body = body.to_string();
        assert_eq!(body.contains("mul_add"), fused_multiply_add);
        body.matches("let mut").count()
    };
    assert!(
        registers(true) <= registers(false),
        "{} > {}",
        registers(true),
        registers(false)
    );
}

/// In pieces, a value from an earlier piece is read from the state array,
/// even as a fused product's factor, and every variable a piece writes or
/// reads is declared in it.
#[test]
fn pieces_declare_every_variable_they_use() {
    let mut cx = Context::new();
    let x = cx.coordinate("x");
    let mut terms = Vec::new();
    let mut sum = cx.sqrt(x);
    for k in 1..=12 {
        let k = cx.rational(k, 1);
        let kx = cx.mul(k, x);
        let s = cx.sin(kx);
        let c = cx.cos(kx);
        terms.push((s, c));
    }
    // The factors, read by a first output, are computed in early pieces; the
    // second output's products read them across pieces.
    let mut first = cx.sqrt(x);
    for &(s, c) in &terms {
        first = cx.add(first, s);
        first = cx.add(first, c);
    }
    for &(s, c) in terms.iter().rev() {
        let term = cx.mul(s, c);
        sum = cx.add(sum, term);
    }
    let prog = Program::new(&cx, &[first, sum]);
    let chunked = with_one_symbol(true, |cfg| prog.emit_chunked(&cx, cfg, 5, &quote!(s)))
        .expect("several pieces");
    assert!(chunked.chunks.len() > 2);
    for chunk in &chunked.chunks {
        let text = chunk.to_string();
        for word in text.split(|c: char| !(c.is_alphanumeric() || c == '_')) {
            if word.starts_with("_t") {
                assert!(
                    text.contains(&format!("let mut {word} ;")),
                    "{word} undeclared in {text}"
                );
            }
        }
    }
}

/// The program's body and outputs as text, its symbols spelled by `symbol`,
/// its functions from `function`, literals suffixed `f64`, nothing fused.
fn emitted(
    cx: &Context,
    prog: &Program,
    symbol: &dyn Fn(Symbol) -> TokenStream,
    function: TokenStream,
) -> (String, Vec<String>) {
    let constant = |v: f64| {
        let lit = proc_macro2::Literal::f64_suffixed(v);
        quote!(#lit)
    };
    let cfg = EmitConfig {
        symbol,
        constant: &constant,
        function: &function,
        temp_prefix: "_t",
        fused_multiply_add: false,
    };
    let (body, outs) = prog.emit(cx, &cfg);
    (
        body.to_string(),
        outs.iter().map(|o| o.to_string()).collect(),
    )
}

/// `f` given an emission whose every symbol reads `q[0]`, with literals
/// suffixed `f64` and functions from the module `func`.
fn with_one_symbol<R>(fused_multiply_add: bool, f: impl FnOnce(&EmitConfig) -> R) -> R {
    let symbol = |_: Symbol| quote!(q[0]);
    let constant = |v: f64| {
        let lit = proc_macro2::Literal::f64_suffixed(v);
        quote!(#lit)
    };
    let function: TokenStream = quote!(func);
    f(&EmitConfig {
        symbol: &symbol,
        constant: &constant,
        function: &function,
        temp_prefix: "_t",
        fused_multiply_add,
    })
}

/// A subtree's composite gathered leaves first, c_k = x_k y_k + c_{k+1}, is
/// stored flat: each c_k holds every term below it. Lowered, c_k starts from
/// c_{k+1}'s value and adds one product, n − 1 additions for all n of them
/// rather than n (n − 1) / 2; a negated part and a constant part are taken
/// as well, and a part whose constant differs is not.
#[test]
fn a_sum_that_holds_another_adds_only_the_rest() {
    let mut cx = Context::new();
    let n = 12;
    let xs: Vec<Expr> = (0..n).map(|k| cx.free_symbol(&format!("x{k}"))).collect();
    let ys: Vec<Expr> = (0..n).map(|k| cx.free_symbol(&format!("y{k}"))).collect();
    let mut composites = vec![cx.mul(xs[n - 1], ys[n - 1])];
    for k in (0..n - 1).rev() {
        let own = cx.mul(xs[k], ys[k]);
        let below = *composites.last().expect("one composite");
        composites.push(cx.add(own, below));
    }
    // The root first, as a depth-first walk from the outputs meets it.
    composites.reverse();
    let p = Program::new(&cx, &composites);
    assert_eq!((p.op_count().add, p.op_count().mul), (n - 1, n));
    for (a, &e) in p.eval(&cx, &env).into_iter().zip(&composites) {
        assert_close(a, cx.eval(e, &env));
    }

    // −x₀ − x₁ − x₂ lowers as a negated sum, which −x₀ − x₁ − x₂ + y₀ holds.
    let minus: Vec<Expr> = xs[..3].iter().map(|&x| cx.neg(x)).collect();
    let falling = cx.sum(&minus);
    let whole = cx.add(falling, ys[0]);
    // x₀ + x₁ + 2 and x₀ + x₁ + x₂ + 2 share the constant; + 3 does not.
    let two = cx.int(2);
    let three = cx.int(3);
    let small = cx.sum(&[xs[0], xs[1], two]);
    let large = cx.sum(&[xs[0], xs[1], xs[2], two]);
    let other = cx.sum(&[xs[0], xs[1], xs[2], three]);
    let outputs = [falling, whole, small, large, other];
    let p = Program::new(&cx, &outputs);
    for (a, &e) in p.eval(&cx, &env).into_iter().zip(&outputs) {
        assert_close(a, cx.eval(e, &env));
    }
    // falling: two additions and the negation; whole: y₀ − (x₀ + x₁ + x₂);
    // small: its first addition falling's, then + 2; large: small + x₂;
    // other: falling's two additions, then + 3.
    assert_eq!(p.op_count().add, 3 + 1 + 1 + 1 + 1, "{:?}", p.op_count());
}

/// The sines and cosines of two or more angles known before the first of
/// them are computed by one `sin_cos_many` call where that first one was,
/// each sine and cosine read from its arrays; one angle alone keeps its
/// calls.
#[test]
fn sines_and_cosines_of_several_angles_are_computed_together() {
    let emit = |two: bool| {
        let mut cx = Context::new();
        let (a, b) = (cx.coordinate("a"), cx.coordinate("b"));
        let (sa, ca) = (cx.sin(a), cx.cos(a));
        let mut outputs = vec![cx.mul(sa, ca), ca];
        if two {
            let cb = cx.cos(b);
            outputs.push(cx.mul(sa, cb));
        }
        let prog = Program::new(&cx, &outputs);
        let symbol = |s: Symbol| {
            let i = s.index();
            quote!(q[#i])
        };
        emitted(&cx, &prog, &symbol, quote!(func)).0
    };
    let together = emit(true);
    assert_eq!(together.matches("sin_cos_many").count(), 1, "{together}");
    // Before the first sine, a's and b's (b's symbol is not the second:
    // coordinates come with their rates).
    let call = together.find("let (_tsin , _tcos) = func :: sin_cos_many ([q [0usize] , q [");
    assert!(
        call.is_some_and(|at| at < together.find("_tsin [0]").unwrap()),
        "{together}"
    );
    for read in ["_tsin [0]", "_tcos [0]", "_tcos [1]"] {
        assert!(together.contains(read), "{read} in {together}");
    }
    assert!(!together.contains("func :: sin (") && !together.contains("func :: cos ("));
    let alone = emit(false);
    assert!(!alone.contains("sin_cos_many"), "{alone}");
    assert!(
        alone.contains("func :: sin (q [0usize])") && alone.contains("func :: cos (q [0usize])")
    );
}

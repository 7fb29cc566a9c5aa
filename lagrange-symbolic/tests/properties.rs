//! Property tests over random expression trees: derivatives against finite
//! differences, value preservation of every rewrite, hash-consing.

use lagrange_symbolic::{Context, Expr, Func, Program, Symbol};
use proptest::prelude::*;

/// A random expression over three symbols. Domains are kept safe by
/// construction: logarithms, roots and denominators see `u² + 1`.
#[derive(Clone, Debug)]
enum Tree {
    Sym(usize),
    Int(i64),
    Half,
    Add(Box<Tree>, Box<Tree>),
    Sub(Box<Tree>, Box<Tree>),
    Mul(Box<Tree>, Box<Tree>),
    DivSafe(Box<Tree>, Box<Tree>),
    Powi(Box<Tree>, i64),
    Call(Func, Box<Tree>),
    SqrtSafe(Box<Tree>),
    LnSafe(Box<Tree>),
    Atan2Safe(Box<Tree>, Box<Tree>),
}

fn tree() -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        (0usize..3).prop_map(Tree::Sym),
        (-3i64..=3).prop_map(Tree::Int),
        Just(Tree::Half),
    ];
    leaf.prop_recursive(4, 24, 2, |inner| {
        let b = || inner.clone().prop_map(Box::new);
        prop_oneof![
            (b(), b()).prop_map(|(a, c)| Tree::Add(a, c)),
            (b(), b()).prop_map(|(a, c)| Tree::Sub(a, c)),
            (b(), b()).prop_map(|(a, c)| Tree::Mul(a, c)),
            (b(), b()).prop_map(|(a, c)| Tree::DivSafe(a, c)),
            (b(), -2i64..=3).prop_map(|(a, n)| Tree::Powi(a, n)),
            (
                prop_oneof![
                    Just(Func::Sin),
                    Just(Func::Cos),
                    Just(Func::Atan),
                    Just(Func::Tanh)
                ],
                b()
            )
                .prop_map(|(f, a)| Tree::Call(f, a)),
            b().prop_map(Tree::SqrtSafe),
            b().prop_map(Tree::LnSafe),
            (b(), b()).prop_map(|(a, c)| Tree::Atan2Safe(a, c)),
        ]
    })
}

fn safe(cx: &mut Context, u: Expr) -> Expr {
    let u2 = cx.powi(u, 2);
    let one = cx.one();
    cx.add(u2, one)
}

fn build(cx: &mut Context, syms: &[Expr], t: &Tree) -> Expr {
    match t {
        Tree::Sym(i) => syms[*i],
        Tree::Int(v) => cx.int(*v),
        Tree::Half => cx.rational(1, 2),
        Tree::Add(a, b) => {
            let (a, b) = (build(cx, syms, a), build(cx, syms, b));
            cx.add(a, b)
        }
        Tree::Sub(a, b) => {
            let (a, b) = (build(cx, syms, a), build(cx, syms, b));
            cx.sub(a, b)
        }
        Tree::Mul(a, b) => {
            let (a, b) = (build(cx, syms, a), build(cx, syms, b));
            cx.mul(a, b)
        }
        Tree::DivSafe(a, b) => {
            let (a, b) = (build(cx, syms, a), build(cx, syms, b));
            let d = safe(cx, b);
            cx.div(a, d)
        }
        Tree::Powi(a, n) => {
            let a = build(cx, syms, a);
            if *n < 0 {
                let d = safe(cx, a);
                cx.powi(d, *n)
            } else {
                cx.powi(a, *n)
            }
        }
        Tree::Call(f, a) => {
            let a = build(cx, syms, a);
            cx.func(*f, a)
        }
        Tree::SqrtSafe(a) => {
            let a = build(cx, syms, a);
            let d = safe(cx, a);
            cx.sqrt(d)
        }
        Tree::LnSafe(a) => {
            let a = build(cx, syms, a);
            let d = safe(cx, a);
            cx.func(Func::Ln, d)
        }
        Tree::Atan2Safe(a, b) => {
            let (a, b) = (build(cx, syms, a), build(cx, syms, b));
            let d = safe(cx, b);
            cx.atan2(a, d)
        }
    }
}

fn setup() -> (Context, Vec<Expr>) {
    let mut cx = Context::new();
    let q = cx.coordinate("q");
    let p = cx.parameter("p");
    let x = cx.free_symbol("x");
    (cx, vec![q, p, x])
}

fn point(cx: &Context, syms: &[Expr], vals: [f64; 3]) -> impl Fn(Symbol) -> f64 + use<> {
    let ids: Vec<Symbol> = syms.iter().map(|&s| cx.as_symbol(s).unwrap()).collect();
    move |s| ids.iter().position(|&i| i == s).map_or(0.0, |k| vals[k])
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    if !a.is_finite() || !b.is_finite() || a.abs() > 1e8 || b.abs() > 1e8 {
        return true;
    }
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, .. ProptestConfig::default() })]

    #[test]
    fn diff_matches_finite_differences(t in tree(), vals in prop::array::uniform3(-2.0f64..2.0), k in 0usize..3) {
        let (mut cx, syms) = setup();
        let e = build(&mut cx, &syms, &t);
        let d = cx.diff(e, syms[k]);
        let h = 1e-5;
        let mut plus = vals;
        plus[k] += h;
        let mut minus = vals;
        minus[k] -= h;
        let fd = (cx.eval(e, &point(&cx, &syms, plus)) - cx.eval(e, &point(&cx, &syms, minus))) / (2.0 * h);
        let exact = cx.eval(d, &point(&cx, &syms, vals));
        prop_assert!(close(exact, fd, 1e-4), "d/d{k} {} = {} -> {exact} vs fd {fd}", cx.display(e), cx.display(d));
    }

    #[test]
    fn directional_is_the_sum_of_partials_times_rates(
        t in tree(),
        vals in prop::array::uniform3(-2.0f64..2.0),
        rates in prop::array::uniform2(-3i64..=3),
    ) {
        // Along (x0 → r0, x1 → r1); x2 has rate zero.
        let (mut cx, syms) = setup();
        let e = build(&mut cx, &syms, &t);
        let (r0, r1) = (cx.int(rates[0]), cx.int(rates[1]));
        let along = cx.directional(e, &[(syms[0], r0), (syms[1], r1)]);
        let d0 = cx.diff(e, syms[0]);
        let d1 = cx.diff(e, syms[1]);
        let (a, b) = (cx.mul(r0, d0), cx.mul(r1, d1));
        let partials = cx.add(a, b);
        let env = point(&cx, &syms, vals);
        let (x, y) = (cx.eval(along, &env), cx.eval(partials, &env));
        prop_assert!(close(x, y, 1e-9), "{} along = {x}, partials {y}", cx.display(e));
    }

    #[test]
    fn rewrites_and_programs_preserve_value(t in tree(), vals in prop::array::uniform3(-2.0f64..2.0)) {
        let (mut cx, syms) = setup();
        let e = build(&mut cx, &syms, &t);
        let env = point(&cx, &syms, vals);
        let v = cx.eval(e, &env);
        let rewritten = [cx.simplify(e), cx.collect(e), cx.expand_trig(e), cx.expand(e)];
        for r in rewritten {
            let w = cx.eval(r, &env);
            prop_assert!(close(v, w, 1e-7), "{} = {v} but {} = {w}", cx.display(e), cx.display(r));
        }
        let de = cx.diff(e, syms[0]);
        let prog = Program::new(&cx, &[e, de, rewritten[1]]);
        let out = prog.eval(&cx, &env);
        prop_assert!(close(out[0], v, 1e-9), "program {} vs {v}", out[0]);
        prop_assert!(close(out[1], cx.eval(de, &env), 1e-9));
        prop_assert!(close(out[2], v, 1e-7));
    }

    #[test]
    fn hash_consing_and_determinism(t in tree()) {
        let (mut cx, syms) = setup();
        let a = build(&mut cx, &syms, &t);
        let n = cx.len();
        let b = build(&mut cx, &syms, &t);
        prop_assert_eq!(a, b);
        prop_assert_eq!(cx.len(), n, "rebuilding must not create nodes");
        let (mut cx2, syms2) = setup();
        let c = build(&mut cx2, &syms2, &t);
        prop_assert_eq!(a, c);
        prop_assert_eq!(cx.display(a), cx2.display(c));
        let (p1, p2) = (Program::new(&cx, &[a]), Program::new(&cx2, &[c]));
        prop_assert_eq!(format!("{:?}", p1), format!("{:?}", p2));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, .. ProptestConfig::default() })]

    /// Hoisting keeps the value: the outputs evaluated with each stand-in bound
    /// to its term's value equal the originals, and no term or rewritten output
    /// hides a parameter-only part behind a coordinate.
    #[test]
    fn hoisting_preserves_value(t in tree(), u in tree(), vals in prop::array::uniform3(-2.0f64..2.0)) {
        let mut cx = Context::new();
        let syms = vec![cx.coordinate("q"), cx.parameter("p"), cx.parameter("r")];
        let a = build(&mut cx, &syms, &t);
        let b = build(&mut cx, &syms, &u);
        let h = cx.hoist(&[a, b], "__h");
        let env = point(&cx, &syms, vals);
        let values: Vec<f64> = h.terms.iter().map(|&x| cx.eval(x, &env)).collect();
        let ids: Vec<Symbol> = h.symbols.iter().map(|&s| cx.as_symbol(s).unwrap()).collect();
        let bound = |s: Symbol| match ids.iter().position(|&i| i == s) {
            Some(k) => values[k],
            None => env(s),
        };
        for (orig, new) in [a, b].into_iter().zip(&h.outputs) {
            let (v, w) = (cx.eval(orig, &env), cx.eval(*new, &bound));
            prop_assert!(close(v, w, 1e-9), "{} = {v} but hoisted {} = {w}", cx.display(orig), cx.display(*new));
        }
        for &term in &h.terms {
            prop_assert!(!cx.depends_on(term, syms[0]), "term {} depends on q", cx.display(term));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, .. ProptestConfig::default() })]

    /// Folding angle sums keeps the value, also on expanded trigonometry
    /// (where the pairs it folds come from).
    #[test]
    fn folding_angle_sums_preserves_value(t in tree(), vals in prop::array::uniform3(-2.0f64..2.0)) {
        let (mut cx, syms) = setup();
        let e = build(&mut cx, &syms, &t);
        let expanded = cx.expand_trig(e);
        let env = point(&cx, &syms, vals);
        for x in [e, expanded] {
            let f = cx.fold_angle_sums(x);
            let (v, w) = (cx.eval(x, &env), cx.eval(f, &env));
            prop_assert!(close(v, w, 1e-9), "{} = {v} but folded {} = {w}", cx.display(x), cx.display(f));
        }
    }
}

#[test]
fn angle_sums_fold_to_the_closed_forms() {
    let mut cx = Context::new();
    let (a, b, m) = (cx.coordinate("a"), cx.coordinate("b"), cx.parameter("m"));
    let (sa, ca, sb, cb) = (cx.sin(a), cx.cos(a), cx.sin(b), cx.cos(b));
    // m (cos a cos b + sin a sin b) = m cos(a − b)
    let cc = cx.product(&[m, ca, cb]);
    let ss = cx.product(&[m, sa, sb]);
    let e = cx.add(cc, ss);
    let f = cx.fold_angle_sums(e);
    assert_eq!(cx.display(f), "m*cos(a - b)");
    // 2 sin a cos b − 2 cos a sin b = 2 sin(a − b)
    let two = cx.int(2);
    let sc = cx.product(&[two, sa, cb]);
    let cs = cx.product(&[two, ca, sb]);
    let e = cx.sub(sc, cs);
    let f = cx.fold_angle_sums(e);
    assert_eq!(cx.display(f), "2*sin(a - b)");
}

//! The derived equations as text, for rustdoc, `EQUATIONS` and
//! `EQUATIONS_LATEX`: a header that says what the symbols are, then every
//! nonzero entry, as formulas while the trees are small and beyond that as
//! one straight-line listing with each shared intermediate written once as
//! `x<k> = …` (see `Program::listing`), so the text grows with the program,
//! not with the expression trees.

use std::fmt::Write;

use lagrange_symbolic::{Expr as Sym, ListingStyle, Program};

use crate::mechanics::{BiasRoute, ForwardRoute, Model};

/// The equations as plain text (header and entries) and as LaTeX, from one
/// pass over the outputs: a large system's straight-line program is built once
/// for both listings.
pub struct Texts {
    /// The plain-text listing (the emitted `EQUATIONS`).
    pub equations: String,
    /// The LaTeX listing (the emitted `EQUATIONS_LATEX`).
    pub latex: String,
}

/// The plain-text equations alone (see [`texts`]).
pub fn equations(model: &Model) -> String {
    texts(model).equations
}

/// Both texts of the model.
pub fn texts(model: &Model) -> Texts {
    let ctx = &model.ctx;
    let outputs = outputs(model);
    let exprs: Vec<Sym> = outputs.iter().map(|(_, e)| *e).collect();
    let names: Vec<String> = outputs.iter().map(|(n, _)| n.clone()).collect();
    let labels: Vec<String> = names.iter().map(|n| latex_label(n)).collect();
    let mut equations = header(model);
    let mut latex = String::from("\\begin{aligned}\n");
    if tree_size(ctx, &exprs) <= TREE_LIMIT {
        let _ = writeln!(
            equations,
            "\n{SYMMETRIC}\nEntries not listed (other than those mirror entries) are zero.\n"
        );
        // Printed with angle sums folded (cos(θ₁ − θ₂), not the products the
        // code computes), in a copy of the context so the model stays as emitted.
        let mut shown = ctx.clone();
        for ((name, label), &e) in names.iter().zip(&labels).zip(&exprs) {
            let e = shown.fold_angle_sums(e);
            let _ = writeln!(equations, "{name} = {}", shown.display(e));
            let _ = writeln!(latex, "{label} &= {} \\\\", shown.latex(e));
        }
    } else {
        let _ = writeln!(
            equations,
            "\n{SYMMETRIC}\nShared intermediates are named x<k>; entries not listed (other than those mirror entries) are zero.\n"
        );
        let program = Program::new(ctx, &exprs);
        equations.push_str(&program.listing(ctx, &names));
        latex.push_str(&program.listing_in(ctx, &labels, ListingStyle::Latex));
    }
    latex.push_str("\\end{aligned}\n");
    if let Some(base) = model
        .outputs
        .regressor
        .as_ref()
        .and_then(|r| r.base.as_ref())
    {
        base_parameters(base, &mut equations, &mut latex);
    }
    Texts { equations, latex }
}

/// `emit(regressor)`'s base parameters in closed form, after the entries.
fn base_parameters(base: &crate::mechanics::BaseForm, equations: &mut String, latex: &mut String) {
    let _ = writeln!(
        equations,
        "\nBase parameters ({} of them; Y_b pi_b = Y pi: each link's part symmetric about its joint \
         regrouped into its parent, then what random motions do not show dropped):",
        base.parameters.len()
    );
    latex.push_str("\\begin{aligned}\n");
    for p in &base.parameters {
        let _ = writeln!(equations, "{}", p.text);
        let _ = writeln!(latex, "{} \\\\", p.latex);
    }
    latex.push_str("\\end{aligned}\n");
    if !base.without_effect.is_empty() {
        let _ = writeln!(
            equations,
            "Without effect: {}",
            base.without_effect.join(", ")
        );
    }
    if !base.dependent.is_empty() {
        let _ = writeln!(
            equations,
            "Also depending on those above at this geometry (folded in by identify::BaseParameters): {}",
            base.dependent.join(", ")
        );
    }
}

/// M's lower triangle is the mirror of its upper one and is not listed, so the
/// note that unlisted entries are zero must except it.
const SYMMETRIC: &str =
    "M is symmetric: only its entries M[i][j] with i <= j are listed (M[j][i] is the same).";

/// What the symbols are: the form of the equations, q, u, the conserved
/// quantity, the route of h, the constraint and reduced rows.
fn header(model: &Model) -> String {
    let mut s = String::new();
    let args = if model.motion.rheonomic { "q, t" } else { "q" };
    match &model.inputs {
        None => {
            let _ = writeln!(s, "M({args}) q'' + h({args}, q') = Q({args}, q')");
        }
        Some(_) => {
            let _ = writeln!(
                s,
                "M({args}) q'' + h({args}, q') = Q({args}, q', u) = Q({args}, q', 0) + dQ({args}, q', u)"
            );
        }
    }
    let _ = writeln!(s, "q = ({})", model.variables.coordinates.join(", "));
    for o in &model.variables.orientations {
        let n = &o.name;
        let _ = writeln!(
            s,
            "orientation {n}: unit quaternion ({n}.w, {n}.x, {n}.y, {n}.z) in q (body axes to world), \
             angular velocity in body axes q' = ({n}.wx, {n}.wy, {n}.wz), its rate q'' = (dot({n}.wx), dot({n}.wy), dot({n}.wz)); \
             the equations hold at |q| = 1 (no chart: they are derived in the chart that moves with the body, at its centre)"
        );
    }
    let cyclic: Vec<&str> = (model
        .variables
        .coordinates
        .iter()
        .zip(&model.variables.cyclic))
    .filter_map(|(name, &c)| c.then_some(name.as_str()))
    .collect();
    if !cyclic.is_empty() {
        let _ = writeln!(
            s,
            "cyclic: {}: no equation reads their values, only their rates",
            cyclic.join(", ")
        );
    }
    if let Some(inputs) = &model.inputs {
        let _ = writeln!(
            s,
            "u = ({}): inputs supplied at run time; M, h, Q and the energies below are at u = 0",
            inputs.names.join(", ")
        );
    }
    let _ = writeln!(
        s,
        "{}",
        if model.motion.rheonomic {
            "rheonomic: the position maps depend on t; conserved (if forces are conservative): Jacobi integral T2 - T0 + V"
        } else {
            "scleronomic: conserved (if forces are conservative): T + V"
        }
    );
    let _ = writeln!(s, "{}; T kinetic, V potential energy.", route_line(model));
    if let Some(line) = forward_line(model) {
        let _ = writeln!(s, "{line}");
    }
    if let Some(c) = &model.constraints.multipliers {
        let _ = writeln!(
            s,
            "constraints (multipliers): G q' + g = 0, G q'' = gamma, rows ({}); the first {} holonomic (Phi = 0)",
            c.names.join(", "),
            c.holonomic
        );
    }
    if let Some(r) = &model.constraints.reduced {
        let _ = writeln!(
            s,
            "reduced form on the speeds u = ({}): rows A q' + b = (u, 0), rates c (A q'' = (u', 0) + c), rows ({}), solved with pivoting at run time",
            r.names.join(", "),
            r.rows.join(", ")
        );
    }
    s
}

/// Up to this many tree nodes (counted with repetition) the equations are
/// printed as formulas, which read best; beyond it as the shared listing,
/// whose size grows with the program instead of the trees.
const TREE_LIMIT: u64 = 20_000;

/// The number of nodes of the outputs written out as trees (a shared node
/// counted at every use), saturating: what printing them as formulas costs.
fn tree_size(ctx: &lagrange_symbolic::Context, outputs: &[Sym]) -> u64 {
    fn size(
        ctx: &lagrange_symbolic::Context,
        e: Sym,
        memo: &mut std::collections::HashMap<Sym, u64>,
    ) -> u64 {
        if let Some(&n) = memo.get(&e) {
            return n;
        }
        let mut n: u64 = 1;
        for c in ctx.node(e).children() {
            n = n.saturating_add(size(ctx, c, memo));
        }
        memo.insert(e, n);
        n
    }
    let mut memo = std::collections::HashMap::new();
    outputs.iter().fold(0u64, |total, &e| {
        total.saturating_add(size(ctx, e, &mut memo))
    })
}

/// Above this size the rustdoc shows a summary and points to `EQUATIONS`.
pub const DOC_CAP: usize = 256 * 1024;

/// The rustdoc text: the equations in a code block, or for a listing beyond
/// [`DOC_CAP`] its header and size, with where the full text is.
pub fn rustdoc(equations: &str, ident: &str) -> Option<String> {
    if equations.len() <= DOC_CAP {
        return None;
    }
    let header: String = equations
        .lines()
        .take_while(|l| !l.is_empty())
        .map(|l| format!("{l}\n"))
        .collect();
    Some(format!(
        "Equations of motion derived by `#[derive(Lagrangian)]`.\n\n```text\n{header}```\n\n\
         The listing has {} lines ({} KiB), more than these docs show; \
         `{ident}::EQUATIONS` holds it.",
        equations.lines().count(),
        equations.len() / 1024
    ))
}

/// `M[0][1]` → `M_{0 1}`, `G[rear_x][2]` → `G_{\mathrm{rear\_x}, 2}`, `dQ[1]/du` →
/// `\partial Q_{1} / \partial u`.
fn latex_label(name: &str) -> String {
    if let Some((q, u)) = name.split_once("/d") {
        return format!(
            "\\partial {} / \\partial \\mathrm{{{}}}",
            latex_label(q),
            escape(u)
        );
    }
    let Some((base, rest)) = name.split_once('[') else {
        return name.to_string();
    };
    let base = match base {
        "Phi" => "\\Phi",
        "gamma" => "\\gamma",
        other => other,
    };
    let indices: Vec<String> = rest
        .trim_end_matches(']')
        .split("][")
        .map(|i| {
            if i.chars().all(|c| c.is_ascii_digit()) {
                i.to_string()
            } else {
                format!("\\mathrm{{{}}}", escape(i))
            }
        })
        .collect();
    format!("{base}_{{{}}}", indices.join(", "))
}

fn escape(name: &str) -> String {
    name.replace('_', "\\_")
}

/// The named, nonzero expressions the listing shows, in order: M, h, Q, T, V,
/// the inputs' forces, the multiplier form's rows, the reduced form's rows.
fn outputs(model: &Model) -> Vec<(String, Sym)> {
    let ctx = &model.ctx;
    let n = model.dof();
    let mut out = Vec::new();
    let mut push = |name: String, e: Sym| {
        if !ctx.is_zero(e) {
            out.push((name, e));
        }
    };
    for i in 0..n {
        for j in i..n {
            push(format!("M[{i}][{j}]"), model.motion.mass[i][j]);
        }
    }
    (model.motion.bias.iter())
        .enumerate()
        .for_each(|(i, &h)| push(format!("h[{i}]"), h));
    (model.motion.forces.iter())
        .enumerate()
        .for_each(|(i, &f)| push(format!("Q[{i}]"), f));
    push("T".into(), model.energies.kinetic);
    push("V".into(), model.energies.potential);
    if let Some(inputs) = &model.inputs {
        for (i, row) in inputs.jacobian_u.iter().enumerate() {
            for (j, &d) in row.iter().enumerate() {
                push(format!("dQ[{i}]/d{}", inputs.names[j]), d);
            }
        }
    }
    if let Some(c) = &model.constraints.multipliers {
        for (k, name) in c.names.iter().enumerate() {
            push(format!("Phi[{name}]"), c.phi[k]);
            for (j, &g) in c.jacobian[k].iter().enumerate() {
                push(format!("G[{name}][{j}]"), g);
            }
            push(format!("g[{name}]"), c.velocity_term[k]);
            push(format!("gamma[{name}]"), c.gamma[k]);
        }
    }
    if let Some(r) = &model.constraints.reduced {
        for (k, name) in r.rows.iter().enumerate() {
            for (j, &a) in r.matrix[k].iter().enumerate() {
                push(format!("A[{name}][{j}]"), a);
            }
            push(format!("b[{name}]"), r.free[k]);
            push(format!("c[{name}]"), r.rates[k]);
        }
    }
    out
}

/// The emitted q̈'s route and both routes' weighted operation counts, where
/// `emit(articulated)` chose one.
fn forward_line(model: &Model) -> Option<String> {
    let c = model.outputs.forward_route.as_ref()?;
    let f = c.factored_mass;
    let taken = match c.route {
        ForwardRoute::ArticulatedBody => "the articulated-body algorithm",
        ForwardRoute::FactoredMass => "M factorised as L^T D L in the program",
    };
    let a = match c.articulated_body {
        Some(a) => format!("{a} articulated-body"),
        None => "articulated-body not applicable (a coordinate drives two joints)".into(),
    };
    Some(format!(
        "q'' (emitted) by {taken}: weighted operations {f} factored M, {a}"
    ))
}

/// The `route:` line: how M and h are computed and, off the recursive route,
/// why (which body, and what about it).
fn route_line(model: &Model) -> String {
    let h = match model.motion.derivation.route {
        BiasRoute::Projection => "d'Alembert projection",
        BiasRoute::Christoffel => "Christoffel symbols",
        BiasRoute::MassMatrix => "Christoffel symbols of M",
        BiasRoute::Recursive => {
            return "route: recursive: M by composite rigid bodies, h by recursive Newton–Euler over the kinematic tree".into();
        }
    };
    let why = model.motion.derivation.reason.as_deref().unwrap_or("");
    format!("route: generic: M from the positions, h by {h}; not recursive because {why}")
}

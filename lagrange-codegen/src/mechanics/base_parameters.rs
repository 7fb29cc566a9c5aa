//! The base parameters in closed form, for the `EQUATIONS` texts: the
//! tree's regrouped numbers (`tree::regrouped`) named after the standard
//! parameter each one extends, and reduced by the columns that the link
//! regressor, evaluated at random states and random values of the
//! description's symbols, shows to have no effect or to depend on the ones
//! before them. The runtime's `identify::BaseParameters` finds the same set
//! numerically (and is the one identification uses); this is its closed
//! form, with the description's symbols in it.
//!
//! The joints' coefficients follow the links' numbers, each a column of its
//! own (`OwnColumn`); a rotor on a joint whose axis is fixed in space is
//! regrouped into its link's axial inertia, as the textbooks do.

use lagrange_symbolic::{Context, Expr as Sym, Program, SymbolKind};

use crate::tree::{Tree, link_regressor, regrouped, root_axial_inertia};

/// A parameter of Y outside the links (a joint's damping, armature or
/// friction), a column of its own.
pub struct OwnColumn {
    /// π's symbol for it and its name (`elbow.damping`).
    pub symbol: Sym,
    pub name: String,
    /// The one row it enters, and its entry there.
    pub row: usize,
    pub entry: Sym,
    /// Whether it is an armature (q̈ on its row), which a root joint's
    /// axial inertia takes in.
    pub armature: bool,
}

/// The base parameters as the texts print them.
pub struct BaseForm {
    /// Each base parameter: its name and its expression in π, as text and
    /// as LaTeX.
    pub parameters: Vec<Named>,
    /// Regrouped parameters that the motion does not show at random states
    /// of a generic geometry: their columns vanish.
    pub without_effect: Vec<String>,
    /// Regrouped parameters whose columns depend on those before them
    /// beyond what the classical rules regroup (the runtime's numerical
    /// reduction folds them in); empty on the arms the tests cover.
    pub dependent: Vec<String>,
}

/// One base parameter.
pub struct Named {
    /// The standard parameter it extends, `R` appended when regrouped
    /// (`upper_arm.IzzR`).
    pub name: String,
    /// `name = expression` (the name alone where nothing was added).
    pub text: String,
    /// The same as a LaTeX `aligned` row, `name &= expression`.
    pub latex: String,
}

/// The suffixes of a link's ten numbers, in π's order.
const SUFFIX: [&str; 10] = [
    "m", "mx", "my", "mz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz",
];

/// The base parameters of `tree`, whose masses are written in π's `symbols`
/// (named `names`, the joints' `own` columns' last); None where the tree
/// turns a free orientation, whose quaternion the random states would have
/// to keep on the unit sphere.
pub fn closed_form(
    ctx: &mut Context,
    tree: &Tree,
    (symbols, names): (&[Sym], &[String]),
    own: &[&OwnColumn],
) -> Option<BaseForm> {
    if tree.turns_freely() {
        return None;
    }
    let mut numbers = regrouped(ctx, tree);
    let folded = fold_rotors(ctx, tree, &mut numbers, own);
    let wanted: Vec<bool> = numbers.iter().map(Option::is_some).collect();
    let by_link = link_regressor(ctx, tree, &wanted);
    let zero = ctx.zero();
    let mut candidates = Vec::new();
    for (j, n) in numbers.iter().enumerate() {
        let Some(n) = n else { continue };
        for (c, &e) in n.iter().enumerate() {
            if !ctx.is_zero(e) {
                let column: Vec<Sym> = by_link
                    .iter()
                    .map(|row| row[j].map_or(zero, |r| r[c]))
                    .collect();
                candidates.push((e, Some(c), column));
            }
        }
    }
    for o in own
        .iter()
        .zip(&folded)
        .filter(|(_, f)| !**f)
        .map(|(o, _)| o)
    {
        let column = (0..by_link.len())
            .map(|i| if i == o.row { o.entry } else { zero })
            .collect();
        candidates.push((o.symbol, None, column));
    }
    let columns: Vec<&[Sym]> = candidates.iter().map(|(_, _, col)| &col[..]).collect();
    let verdicts = independence(ctx, &columns);
    let mut form = BaseForm {
        parameters: Vec::new(),
        without_effect: Vec::new(),
        dependent: Vec::new(),
    };
    for ((e, c, _), verdict) in candidates.iter().zip(verdicts) {
        let name = match c {
            Some(c) => name_of(ctx, *e, *c, symbols, names),
            None => own_name(*e, symbols, names),
        };
        match verdict {
            Verdict::Kept => form.parameters.push(written(ctx, name, *e, symbols, names)),
            Verdict::NoEffect => form.without_effect.push(name),
            Verdict::Dependent => form.dependent.push(name),
        }
    }
    Some(form)
}

/// Adds each armature on a joint whose axis is fixed in space to its link's
/// axial inertia, where that link holds one (its column is then the same
/// q̈ on the joint's row); which of `own` were so folded.
fn fold_rotors(
    ctx: &mut Context,
    tree: &Tree,
    numbers: &mut [Option<[Sym; 10]>],
    own: &[&OwnColumn],
) -> Vec<bool> {
    own.iter()
        .map(|o| {
            let Some((j, c)) = o
                .armature
                .then(|| root_axial_inertia(tree, o.row))
                .flatten()
            else {
                return false;
            };
            match &mut numbers[j] {
                Some(n) if !ctx.is_zero(n[c]) => {
                    n[c] = ctx.add(n[c], o.symbol);
                    true
                }
                _ => false,
            }
        })
        .collect()
}

/// A joint's parameter's name, read off π's names by its symbol.
fn own_name(e: Sym, symbols: &[Sym], names: &[String]) -> String {
    (symbols.iter().zip(names))
        .find(|(s, _)| **s == e)
        .map_or_else(String::new, |(_, name)| name.clone())
}

/// The standard parameter a regrouped number extends (the one of its own
/// kind with coefficient one), with `R` appended when anything was added to
/// it: `forearm.Izz` or `upper_arm.IzzR`.
fn name_of(ctx: &mut Context, e: Sym, c: usize, symbols: &[Sym], names: &[String]) -> String {
    let own = (symbols.iter().zip(names)).find(|&(&s, name)| {
        name.rsplit('.').next() == Some(SUFFIX[c]) && {
            let d = ctx.diff(e, s);
            d == ctx.one()
        }
    });
    match own {
        Some((&s, name)) if s == e => name.clone(),
        Some((_, name)) => format!("{name}R"),
        None => format!("({})", SUFFIX[c]),
    }
}

/// `name = Σ coefficient · π_k` as text and LaTeX, the coefficients in the
/// description's symbols. A number's round-off below 1e-12 (a URDF's
/// quarter turn written to eight digits leaves cos(π/2) ≈ 3.7e-9, whose
/// powers reach 1e-68) is left out, and numbers are written to twelve
/// decimals.
fn written(ctx: &mut Context, name: String, e: Sym, symbols: &[Sym], names: &[String]) -> Named {
    if ctx.as_symbol(e).is_some() {
        let latex = latex_name(&name);
        return Named {
            text: name.clone(),
            latex,
            name,
        };
    }
    let mut text = String::new();
    let mut latex = String::new();
    for (&s, standard) in symbols.iter().zip(names) {
        let k = ctx.diff(e, s);
        let Some((negative, shown, tex)) = coefficient(ctx, k) else {
            continue;
        };
        let sign = match (text.is_empty(), negative) {
            (true, false) => "",
            (true, true) => "-",
            (false, false) => " + ",
            (false, true) => " - ",
        };
        let space = |c: &str| {
            if c.is_empty() {
                String::new()
            } else {
                format!("{c} ")
            }
        };
        text.push_str(&format!("{sign}{}{standard}", space(&shown)));
        latex.push_str(&format!("{sign}{}{}", space(&tex), latex_name(standard)));
    }
    Named {
        text: format!("{name} = {text}"),
        latex: format!("{} &= {latex}", latex_name(&name)),
        name,
    }
}

/// A coefficient as (negative, text, LaTeX), empty for one; None for zero
/// or a number's round-off.
fn coefficient(ctx: &mut Context, k: Sym) -> Option<(bool, String, String)> {
    if ctx.is_zero(k) {
        return None;
    }
    if !ctx.free_symbols(k).is_empty() {
        let (shown, tex) = (ctx.display(k), ctx.latex(k));
        // A sum is bracketed; a product reads without.
        if shown.contains(" + ") || shown.contains(" - ") {
            return Some((false, format!("({shown})"), format!("\\left({tex}\\right)")));
        }
        return Some((false, shown, tex));
    }
    let value = ctx.eval(k, &|_| f64::NAN);
    if value.abs() < 1e-12 {
        return None;
    }
    let digits = format!("{:.12}", value.abs());
    let digits = digits.trim_end_matches('0').trim_end_matches('.');
    let shown = if digits == "1" {
        String::new()
    } else {
        digits.to_string()
    };
    Some((value < 0.0, shown.clone(), shown))
}

/// `\mathrm{upper\_arm.Izz}`.
fn latex_name(name: &str) -> String {
    format!("\\mathrm{{{}}}", name.replace('_', "\\_"))
}

enum Verdict {
    Kept,
    NoEffect,
    Dependent,
}

/// Left to right, whether each column (a function of q, q̇, q̈) is kept, has
/// no effect or depends on those kept before it, from the columns stacked at
/// random states with the description's symbols at random values in
/// [0.5, 1.5] (lengths and masses of a generic geometry), by modified
/// Gram–Schmidt with a relative tolerance of 1e-8.
fn independence(ctx: &Context, columns: &[&[Sym]]) -> Vec<Verdict> {
    let rows = columns.first().map_or(0, |c| c.len());
    let entries: Vec<Sym> = columns.iter().flat_map(|c| c.iter().copied()).collect();
    let program = Program::new(ctx, &entries);
    let states = (2 * columns.len()).div_ceil(rows.max(1)) + 4;
    let mut stacked: Vec<Vec<f64>> = vec![Vec::new(); columns.len()];
    let mut rng = 0x2545_f491_4f6c_dd1d_u64;
    let params = ctx.parameters().len();
    let values: Vec<f64> = (0..params).map(|_| 1.0 + 0.5 * uniform(&mut rng)).collect();
    for _ in 0..states {
        let state: Vec<f64> = (0..3 * rows).map(|_| 2.0 * uniform(&mut rng)).collect();
        let env = |s| match ctx.symbol_kind(s) {
            SymbolKind::Coordinate(i) => state[i],
            SymbolKind::Velocity(i) => state[rows + i],
            SymbolKind::Acceleration(i) => state[2 * rows + i],
            SymbolKind::Parameter(i) => values[i],
            SymbolKind::Time => 0.5,
            SymbolKind::Free | SymbolKind::Input(_) => f64::NAN,
        };
        let out = program.eval(ctx, &env);
        for (k, column) in stacked.iter_mut().enumerate() {
            column.extend_from_slice(&out[k * rows..(k + 1) * rows]);
        }
    }
    gram_schmidt(stacked)
}

fn gram_schmidt(columns: Vec<Vec<f64>>) -> Vec<Verdict> {
    let norm = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>().sqrt();
    let largest = columns.iter().map(|c| norm(c)).fold(0.0, f64::max);
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let mut verdicts = Vec::with_capacity(columns.len());
    for mut c in columns {
        let before = norm(&c);
        if before.is_nan() || before <= 1e-10 * largest {
            verdicts.push(Verdict::NoEffect);
            continue;
        }
        for b in &basis {
            let dot: f64 = c.iter().zip(b).map(|(x, y)| x * y).sum();
            c.iter_mut().zip(b).for_each(|(x, y)| *x -= dot * y);
        }
        let after = norm(&c);
        if after <= 1e-8 * before {
            verdicts.push(Verdict::Dependent);
            continue;
        }
        c.iter_mut().for_each(|x| *x /= after);
        basis.push(c);
        verdicts.push(Verdict::Kept);
    }
    verdicts
}

/// SplitMix64 in [−1, 1): deterministic, so the texts are the same on every
/// build.
fn uniform(seed: &mut u64) -> f64 {
    *seed = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *seed;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

//! Human-readable output: plain text (Rust-like) and LaTeX.
//!
//! Both share one printer; only the leaf syntax differs. Factors of a
//! product are shown parameters first, then coordinates and velocities, then
//! function calls (`m*l^2*sin(theta)`), independent of arena order; negative
//! powers are shown as a denominator and negative terms as subtraction.

use crate::context::Context;
use crate::node::{Expr, Func, Node, SymbolKind};
use crate::rational::Num;

const SUM: u8 = 1;
const PRODUCT: u8 = 2;
const POWER: u8 = 3;
const ATOM: u8 = 4;

#[derive(Copy, Clone, PartialEq)]
enum Style {
    Text,
    Latex,
}

impl Context {
    /// Plain text, Rust-like: `m*l^2*sin(theta)`, velocities as `dot(theta)`.
    pub fn display(&self, e: Expr) -> String {
        self.show(e, Style::Text).0
    }

    /// LaTeX: `m l^{2} \sin\theta`, `\dot{\theta}`, `\frac{a}{b}`.
    pub fn latex(&self, e: Expr) -> String {
        self.show(e, Style::Latex).0
    }

    fn show(&self, e: Expr, st: Style) -> (String, u8) {
        match self.node(e) {
            Node::Const(_) | Node::Float(_) => self.show_num(self.num(e).unwrap_or(Num::ZERO), st),
            Node::Sym(s) => {
                let name = self.symbol_name(*s);
                let text = match st {
                    Style::Text => name.to_owned(),
                    Style::Latex => latex_name(name),
                };
                (text, ATOM)
            }
            Node::Add(terms) => self.show_sum(terms, st),
            Node::Mul(fs) => match self.num(fs[0]) {
                Some(c) => self.show_product(c, &fs[1..], st),
                None => self.show_product(Num::ONE, fs, st),
            },
            &Node::Pow(b, x) => match self.num(x) {
                Some(n) if n.is_negative() => self.show_product(Num::ONE, &[e], st),
                _ => self.show_power(b, x, st),
            },
            &Node::Call(f, a) => (self.show_call(f, a, None, st), ATOM),
            &Node::Atan2(y, x) => {
                let ys = self.show(y, st).0;
                let xs = self.show(x, st).0;
                let text = match st {
                    Style::Text => format!("atan2({ys}, {xs})"),
                    Style::Latex => format!("\\operatorname{{atan2}}\\left({ys}, {xs}\\right)"),
                };
                (text, ATOM)
            }
            &Node::Select(t, a, b) => {
                let ts = self.show(t, st).0;
                let as_ = self.show(a, st).0;
                let bs = self.show(b, st).0;
                let text = match st {
                    Style::Text => format!("(if {ts} > 0 {{ {as_} }} else {{ {bs} }})"),
                    Style::Latex => format!(
                        "\\begin{{cases}} {as_} & {ts} > 0 \\\\ {bs} & \\text{{otherwise}} \\end{{cases}}"
                    ),
                };
                (text, ATOM)
            }
        }
    }

    fn show_num(&self, n: Num, st: Style) -> (String, u8) {
        let neg = n.is_negative();
        let (text, prec) = match (n.abs(), st) {
            (Num::Rat(r), _) if r.is_integer() => (r.num.to_string(), ATOM),
            (Num::Rat(r), Style::Text) => (format!("{}/{}", r.num, r.den), PRODUCT),
            (Num::Rat(r), Style::Latex) => (format!("\\frac{{{}}}{{{}}}", r.num, r.den), ATOM),
            (Num::Float(v), _) => (format!("{v:?}"), ATOM),
        };
        if neg {
            (format!("-{text}"), SUM)
        } else {
            (text, prec)
        }
    }

    fn wrap(&self, (text, prec): (String, u8), min: u8, st: Style) -> String {
        if prec >= min {
            text
        } else if st == Style::Latex {
            format!("\\left({text}\\right)")
        } else {
            format!("({text})")
        }
    }

    fn show_sum(&self, terms: &[Expr], st: Style) -> (String, u8) {
        let mut sorted = terms.to_vec();
        sorted.sort_by_cached_key(|&t| self.term_rank(t));
        let mut out = String::new();
        for (i, &t) in sorted.iter().enumerate() {
            let negative = self.is_negative_term(t);
            let magnitude = if negative {
                self.show_negated(t, st)
            } else {
                self.show(t, st)
            };
            let body = self.wrap(magnitude, PRODUCT, st);
            match (i, negative) {
                (0, false) => out.push_str(&body),
                (0, true) => out.push_str(&format!("-{body}")),
                (_, false) => out.push_str(&format!(" + {body}")),
                (_, true) => out.push_str(&format!(" - {body}")),
            }
        }
        (out, SUM)
    }

    /// `-t` for a term with a negative coefficient.
    fn show_negated(&self, t: Expr, st: Style) -> (String, u8) {
        if let Some(n) = self.num(t) {
            return self.show_num(n.neg(), st);
        }
        match self.node(t) {
            Node::Mul(fs) => {
                let c = self.num(fs[0]).unwrap_or(Num::MINUS_ONE);
                self.show_product(c.neg(), &fs[1..], st)
            }
            _ => self.show(t, st),
        }
    }

    /// Display order of a factor: parameters, other symbols, coordinates,
    /// velocities, then calls grouped by argument, then compound factors
    /// smallest first; ties by id.
    fn display_rank(&self, f: Expr) -> (u8, usize, usize) {
        let base = match *self.node(f) {
            Node::Pow(b, _) => b,
            _ => f,
        };
        match self.node(base) {
            Node::Sym(s) => {
                let rank = match self.symbol_kind(*s) {
                    SymbolKind::Parameter(_) => 0,
                    SymbolKind::Free | SymbolKind::Input(_) => 1,
                    SymbolKind::Time => 2,
                    SymbolKind::Coordinate(_) => 3,
                    SymbolKind::Velocity(_) => 4,
                    SymbolKind::Acceleration(_) => 5,
                };
                (rank, base.index(), 0)
            }
            &Node::Call(func, a) => (6, a.index(), func as usize),
            &Node::Atan2(y, _) => (6, y.index(), usize::MAX),
            node => (7, node.children().len(), base.index()),
        }
    }

    /// Display order of a term in a sum: positive before negative, then by
    /// the display order of its factors; constants last.
    fn term_rank(&self, t: Expr) -> (bool, bool, Vec<(u8, usize, usize)>) {
        let factors: &[Expr] = match self.node(t) {
            Node::Mul(fs) if self.num(fs[0]).is_some() => &fs[1..],
            Node::Mul(fs) => fs,
            _ => std::slice::from_ref(&t),
        };
        let mut key: Vec<_> = factors.iter().map(|&f| self.display_rank(f)).collect();
        key.sort();
        (self.num(t).is_some(), self.is_negative_term(t), key)
    }

    fn show_product(&self, coeff: Num, factors: &[Expr], st: Style) -> (String, u8) {
        let mut sorted = factors.to_vec();
        sorted.sort_by_key(|&f| self.display_rank(f));
        let mut num: Vec<String> = Vec::new();
        let mut den: Vec<(String, u8)> = Vec::new();
        let (c_num, c_den) = match coeff.abs() {
            Num::Rat(r) => (r.num.to_string(), r.den.to_string()),
            Num::Float(v) => (format!("{v:?}"), "1".to_owned()),
        };
        if c_num != "1" {
            num.push(c_num);
        }
        if c_den != "1" {
            den.push((c_den, ATOM));
        }
        for f in sorted {
            if let Node::Pow(b, x) = *self.node(f)
                && let Some(n) = self.num(x).filter(|n| n.is_negative())
            {
                let shown = if n.neg().is_one() {
                    self.show(b, st)
                } else {
                    self.show_power_num(b, n.neg(), st)
                };
                den.push(shown);
            } else {
                num.push(self.wrap(self.show(f, st), PRODUCT + 1, st));
            }
        }
        let sep = if st == Style::Latex { " " } else { "*" };
        let numer = if num.is_empty() {
            "1".to_owned()
        } else {
            num.join(sep)
        };
        let body = if den.is_empty() {
            numer
        } else if st == Style::Latex {
            let d: Vec<String> = if den.len() == 1 {
                vec![den[0].0.clone()]
            } else {
                den.into_iter()
                    .map(|d| self.wrap(d, PRODUCT + 1, st))
                    .collect()
            };
            format!("\\frac{{{numer}}}{{{}}}", d.join(" "))
        } else if den.len() == 1 && den[0].1 >= POWER {
            format!("{numer}/{}", den[0].0)
        } else if den.len() == 1 {
            format!("{numer}/({})", den[0].0)
        } else {
            let d: Vec<String> = den
                .into_iter()
                .map(|d| self.wrap(d, PRODUCT + 1, st))
                .collect();
            format!("{numer}/({})", d.join("*"))
        };
        if coeff.is_negative() {
            (format!("-{body}"), SUM)
        } else {
            (body, PRODUCT)
        }
    }

    fn show_power_num(&self, b: Expr, x: Num, st: Style) -> (String, u8) {
        let mut text = self.show_power_with(
            b,
            self.show_num(x, st),
            x == crate::construct::rat(1, 2),
            st,
        );
        if let (Style::Latex, Node::Call(f, a)) = (st, self.node(b))
            && let Some(n) = x.as_integer()
        {
            text = self.show_call(*f, *a, Some(n), st);
        }
        (
            text,
            if x == crate::construct::rat(1, 2) {
                ATOM
            } else {
                POWER
            },
        )
    }

    fn show_power(&self, b: Expr, x: Expr, st: Style) -> (String, u8) {
        match self.num(x) {
            Some(n) => self.show_power_num(b, n, st),
            None => (self.show_power_with(b, self.show(x, st), false, st), POWER),
        }
    }

    fn show_power_with(&self, b: Expr, exp: (String, u8), is_sqrt: bool, st: Style) -> String {
        let base = self.show(b, st);
        match st {
            Style::Text if is_sqrt => format!("sqrt({})", base.0),
            Style::Latex if is_sqrt => format!("\\sqrt{{{}}}", base.0),
            Style::Text => format!("{}^{}", self.wrap(base, ATOM, st), self.wrap(exp, ATOM, st)),
            Style::Latex => format!("{}^{{{}}}", self.wrap(base, ATOM, st), exp.0),
        }
    }

    fn show_call(&self, f: Func, a: Expr, power: Option<i64>, st: Style) -> String {
        let arg = self.show(a, st);
        if st == Style::Text {
            return format!("{}({})", f.name(), arg.0);
        }
        let name = match f {
            Func::Asin => "\\arcsin".to_owned(),
            Func::Acos => "\\arccos".to_owned(),
            Func::Atan => "\\arctan".to_owned(),
            Func::Abs => return format!("\\left|{}\\right|", arg.0),
            Func::Sqrt => return format!("\\sqrt{{{}}}", arg.0),
            _ => format!("\\{}", f.name()),
        };
        let name = match power {
            Some(n) => format!("{name}^{{{n}}}"),
            None => name,
        };
        if arg.1 == ATOM && matches!(self.node(a), Node::Sym(_)) {
            if arg.0.starts_with('\\') {
                format!("{name}{}", arg.0)
            } else {
                format!("{name} {}", arg.0)
            }
        } else {
            format!("{name}\\left({}\\right)", arg.0)
        }
    }
}

const GREEK: &[&str] = &[
    "alpha",
    "beta",
    "gamma",
    "delta",
    "epsilon",
    "varepsilon",
    "zeta",
    "eta",
    "theta",
    "vartheta",
    "iota",
    "kappa",
    "lambda",
    "mu",
    "nu",
    "xi",
    "pi",
    "rho",
    "sigma",
    "tau",
    "upsilon",
    "phi",
    "varphi",
    "chi",
    "psi",
    "omega",
    "Gamma",
    "Delta",
    "Theta",
    "Lambda",
    "Xi",
    "Pi",
    "Sigma",
    "Upsilon",
    "Phi",
    "Psi",
    "Omega",
];

/// `theta1 -> \theta_{1}`, `dot(phi) -> \dot{\phi}`, `m_a -> m_{a}`,
/// `mass -> \mathrm{mass}`.
pub(crate) fn latex_name(name: &str) -> String {
    for (prefix, accent) in [("ddot(", "\\ddot"), ("dot(", "\\dot")] {
        if let Some(inner) = name.strip_prefix(prefix).and_then(|r| r.strip_suffix(')')) {
            return format!("{accent}{{{}}}", latex_name(inner));
        }
    }
    let (base, sub) = match name.split_once('_') {
        Some((b, s)) if !b.is_empty() => (b, s),
        _ => {
            let cut = name.trim_end_matches(|c: char| c.is_ascii_digit()).len();
            if cut == 0 {
                (name, "")
            } else {
                name.split_at(cut)
            }
        }
    };
    let base = if GREEK.contains(&base) {
        format!("\\{base}")
    } else if base.chars().count() > 1 {
        format!("\\mathrm{{{base}}}")
    } else {
        base.to_owned()
    };
    if sub.is_empty() {
        base
    } else {
        format!("{base}_{{{}}}", sub.replace('_', "\\_"))
    }
}

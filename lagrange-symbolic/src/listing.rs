//! A straight-line program as readable text: each value the program computes
//! once and uses more than once becomes a named line `x12 = …`; values used
//! once are written inline where they are used. The text grows with the
//! program (which CSE keeps small), not with the expression trees, which may
//! repeat a subexpression thousands of times.

use std::fmt::Write;

use crate::context::Context;
use crate::display::latex_name;
use crate::program::{Op, Program, Value};

/// Binding strength of a written value, to know when to parenthesise it.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum,
    Product,
    Unary,
    Atom,
}

/// How a listing is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ListingStyle {
    /// Plain text: `x12 = m*l^2*sin(q)`.
    Text,
    /// LaTeX lines of an `aligned` block: `x_{12} &= m\,l^{2}\,\sin q \\`.
    Latex,
}

impl Program {
    /// The program as plain text: shared intermediates first, in computation
    /// order, as `x<k> = …`, then one line `name = …` per output (`names` must
    /// have one entry per output).
    pub fn listing(&self, ctx: &Context, names: &[String]) -> String {
        self.listing_in(ctx, names, ListingStyle::Text)
    }

    /// The listing in the given style; LaTeX output names are written as
    /// given (they are LaTeX already).
    pub fn listing_in(&self, ctx: &Context, names: &[String], style: ListingStyle) -> String {
        assert_eq!(names.len(), self.outputs.len(), "one name per output");
        let uses = self.uses();
        let named: Vec<bool> = (0..self.ops.len())
            .map(|v| uses[v] > 1 && !matches!(self.ops[v], Op::Sym(_) | Op::Const(_)))
            .collect();
        let mut text: Vec<Option<(String, Prec)>> = vec![None; self.ops.len()];
        let mut out = String::new();
        let (eq, end) = match style {
            ListingStyle::Text => (" = ", ""),
            ListingStyle::Latex => (" &= ", " \\\\"),
        };
        for v in 0..self.ops.len() {
            let written = self.write(ctx, v as Value, &text, style);
            if named[v] {
                let name = match style {
                    ListingStyle::Text => format!("x{v}"),
                    ListingStyle::Latex => format!("x_{{{v}}}"),
                };
                let _ = writeln!(out, "{name}{eq}{}{end}", written.0);
                text[v] = Some((name, Prec::Atom));
            } else {
                text[v] = Some(written);
            }
        }
        for (name, &v) in names.iter().zip(&self.outputs) {
            let value = text[v as usize].as_ref().map_or("?", |(s, _)| s.as_str());
            let _ = writeln!(out, "{name}{eq}{value}{end}");
        }
        out
    }

    /// How many times each value is read, by operations and as an output.
    fn uses(&self) -> Vec<usize> {
        let mut uses = vec![0usize; self.ops.len()];
        for op in &self.ops {
            for a in op.operands() {
                uses[a as usize] += 1;
            }
        }
        for &v in &self.outputs {
            uses[v as usize] += 1;
        }
        uses
    }

    /// The text of value v from the texts of its operands.
    fn write(
        &self,
        ctx: &Context,
        v: Value,
        text: &[Option<(String, Prec)>],
        style: ListingStyle,
    ) -> (String, Prec) {
        let o = Operands {
            text,
            latex: style == ListingStyle::Latex,
        };
        let latex = o.latex;
        match self.ops[v as usize] {
            Op::Sym(s) => {
                let name = ctx.symbol_name(s);
                let name = if latex {
                    latex_name(name)
                } else {
                    name.to_string()
                };
                (name, Prec::Atom)
            }
            Op::Const(bits) => {
                let x = f64::from_bits(bits);
                let p = if x < 0.0 { Prec::Unary } else { Prec::Atom };
                (format!("{x:?}"), p)
            }
            Op::Add(a, b) => (
                format!("{} + {}", o.at(a, Prec::Sum), o.at(b, Prec::Sum)),
                Prec::Sum,
            ),
            Op::Sub(a, b) => (
                format!("{} - {}", o.at(a, Prec::Sum), o.at(b, Prec::Product)),
                Prec::Sum,
            ),
            Op::Mul(a, b) => {
                let sep = if latex { "\\," } else { "*" };
                (
                    format!("{}{sep}{}", o.at(a, Prec::Product), o.at(b, Prec::Unary)),
                    Prec::Product,
                )
            }
            Op::Div(a, b) if latex => (
                format!("\\frac{{{}}}{{{}}}", o.plain(a), o.plain(b)),
                Prec::Atom,
            ),
            Op::Div(a, b) => (
                format!("{}/{}", o.at(a, Prec::Product), o.at(b, Prec::Atom)),
                Prec::Product,
            ),
            Op::Neg(a) => (format!("-{}", o.at(a, Prec::Unary)), Prec::Unary),
            op @ (Op::Call(..) | Op::Atan2(..) | Op::Powf(..) | Op::Powi(..) | Op::Select(..)) => {
                write_function(op, &o)
            }
        }
    }
}

/// The texts of the values already written, for writing one more.
struct Operands<'a> {
    text: &'a [Option<(String, Prec)>],
    latex: bool,
}

impl Operands<'_> {
    /// Operand a, parenthesised where it binds more loosely than `min`.
    fn at(&self, a: Value, min: Prec) -> String {
        let (s, p) = self.text[a as usize]
            .clone()
            .unwrap_or(("?".into(), Prec::Atom));
        match (p < min, self.latex) {
            (false, _) => s,
            (true, false) => format!("({s})"),
            (true, true) => format!("\\left({s}\\right)"),
        }
    }

    /// Operand a as written, where the notation delimits it already.
    fn plain(&self, a: Value) -> String {
        self.text[a as usize].clone().map_or("?".into(), |(s, _)| s)
    }
}

/// Calls, powers and selections (the operations written with their own
/// delimiters); the arithmetic is written by `Listing::write`.
fn write_function(op: Op, o: &Operands) -> (String, Prec) {
    let latex = o.latex;
    match op {
        Op::Call(f, a) if latex => (latex_call(f.name(), &o.plain(a)), Prec::Atom),
        Op::Call(f, a) => (format!("{}({})", f.name(), o.at(a, Prec::Sum)), Prec::Atom),
        Op::Atan2(a, b) => {
            let name = if latex {
                "\\operatorname{atan2}"
            } else {
                "atan2"
            };
            (
                format!("{name}({}, {})", o.plain(a), o.plain(b)),
                Prec::Atom,
            )
        }
        Op::Powf(a, b) if latex => (
            format!("{{{}}}^{{{}}}", o.at(a, Prec::Atom), o.plain(b)),
            Prec::Unary,
        ),
        Op::Powf(a, b) => (
            format!("{}^{}", o.at(a, Prec::Atom), o.at(b, Prec::Atom)),
            Prec::Unary,
        ),
        Op::Powi(a, n) if latex => (format!("{{{}}}^{{{n}}}", o.at(a, Prec::Atom)), Prec::Unary),
        Op::Powi(a, n) => (format!("{}^{n}", o.at(a, Prec::Atom)), Prec::Unary),
        Op::Select(t, a, b) if latex => (
            format!(
                "\\begin{{cases}} {} & {} > 0 \\\\ {} & \\text{{otherwise}} \\end{{cases}}",
                o.plain(a),
                o.plain(t),
                o.plain(b)
            ),
            Prec::Atom,
        ),
        Op::Select(t, a, b) => (
            format!(
                "(if {} > 0 {{ {} }} else {{ {} }})",
                o.plain(t),
                o.plain(a),
                o.plain(b)
            ),
            Prec::Atom,
        ),
        _ => unreachable!("arithmetic is written by Listing::write"),
    }
}

/// A function call in LaTeX: `\sin\left(x\right)`, `\sqrt{x}`, `\left|x\right|`.
fn latex_call(name: &str, arg: &str) -> String {
    match name {
        "sqrt" => format!("\\sqrt{{{arg}}}"),
        "abs" => format!("\\left|{arg}\\right|"),
        "sin" | "cos" | "tan" | "sinh" | "cosh" | "tanh" | "exp" | "ln" | "log" => {
            format!("\\{name}\\left({arg}\\right)")
        }
        other => format!("\\operatorname{{{other}}}\\left({arg}\\right)"),
    }
}

#[cfg(test)]
mod tests {
    use crate::Context;
    use crate::Program;

    #[test]
    fn shared_values_are_named_once_and_single_uses_inlined() {
        let mut cx = Context::new();
        let q = cx.coordinate("q");
        let s = cx.sin(q);
        let c = cx.cos(q);
        let sc = cx.mul(s, c);
        let two = cx.int(2);
        let a = cx.add(sc, two);
        let p = Program::new(&cx, &[a, s]);
        let text = p.listing(&cx, &["A".into(), "S".into()]);
        // sin(q) is read by the product and as an output: one named line;
        // cos(q) is read once: written where it is used.
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3, "{text}");
        assert!(lines[0].ends_with(" = sin(q)"), "{text}");
        let x = lines[0].split(' ').next().unwrap();
        assert_eq!(lines[1], format!("A = 2.0 + {x}*cos(q)"), "{text}");
        assert_eq!(lines[2], format!("S = {x}"), "{text}");
    }

    #[test]
    fn latex_listing_names_and_fractions() {
        let mut cx = Context::new();
        let q = cx.coordinate("theta");
        let s = cx.sin(q);
        let two = cx.int(2);
        let h = cx.div(s, two);
        let p = Program::new(&cx, &[h, s]);
        let text = p.listing_in(&cx, &["H".into(), "S".into()], super::ListingStyle::Latex);
        assert!(
            text.contains("&= \\sin\\left(\\theta\\right) \\\\"),
            "{text}"
        );
        assert!(text.contains("x_{"), "{text}");
    }

    #[test]
    fn the_listing_evaluates_like_the_program() {
        // Parenthesisation: (a + b)·(a − b) and a − (b − c) must survive.
        let mut cx = Context::new();
        let a = cx.coordinate("a");
        let b = cx.coordinate("b");
        let c = cx.coordinate("c");
        let s = cx.add(a, b);
        let d = cx.sub(a, b);
        let p1 = cx.mul(s, d);
        let bc = cx.sub(b, c);
        let p2 = cx.sub(a, bc);
        let p = Program::new(&cx, &[p1, p2]);
        let text = p.listing(&cx, &["P".into(), "R".into()]);
        let line = |name: &str| {
            let prefix = format!("{name} = ");
            text.lines()
                .find(|l| l.starts_with(&prefix))
                .unwrap()
                .to_string()
        };
        assert!(line("P").contains('('), "{text}");
        assert!(!line("R").contains("a - b - c"), "{text}");
    }
}

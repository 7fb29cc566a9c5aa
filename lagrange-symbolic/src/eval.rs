//! Direct numeric evaluation of an expression (the reference semantics that
//! [`Program`](crate::Program) must reproduce).

use std::collections::HashMap;

use crate::context::Context;
use crate::node::{Expr, Node, Symbol};

impl Context {
    /// Evaluate `e` in `f64`, reading symbols through `env`. Shared
    /// subexpressions are evaluated once.
    pub fn eval(&self, e: Expr, env: &dyn Fn(Symbol) -> f64) -> f64 {
        let mut memo = HashMap::new();
        self.eval_in(e, env, &mut memo)
    }

    fn eval_in(&self, e: Expr, env: &dyn Fn(Symbol) -> f64, memo: &mut HashMap<Expr, f64>) -> f64 {
        if let Some(&v) = memo.get(&e) {
            return v;
        }
        let v = match self.node(e) {
            Node::Const(r) => r.to_f64(),
            Node::Float(b) => f64::from_bits(*b),
            Node::Sym(s) => env(*s),
            Node::Add(ts) => ts.iter().map(|&t| self.eval_in(t, env, memo)).sum(),
            Node::Mul(fs) => fs.iter().map(|&f| self.eval_in(f, env, memo)).product(),
            &Node::Pow(b, x) => {
                let base = self.eval_in(b, env, memo);
                match self.as_rational(x) {
                    Some(r) if r.is_integer() && i32::try_from(r.num).is_ok() => {
                        base.powi(r.num as i32)
                    }
                    Some(r) if r.den == 2 && i32::try_from(r.num).is_ok() => {
                        base.sqrt().powi(r.num as i32)
                    }
                    _ => base.powf(self.eval_in(x, env, memo)),
                }
            }
            &Node::Call(f, a) => f.apply(self.eval_in(a, env, memo)),
            &Node::Atan2(y, x) => self.eval_in(y, env, memo).atan2(self.eval_in(x, env, memo)),
            &Node::Select(t, a, b) => {
                if self.eval_in(t, env, memo) > 0.0 {
                    self.eval_in(a, env, memo)
                } else {
                    self.eval_in(b, env, memo)
                }
            }
        };
        memo.insert(e, v);
        v
    }
}

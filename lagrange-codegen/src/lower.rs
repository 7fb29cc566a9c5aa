//! `syn::Expr` → symbolic expressions.
//!
//! Resolves names (coordinates, parameters, definitions, `t`), maps the operators
//! and functions a mechanics user writes onto the expression engine, and enforces
//! the rules that need resolved names: unknown symbols, unsupported functions,
//! velocities where only positions make sense, `^` precedence traps. Every error
//! points at the offending token.

use std::collections::BTreeMap;

use lagrange_symbolic::{Context, Expr as Sym, Func};
use syn::{BinOp, Expr, Ident, Lit, UnOp};

use crate::ctxt::Ctxt;

/// What an expression is allowed to depend on.
#[derive(Copy, Clone, PartialEq, Eq, Debug)]
pub enum Mode {
    /// Positions ξ(q, t) and potentials: coordinates, time, parameters; no velocities.
    Configuration,
    /// Forces and dissipation: velocities allowed too.
    State,
    /// Masses: parameters and literals only.
    Constant,
}

impl Mode {
    fn describe(self) -> &'static str {
        match self {
            Mode::Configuration => "a position, a gravity vector or a potential",
            Mode::State => "this expression",
            Mode::Constant => "a mass",
        }
    }
}

/// A place of the description that inputs may not reach, with the reason the
/// error gives. Inputs have no known time derivative, so they are kept out of
/// everything the derivation differentiates in time.
#[derive(Copy, Clone, Debug)]
pub struct NoInputs {
    pub place: &'static str,
    pub why: &'static str,
}

const NO_RATE: &str =
    "the equations of motion would need its time derivative, which is not supplied at run time";

impl NoInputs {
    pub const POSITION: NoInputs = NoInputs {
        place: "a position map",
        why: NO_RATE,
    };
    pub const ROTATION: NoInputs = NoInputs {
        place: "a rotation",
        why: NO_RATE,
    };
    pub const MASS: NoInputs = NoInputs {
        place: "a mass",
        why: "a mass is constant, and the equations of motion would need its time derivative, which is not supplied at run time",
    };
    pub const INERTIA: NoInputs = NoInputs {
        place: "an inertia",
        why: "an inertia is constant, and the equations of motion would need its time derivative, which is not supplied at run time",
    };
    pub const GRAVITY: NoInputs = NoInputs {
        place: "gravity",
        why: "gravity is a fixed field of the unforced system, part of its conserved energy",
    };
    pub const HOLONOMIC: NoInputs = NoInputs {
        place: "a holonomic constraint",
        why: "the constraint is differentiated twice in time, which would need the input's time derivatives, not supplied at run time",
    };
    pub const NONHOLONOMIC: NoInputs = NoInputs {
        place: "a nonholonomic constraint",
        why: "the constraint is differentiated in time, which would need the input's time derivative, not supplied at run time",
    };
    pub const SPEED: NoInputs = NoInputs {
        place: "a speed",
        why: "the reduced equations differentiate the speeds in time, which would need the input's time derivative, not supplied at run time",
    };

    const FIX: &'static str =
        "apply the input as a force (`force`, `generalized_force`, `potential` or `dissipation`)";

    fn message(self, input: &str, via: Option<&str>) -> String {
        let (place, why, fix) = (self.place, self.why, Self::FIX);
        match via {
            None => format!("input `{input}` cannot appear in {place}: {why}; {fix}"),
            Some(d) => format!(
                "`{d}` uses the input `{input}`, which cannot appear in {place}: {why}; {fix}"
            ),
        }
    }
}

#[derive(Copy, Clone, Debug)]
enum Binding {
    Coordinate(Sym),
    Parameter(Sym),
    /// An input signal (`inputs(...)`).
    Input(Sym),
    /// A point or a body: index into `Lowerer::frames`.
    Frame(usize),
    /// A definition whose expression failed (its error is reported already):
    /// its uses report nothing more.
    Failed,
    Definition {
        value: Sym,
        has_velocity: bool,
        has_state: bool,
        /// The first input the definition uses, if any.
        input: Option<Sym>,
    },
}

/// What `P.x`, `dot(P.x)` and `B.omega_x` refer to: a point, or a body's centre
/// and angular velocity.
#[derive(Clone, Debug)]
pub struct Frame {
    pub name: String,
    pub position: Vec<Sym>,
    /// World- and body-frame angular velocity, for bodies.
    pub omega: Option<[[Sym; 3]; 2]>,
    /// The rotation matrix R (body to world), for bodies: column j is the
    /// body's j-th axis in world components.
    pub axes: Option<crate::mat3::Mat3>,
}

/// A Cartesian coordinate (or velocity) of a point that appeared in a constraint,
/// kept as a free symbol so the reaction Σ λ ∂f/∂ξ can be taken before composing
/// with ξ(q,t).
#[derive(Copy, Clone, Debug)]
pub struct CartesianRef {
    pub symbol: Sym,
    pub frame: usize,
    pub component: usize,
    pub velocity: bool,
}

/// Names in scope and the context the expressions are built in.
pub struct Lowerer<'a> {
    pub ctx: Context,
    pub(crate) cx: &'a Ctxt,
    scope: BTreeMap<String, Binding>,
    pub frames: Vec<Frame>,
    /// When set, point coordinates lower to free symbols recorded here.
    pub cartesian: Option<Vec<CartesianRef>>,
    /// When set, inputs are an error here (see [`Lowerer::without_inputs`]).
    no_inputs: Option<NoInputs>,
}

const FUNCTIONS: &str = "sin, cos, tan, asin, acos, atan, atan2, sinh, cosh, tanh, exp, ln, log, sqrt, abs, sign, min, max, clamp, pow, powi, powf, dot; and `if a > b { .. } else { .. }`";

impl<'a> Lowerer<'a> {
    pub fn new(cx: &'a Ctxt) -> Self {
        let mut ctx = Context::new();
        ctx.time();
        Lowerer {
            ctx,
            cx,
            scope: BTreeMap::new(),
            frames: Vec::new(),
            cartesian: None,
            no_inputs: None,
        }
    }

    /// Runs `f` with inputs forbidden: an input (or a definition that uses
    /// one) is reported at its token with `place`'s reason.
    pub fn without_inputs<R>(&mut self, place: NoInputs, f: impl FnOnce(&mut Self) -> R) -> R {
        let outer = self.no_inputs.replace(place);
        let r = f(self);
        self.no_inputs = outer;
        r
    }

    /// Brings an input into scope, unless its name is already taken (`check`
    /// reports the clash at the input; the earlier meaning stays, so uses of
    /// the name do not add errors of their own).
    pub fn declare_input(&mut self, name: &Ident) -> Sym {
        let u = self.ctx.input(&name.to_string());
        self.scope
            .entry(name.to_string())
            .or_insert(Binding::Input(u));
        u
    }

    /// Brings a point or body into scope for `P.x`, `dot(P.x)`, `B.omega_x`.
    pub fn declare_frame(&mut self, name: &Ident, frame: Frame) -> usize {
        let i = self.frames.len();
        self.frames.push(frame);
        self.scope.insert(name.to_string(), Binding::Frame(i));
        i
    }

    /// The frame a name refers to, if it is a point or body in scope.
    pub fn frame_of(&self, name: &Ident) -> Option<usize> {
        match self.scope.get(&name.to_string()) {
            Some(Binding::Frame(i)) => Some(*i),
            _ => None,
        }
    }

    pub fn declare_coordinate(&mut self, name: &Ident) -> Sym {
        let q = self.ctx.coordinate(&name.to_string());
        self.scope.insert(name.to_string(), Binding::Coordinate(q));
        q
    }

    pub fn declare_parameter(&mut self, name: &Ident) -> Sym {
        let p = self.ctx.parameter(&name.to_string());
        self.scope.insert(name.to_string(), Binding::Parameter(p));
        p
    }

    /// Lowers a definition (velocities allowed) and brings it into scope for later items.
    pub fn declare_definition(&mut self, name: &Ident, value: &Expr) {
        if let Some(v) = self.expr(value, Mode::State) {
            let velocities = self.ctx.velocities();
            let has_velocity = velocities.iter().any(|&qd| self.ctx.depends_on(v, qd));
            let mut state = self.ctx.coordinates();
            state.extend(velocities);
            state.push(self.ctx.time());
            let has_state = state.iter().any(|&s| self.ctx.depends_on(v, s));
            let input = self
                .ctx
                .inputs()
                .into_iter()
                .find(|&u| self.ctx.depends_on(v, u));
            self.scope.insert(
                name.to_string(),
                Binding::Definition {
                    value: v,
                    has_velocity,
                    has_state,
                    input,
                },
            );
        } else {
            self.scope.insert(name.to_string(), Binding::Failed);
        }
    }

    /// Lowers `[a, b, c]` into its components.
    pub fn vector(&mut self, e: &Expr, mode: Mode) -> Option<Vec<Sym>> {
        let Expr::Array(a) = e else { return None };
        let parts: Vec<Option<Sym>> = a.elems.iter().map(|x| self.expr(x, mode)).collect();
        parts.into_iter().collect()
    }

    pub fn expr(&mut self, e: &Expr, mode: Mode) -> Option<Sym> {
        match e {
            Expr::Lit(l) => self.literal(&l.lit),
            Expr::Paren(p) => self.expr(&p.expr, mode),
            Expr::Group(g) => self.expr(&g.expr, mode),
            Expr::Path(p) => match p.path.get_ident() {
                Some(id) => self.name(id, mode),
                None => self.unsupported(e, "a path; use a plain name"),
            },
            Expr::Field(f) => self.field(f, mode),
            Expr::Unary(u) => match u.op {
                UnOp::Neg(_) => {
                    let a = self.expr(&u.expr, mode)?;
                    Some(self.ctx.neg(a))
                }
                _ => self.unsupported(e, "this unary operator"),
            },
            Expr::Binary(b) => self.binary(b, mode),
            Expr::If(i) => self.conditional(i, mode),
            Expr::Call(c) => self.call(c, mode),
            Expr::MethodCall(m) => self.method(m, mode),
            Expr::Array(_) => {
                self.cx.error_spanned_by(
                    e,
                    "a vector is not allowed here; expected a scalar expression",
                );
                None
            }
            _ => self.unsupported(e, "this kind of expression"),
        }
    }

    fn unsupported(&self, e: &Expr, what: &str) -> Option<Sym> {
        self.cx.error_spanned_by(
            e,
            format!("{what} is not supported in #[lagrange] expressions (use numbers, names, + - * / ^, and functions: {FUNCTIONS})"),
        );
        None
    }

    fn name(&mut self, id: &Ident, mode: Mode) -> Option<Sym> {
        let key = id.to_string();
        match key.as_str() {
            "t" => {
                if mode == Mode::Constant {
                    self.cx.error_at(
                        id.span(),
                        "a mass must be constant: it cannot depend on time `t`",
                    );
                    return None;
                }
                return Some(self.ctx.time());
            }
            "pi" | "PI" => return Some(self.ctx.float(std::f64::consts::PI)),
            _ => {}
        }
        match self.scope.get(&key).copied() {
            Some(Binding::Parameter(p)) => Some(p),
            Some(Binding::Coordinate(q)) => {
                if mode == Mode::Constant {
                    self.cx.error_at(
                        id.span(),
                        format!(
                            "a mass must be constant: it cannot depend on the coordinate `{key}`"
                        ),
                    );
                    return None;
                }
                Some(q)
            }
            Some(Binding::Input(u)) => {
                if let Some(place) = self.no_inputs {
                    self.cx.error_at(id.span(), place.message(&key, None));
                    return None;
                }
                Some(u)
            }
            Some(Binding::Definition {
                value,
                has_velocity,
                has_state,
                input,
            }) => {
                if let (Some(place), Some(u)) = (self.no_inputs, input) {
                    let name = self
                        .ctx
                        .as_symbol(u)
                        .map(|s| self.ctx.symbol_name(s).to_string());
                    let name = name.unwrap_or_default();
                    self.cx
                        .error_at(id.span(), place.message(&name, Some(&key)));
                    return None;
                }
                if mode == Mode::Configuration && has_velocity {
                    self.cx.error_at(
                        id.span(),
                        format!(
                            "`{key}` depends on velocities and cannot be used in {}",
                            mode.describe()
                        ),
                    );
                    return None;
                }
                if mode == Mode::Constant && has_state {
                    self.cx.error_at(
                        id.span(),
                        format!(
                            "a mass must be constant, but `{key}` depends on the state or time"
                        ),
                    );
                    return None;
                }
                Some(value)
            }
            Some(Binding::Frame(_)) => {
                self.cx.error_at(
                    id.span(),
                    format!("`{key}` is a point or body, not a number; use its coordinates `{key}.x`, `{key}.y`, `{key}.z`"),
                );
                None
            }
            Some(Binding::Failed) => None,
            None => {
                let msg = format!(
                    "unknown symbol `{key}`: not a coordinate, a parameter field, a definition, or `t`"
                );
                self.cx.error_at(id.span(), msg);
                None
            }
        }
    }

    /// `self.m` (the parameter `m`), `P.x` (a coordinate of a point or body centre),
    /// `B.omega_x` / `B.omega_1` (world / body components of a body's angular velocity).
    fn field(&mut self, f: &syn::ExprField, mode: Mode) -> Option<Sym> {
        if let Expr::Field(inner) = &*f.base {
            return self.axis_component(inner, &f.member, mode);
        }
        let base = match &*f.base {
            Expr::Path(p) => p.path.get_ident(),
            _ => None,
        };
        let (Some(base), syn::Member::Named(member)) = (base, &f.member) else {
            self.cx.error_spanned_by(
                f,
                "only `self.<parameter>`, `<point>.x` and `<body>.omega_x` field accesses are supported",
            );
            return None;
        };
        if base == "self" {
            return self.self_field(member);
        }
        let Some(frame) = self.frame_of(base) else {
            self.cx.error_at(
                base.span(),
                format!("unknown point or body `{base}`; declare it with `point({base}, ...)` or `body({base}, ...)`"),
            );
            return None;
        };
        let m = member.to_string();
        if let Some(c) = component(&m) {
            return self.coordinate_of(frame, c, false, base, member, mode);
        }
        let omega = match m.as_str() {
            "omega_x" => Some((0, 0)),
            "omega_y" => Some((0, 1)),
            "omega_z" => Some((0, 2)),
            "omega_1" => Some((1, 0)),
            "omega_2" => Some((1, 1)),
            "omega_3" => Some((1, 2)),
            _ => None,
        };
        let Some((which, c)) = omega else {
            self.cx.error_at(
                member.span(),
                format!("`{base}.{m}`: expected a coordinate `x`, `y`, `z`, or for a body `omega_x`/`omega_y`/`omega_z` (world frame), `omega_1`/`omega_2`/`omega_3` (body frame) or an axis component `axis_x.x` … `axis_z.z`"),
            );
            return None;
        };
        let Some(w) = self.frames[frame].omega else {
            self.cx.error_at(
                member.span(),
                format!("`{base}` is a point; only bodies have an angular velocity"),
            );
            return None;
        };
        if mode != Mode::State {
            self.cx.error_at(
                member.span(),
                format!(
                    "the angular velocity `{base}.{m}` cannot appear in {}",
                    mode.describe()
                ),
            );
            return None;
        }
        Some(w[which][c])
    }

    /// `B.axis_x.y`: a world component of one of a body's unit axes, that is
    /// an entry of its rotation matrix (R_ij = `B.axis_<j>.<i>`).
    fn axis_component(
        &mut self,
        inner: &syn::ExprField,
        member: &syn::Member,
        mode: Mode,
    ) -> Option<Sym> {
        let usage = "write `<body>.axis_x.x` (… `axis_z.z`): the world components of a body's axes";
        let base = match &*inner.base {
            Expr::Path(p) => p.path.get_ident(),
            _ => None,
        };
        let axis = match &inner.member {
            syn::Member::Named(m) => ["axis_x", "axis_y", "axis_z"].iter().position(|a| m == a),
            syn::Member::Unnamed(_) => None,
        };
        let component = match member {
            syn::Member::Named(m) => component(&m.to_string()),
            syn::Member::Unnamed(_) => None,
        };
        let (Some(base), Some(axis), Some(c)) = (base, axis, component) else {
            self.cx
                .error_spanned_by(inner, format!("unsupported field access: {usage}"));
            return None;
        };
        let Some(frame) = self.frame_of(base) else {
            self.cx.error_at(
                base.span(),
                format!("unknown body `{base}`; declare it with `body({base}, ...)`"),
            );
            return None;
        };
        let Some(r) = self.frames[frame].axes else {
            self.cx.error_at(
                base.span(),
                format!("`{base}` is a point; only bodies have axes"),
            );
            return None;
        };
        if mode == Mode::Constant {
            self.cx.error_spanned_by(
                inner,
                format!(
                    "a body's axes depend on the configuration and cannot appear in {}",
                    mode.describe()
                ),
            );
            return None;
        }
        Some(r[c][axis])
    }

    /// A Cartesian coordinate (or, with `velocity`, its rate) of a frame: the
    /// expression itself, or a recorded free symbol while lowering a constraint.
    fn coordinate_of(
        &mut self,
        frame: usize,
        c: usize,
        velocity: bool,
        base: &Ident,
        member: &Ident,
        mode: Mode,
    ) -> Option<Sym> {
        let f = &self.frames[frame];
        if c >= f.position.len() {
            self.cx.error_at(
                member.span(),
                format!("`{base}.{member}`: the scene is planar, `{base}` has only `x` and `y`"),
            );
            return None;
        }
        if mode == Mode::Constant {
            self.cx.error_at(
                base.span(),
                format!("a mass must be constant: it cannot depend on the position of `{base}`"),
            );
            return None;
        }
        if velocity && mode != Mode::State {
            self.cx.error_at(
                base.span(),
                format!(
                    "velocity `dot({base}.{member})` cannot appear in {}",
                    mode.describe()
                ),
            );
            return None;
        }
        let x = f.position[c];
        let value = if velocity {
            self.ctx.time_derivative(x)
        } else {
            x
        };
        let name = if velocity {
            format!("dot({base}.{member})")
        } else {
            format!("{base}.{member}")
        };
        match &mut self.cartesian {
            None => Some(value),
            Some(refs) => {
                let symbol = self.ctx.free_symbol(&name);
                if !refs.iter().any(|r| r.symbol == symbol) {
                    refs.push(CartesianRef {
                        symbol,
                        frame,
                        component: c,
                        velocity,
                    });
                }
                Some(symbol)
            }
        }
    }

    /// `self.m` is accepted as a spelling of the parameter `m`.
    fn self_field(&mut self, name: &Ident) -> Option<Sym> {
        match self.scope.get(&name.to_string()) {
            Some(Binding::Parameter(p)) => Some(*p),
            _ => {
                self.cx.error_at(
                    name.span(),
                    format!("`self.{name}` is not a parameter field of the struct"),
                );
                None
            }
        }
    }

    fn literal(&mut self, lit: &Lit) -> Option<Sym> {
        match lit {
            Lit::Int(i) => match i.base10_parse::<i64>() {
                Ok(v) => Some(self.ctx.int(v)),
                Err(e) => {
                    self.cx.syn_error(e);
                    None
                }
            },
            Lit::Float(f) => Some(
                decimal(&mut self.ctx, f.base10_digits()).unwrap_or_else(|| {
                    let v = f.base10_parse::<f64>().unwrap_or(f64::NAN);
                    self.ctx.float(v)
                }),
            ),
            other => {
                self.cx.error_spanned_by(other, "expected a number");
                None
            }
        }
    }

    fn binary(&mut self, b: &syn::ExprBinary, mode: Mode) -> Option<Sym> {
        if let BinOp::BitXor(_) = &b.op {
            // `^` binds looser than + - * / in Rust: `a + b^2` parses as `(a + b)^2`
            // and `x^2 + y` as `x^(2 + y)`. Rather than silently compute the wrong
            // power, insist on parentheses when an operand is itself an operation.
            for side in [&*b.left, &*b.right] {
                if matches!(side, Expr::Binary(_)) {
                    self.cx.error_spanned_by(
                        side,
                        format!(
                            "`^` binds looser than `+ - * /` in Rust, so this operand of `^` would be `{}`; add parentheses, e.g. `a + (b^2)`, or write `pow(b, 2)`",
                            quote::ToTokens::to_token_stream(side)
                        ),
                    );
                    return None;
                }
            }
        }
        let l = self.expr(&b.left, mode);
        let r = self.expr(&b.right, mode);
        let (l, r) = (l?, r?);
        match &b.op {
            BinOp::Add(_) => Some(self.ctx.add(l, r)),
            BinOp::Sub(_) => Some(self.ctx.sub(l, r)),
            BinOp::Mul(_) => Some(self.ctx.mul(l, r)),
            BinOp::Div(_) if self.ctx.is_zero(r) => {
                // The engine would fold `m / 0` to an infinity and the equations
                // would carry it silently.
                self.cx.error_spanned_by(
                    &b.right,
                    format!(
                        "division by zero: `{}` is the constant 0",
                        quote::ToTokens::to_token_stream(&*b.right)
                    ),
                );
                None
            }
            BinOp::Div(_) => Some(self.ctx.div(l, r)),
            BinOp::BitXor(_) => Some(self.ctx.pow(l, r)),
            _ => {
                self.cx.error_spanned_by(
                    b.op,
                    "unsupported operator in #[lagrange] expressions; use + - * / and ^ (power)",
                );
                None
            }
        }
    }

    fn call(&mut self, c: &syn::ExprCall, mode: Mode) -> Option<Sym> {
        let Expr::Path(p) = &*c.func else {
            return self.unsupported(&c.func, "calling this");
        };
        let Some(fname) = p.path.get_ident() else {
            return self.unsupported(&c.func, "a path call");
        };
        let args: Vec<&Expr> = c.args.iter().collect();
        let name = fname.to_string();
        if name == "dot" {
            return self.velocity(fname, &args, mode);
        }
        let Some(arity) = arity(&name) else {
            self.cx.error_at(
                fname.span(),
                format!("unsupported function `{name}`; supported: {FUNCTIONS}"),
            );
            return None;
        };
        if args.len() != arity {
            self.cx.error_spanned_by(
                c,
                format!(
                    "`{name}` takes {arity} argument{}, found {}",
                    if arity == 1 { "" } else { "s" },
                    args.len()
                ),
            );
            return None;
        }
        let lowered: Vec<Option<Sym>> = args.iter().map(|a| self.expr(a, mode)).collect();
        let lowered: Vec<Sym> = lowered.into_iter().collect::<Option<_>>()?;
        Some(self.apply(&name, &lowered))
    }

    /// `x.sin()`, `x.powi(2)`, `y.atan2(x)`: Rust method spelling of the same functions.
    fn method(&mut self, m: &syn::ExprMethodCall, mode: Mode) -> Option<Sym> {
        let name = m.method.to_string();
        let Some(arity) = arity(&name) else {
            self.cx.error_at(
                m.method.span(),
                format!("unsupported function `{name}`; supported: {FUNCTIONS}"),
            );
            return None;
        };
        if m.args.len() + 1 != arity {
            self.cx.error_spanned_by(
                m,
                format!(
                    "`.{name}()` takes {} argument{}",
                    arity - 1,
                    if arity == 2 { "" } else { "s" }
                ),
            );
            return None;
        }
        let recv = self.expr(&m.receiver, mode);
        let rest: Vec<Option<Sym>> = m.args.iter().map(|a| self.expr(a, mode)).collect();
        let mut all = vec![recv?];
        for r in rest {
            all.push(r?);
        }
        Some(self.apply(&name, &all))
    }

    fn apply(&mut self, name: &str, a: &[Sym]) -> Sym {
        let f = match name {
            "sin" => Func::Sin,
            "cos" => Func::Cos,
            "tan" => Func::Tan,
            "asin" => Func::Asin,
            "acos" => Func::Acos,
            "atan" => Func::Atan,
            "sinh" => Func::Sinh,
            "cosh" => Func::Cosh,
            "tanh" => Func::Tanh,
            "exp" => Func::Exp,
            "ln" | "log" => Func::Ln,
            "sqrt" => Func::Sqrt,
            "abs" => Func::Abs,
            "atan2" => return self.ctx.atan2(a[0], a[1]),
            "sign" => return self.ctx.sign(a[0]),
            "min" => return self.ctx.min(a[0], a[1]),
            "max" => return self.ctx.max(a[0], a[1]),
            "clamp" => {
                let low = self.ctx.max(a[0], a[1]);
                return self.ctx.min(low, a[2]);
            }
            // pow, powi, powf
            _ => return self.ctx.pow(a[0], a[1]),
        };
        self.ctx.func(f, a[0])
    }

    /// `dot(q)`: the generalized velocity of coordinate `q`.
    fn velocity(&mut self, fname: &Ident, args: &[&Expr], mode: Mode) -> Option<Sym> {
        if let [Expr::Field(f)] = args
            && let Expr::Path(p) = &*f.base
            && let Some(base) = p.path.get_ident()
            && let syn::Member::Named(member) = &f.member
            && let Some(frame) = self.frame_of(base)
            && let Some(c) = component(&member.to_string())
        {
            return self.coordinate_of(frame, c, true, base, member, mode);
        }
        let target = match args {
            [Expr::Path(p)] => p.path.get_ident(),
            _ => None,
        };
        let Some(target) = target else {
            self.cx.error_at(
                fname.span(),
                "`dot(...)` takes one coordinate name, e.g. `dot(theta)`",
            );
            return None;
        };
        let Some(Binding::Coordinate(q)) = self.scope.get(&target.to_string()).copied() else {
            self.cx.error_at(
                target.span(),
                format!("`dot({target})`: `{target}` is not a generalized coordinate"),
            );
            return None;
        };
        if mode != Mode::State {
            self.cx.error_at(
                fname.span().join(target.span()).unwrap_or(fname.span()),
                format!("velocity `dot({target})` cannot appear in {}: it must depend on coordinates, parameters and `t` only", mode.describe()),
            );
            return None;
        }
        self.ctx.velocity(q)
    }
}

/// `x`, `y`, `z` → 0, 1, 2.
fn component(name: &str) -> Option<usize> {
    match name {
        "x" => Some(0),
        "y" => Some(1),
        "z" => Some(2),
        _ => None,
    }
}

fn arity(name: &str) -> Option<usize> {
    Some(match name {
        "sin" | "cos" | "tan" | "asin" | "acos" | "atan" | "sinh" | "cosh" | "tanh" | "exp"
        | "ln" | "log" | "sqrt" | "abs" | "sign" => 1,
        "atan2" | "pow" | "powi" | "powf" | "min" | "max" => 2,
        "clamp" => 3,
        _ => return None,
    })
}

/// A decimal literal as an exact rational: `9.81` → 981/100, `1e-3` → 1/1000.
/// Exactness matters: `0.1 * 10` must fold to 1, not to 1.0000000000000002.
fn decimal(ctx: &mut Context, digits: &str) -> Option<Sym> {
    let (mantissa, exp) = match digits.find(['e', 'E']) {
        Some(i) => (&digits[..i], digits[i + 1..].parse::<i32>().ok()?),
        None => (digits, 0),
    };
    let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let all: String = format!("{int_part}{frac_part}");
    let mut num: i64 = all.parse().ok()?;
    let mut scale = exp - frac_part.len() as i32;
    let mut den: i64 = 1;
    while scale > 0 {
        num = num.checked_mul(10)?;
        scale -= 1;
    }
    while scale < 0 {
        den = den.checked_mul(10)?;
        scale += 1;
    }
    Some(ctx.rational(num, den))
}

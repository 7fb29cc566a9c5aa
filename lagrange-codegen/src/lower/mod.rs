//! `syn::Expr` → symbolic expressions.
//!
//! Resolves names (coordinates, parameters, definitions, `t`), maps the operators
//! and functions a mechanics user writes onto the expression engine, and enforces
//! the rules that need resolved names: unknown symbols, unsupported functions,
//! velocities where only positions make sense, `^` precedence traps. Every error
//! points at the offending token.

use std::collections::BTreeMap;

use lagrange_symbolic::{Context, Expr as Sym};
use syn::{Expr, Ident, UnOp};

use crate::ctxt::Ctxt;

mod arith;
mod call;
pub mod condition;
mod field;
mod input;
mod name;
pub mod rotation;
mod torque;

pub use input::NoInputs;

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

#[derive(Copy, Clone, Debug)]
enum Binding {
    Coordinate(Sym),
    Parameter(Sym),
    /// An input signal (`inputs(...)`).
    Input(Sym),
    /// A point or a body: index into `Lowerer::frames`.
    Frame(usize),
    /// A free orientation (`orientation(...)`): index into
    /// `Lowerer::orientations`.
    Orientation(usize),
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
    /// The point's or body's name.
    pub name: String,
    /// Its world position ξ(q, t) (a body's: its reference point).
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
    /// The free symbol standing for the component.
    pub symbol: Sym,
    /// The frame (index into `Lowerer::frames`) it belongs to.
    pub frame: usize,
    /// The Cartesian component: 0 = x, 1 = y, 2 = z.
    pub component: usize,
    /// Whether it is a velocity component (`dot(P.x)`) rather than a position.
    pub velocity: bool,
}

/// Names in scope and the context the expressions are built in.
pub struct Lowerer<'a> {
    /// The context the expressions are built in.
    pub ctx: Context,
    pub(crate) cx: &'a Ctxt,
    scope: BTreeMap<String, Binding>,
    /// Every point and body lowered so far, by the index their names bind to.
    pub frames: Vec<Frame>,
    /// When set, point coordinates lower to free symbols recorded here.
    pub cartesian: Option<Vec<CartesianRef>>,
    /// When set, inputs are an error here (see [`Lowerer::without_inputs`]).
    no_inputs: Option<NoInputs>,
    /// What the expression being lowered is, for its errors ("the inertia
    /// of body `b`", "the position of point `p`"); see [`Lowerer::lowering_as`].
    place: Option<String>,
    /// The free orientations, in declaration order.
    pub orientations: Vec<OrientationSymbols>,
}

/// A free orientation's symbols. The derivation works in a chart moving
/// with the body: the rotation is R₀·exp(θ) with R₀ the orientation now (from
/// the quaternion, a constant to every derivative) and θ a rotation vector in
/// body axes, three ordinary coordinates whose rates at θ = 0 are the angular
/// velocity ω and whose second rates there are ω̇. Lagrange's equations in θ,
/// taken at θ = 0 (the derivation substitutes it last), are then the
/// equations in ω with no chart at all: R₀ has no singular set.
pub struct OrientationSymbols {
    /// The orientation's name.
    pub name: String,
    /// θ: three coordinates, zero wherever an equation is evaluated.
    pub theta: [Sym; 3],
    /// (w, x, y, z), read from q.
    pub quaternion: [Sym; 4],
}

const FUNCTIONS: &str = "sin, cos, tan, asin, acos, atan, atan2, sinh, cosh, tanh, exp, ln, log, sqrt, abs, sign, min, max, clamp, pow, powi, powf, dot; and `if a > b { .. } else { .. }`";

impl<'a> Lowerer<'a> {
    /// A lowerer with time declared and nothing in scope; errors go to `cx`.
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
            place: None,
            orientations: Vec::new(),
        }
    }

    /// Runs `f` with `place` ("the mass of point `p`") named in the errors of
    /// the expressions it lowers.
    pub fn lowering_as<R>(&mut self, place: String, f: impl FnOnce(&mut Self) -> R) -> R {
        let outer = self.place.replace(place);
        let r = f(self);
        self.place = outer;
        r
    }

    /// What an expression lowered in `mode` is, for an error ("cannot appear
    /// in {}", "{} must be constant").
    fn describe(&self, mode: Mode) -> String {
        match mode {
            Mode::Configuration => match (&self.place, self.no_inputs) {
                (Some(place), _) => place.clone(),
                (None, Some(no_inputs)) => no_inputs.place.to_string(),
                // The one configuration expression that may read inputs.
                (None, None) => "the potential".to_string(),
            },
            Mode::State => "this expression".to_string(),
            Mode::Constant => match &self.place {
                Some(place) => place.clone(),
                None => "a mass".to_string(),
            },
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

    /// Brings coordinate `name` into scope and returns its symbol.
    pub fn declare_coordinate(&mut self, name: &Ident) -> Sym {
        let q = self.ctx.coordinate(&name.to_string());
        self.scope.insert(name.to_string(), Binding::Coordinate(q));
        q
    }

    /// Declares a free orientation `name`: its θ coordinates (`name.wx`,
    /// `name.wy`, `name.wz`, whose rates are ω in body axes) and its
    /// quaternion's components (`name.w`, `name.x`, `name.y`, `name.z`).
    pub fn declare_orientation(&mut self, name: &Ident) {
        let n = name.to_string();
        let theta = ["wx", "wy", "wz"].map(|a| self.ctx.coordinate(&format!("{n}.{a}")));
        let quaternion = ["w", "x", "y", "z"].map(|c| self.ctx.free_symbol(&format!("{n}.{c}")));
        let index = self.orientations.len();
        self.scope.insert(n.clone(), Binding::Orientation(index));
        self.orientations.push(OrientationSymbols {
            name: n,
            theta,
            quaternion,
        });
    }

    /// The orientations as the derivation takes them.
    pub fn orientation_models(&self) -> Vec<crate::lowered::OrientationModel> {
        let model = |o: &OrientationSymbols| crate::lowered::OrientationModel {
            name: o.name.clone(),
            theta: o.theta,
            quaternion: o.quaternion,
        };
        self.orientations.iter().map(model).collect()
    }

    /// The index of the orientation named `name`, if one is in scope.
    pub fn orientation_index(&self, name: &str) -> Option<usize> {
        match self.scope.get(name) {
            Some(Binding::Orientation(k)) => Some(*k),
            _ => None,
        }
    }

    /// Brings parameter `name` (a struct field) into scope and returns its symbol.
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

    /// Lowers an expression of the description; `None` after reporting an error
    /// at its token (an unknown name, a function it does not know, a velocity
    /// where `mode` allows none).
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
}

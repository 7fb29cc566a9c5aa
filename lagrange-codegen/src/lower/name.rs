//! Names: coordinates, parameters, inputs, definitions, `t` and `pi`, with the
//! rules that need the name resolved (constant masses, velocities in positions,
//! inputs where their rate would be needed).

use lagrange_symbolic::Expr as Sym;
use syn::Ident;

use super::{Binding, Lowerer, Mode};

impl Lowerer<'_> {
    pub(super) fn name(&mut self, id: &Ident, mode: Mode) -> Option<Sym> {
        let key = id.to_string();
        match key.as_str() {
            "t" => {
                if mode == Mode::Constant {
                    let what = self.describe(mode);
                    self.cx.error_at(
                        id.span(),
                        format!("{what} must be constant: it cannot depend on time `t`"),
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
                            "{} must be constant: it cannot depend on the coordinate `{key}`",
                            self.describe(mode)
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
            }) => self.definition(id, mode, value, (has_velocity, has_state), input),
            Some(Binding::Orientation(_)) => {
                self.cx.error_at(
                    id.span(),
                    format!("`{key}` is an orientation, not a number; use it as a rotation (`rotation = {key}`, or a factor of one)"),
                );
                None
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
                    "unknown symbol `{key}`: not a coordinate, a parameter field, an input, a definition, a point or body, or `t`"
                );
                self.cx.error_at(id.span(), msg);
                None
            }
        }
    }

    /// A use of a definition: refused where its input, velocities or state
    /// may not appear (the definition itself lowered without error).
    fn definition(
        &mut self,
        id: &Ident,
        mode: Mode,
        value: Sym,
        (has_velocity, has_state): (bool, bool),
        input: Option<Sym>,
    ) -> Option<Sym> {
        let key = id.to_string();
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
                    self.describe(mode)
                ),
            );
            return None;
        }
        if mode == Mode::Constant && has_state {
            self.cx.error_at(
                id.span(),
                format!(
                    "{} must be constant, but `{key}` depends on the state or time",
                    self.describe(mode)
                ),
            );
            return None;
        }
        Some(value)
    }
}

//! Where inputs may not appear, and why.

/// A place of the description that inputs may not reach, with the reason the
/// error gives. Inputs have no known time derivative, so they are kept out of
/// everything the derivation differentiates in time.
#[derive(Copy, Clone, Debug)]
pub struct NoInputs {
    /// What the place is, as the error names it.
    pub place: &'static str,
    /// Why inputs may not appear there.
    pub why: &'static str,
}

const NO_RATE: &str =
    "the equations of motion would need its time derivative, which is not supplied at run time";

impl NoInputs {
    /// A point's or body's position ξ(q, t).
    pub const POSITION: NoInputs = NoInputs {
        place: "a position map",
        why: NO_RATE,
    };
    /// A body's rotation R(q, t).
    pub const ROTATION: NoInputs = NoInputs {
        place: "a rotation",
        why: NO_RATE,
    };
    /// A point's or body's mass.
    pub const MASS: NoInputs = NoInputs {
        place: "a mass",
        why: "a mass is constant, and the equations of motion would need its time derivative, which is not supplied at run time",
    };
    /// A body's inertia.
    pub const INERTIA: NoInputs = NoInputs {
        place: "an inertia",
        why: "an inertia is constant, and the equations of motion would need its time derivative, which is not supplied at run time",
    };
    /// The gravity field.
    pub const GRAVITY: NoInputs = NoInputs {
        place: "gravity",
        why: "gravity is a fixed field of the unforced system, part of its conserved energy",
    };
    /// A holonomic constraint f(q, t).
    pub const HOLONOMIC: NoInputs = NoInputs {
        place: "a holonomic constraint",
        why: "the constraint is differentiated twice in time, which would need the input's time derivatives, not supplied at run time",
    };
    /// A nonholonomic constraint.
    pub const NONHOLONOMIC: NoInputs = NoInputs {
        place: "a nonholonomic constraint",
        why: "the constraint is differentiated in time, which would need the input's time derivative, not supplied at run time",
    };
    /// A joint's damping, armature, gear ratio or rotor inertia.
    pub const JOINT: NoInputs = NoInputs {
        place: "a joint's coefficients",
        why: "a joint's coefficients are constants of the system, read from the parameters alone",
    };
    /// A shape's sizes.
    pub const SHAPE: NoInputs = NoInputs {
        place: "a shape's size",
        why: "a shape is drawn from the parameters alone, before any input is known",
    };
    /// An independent speed of the reduced form.
    pub const SPEED: NoInputs = NoInputs {
        place: "a speed",
        why: "the reduced equations differentiate the speeds in time, which would need the input's time derivative, not supplied at run time",
    };

    const FIX: &'static str =
        "apply the input as a force (`force`, `generalized_force`, `potential` or `dissipation`)";

    pub(super) fn message(self, input: &str, via: Option<&str>) -> String {
        let place = self.place;
        let why = self.why;
        let fix = Self::FIX;
        match via {
            None => format!("input `{input}` cannot appear in {place}: {why}; {fix}"),
            Some(d) => format!(
                "`{d}` uses the input `{input}`, which cannot appear in {place}: {why}; {fix}"
            ),
        }
    }
}

//! The attribute's words, each spelled once: the keys of `#[lagrange(...)]`
//! with the form each takes, the outputs of `emit(...)` and the formulations
//! of `formulation(...)` with what each gives. Parsing, the spelling
//! suggestions ([`crate::spelling`]) and the error messages read these tables,
//! so that a word added here is accepted, suggested and listed alike.

use crate::ast::{Extra, Formulation};
use crate::spelling::closest;

/// One word of the attribute.
pub(super) struct Word<T: 'static> {
    /// As the user writes it.
    pub spelling: &'static str,
    /// What it parses to.
    pub value: T,
    /// For a key, the form it takes; for an output or a formulation, what it
    /// gives.
    pub about: &'static str,
}

/// The words of one place of the attribute, in the order the messages list
/// them.
pub(super) struct Words<T: 'static>(&'static [Word<T>]);

impl<T: Copy + PartialEq> Words<T> {
    /// The meaning of `word`, if it is one of these.
    pub fn find(&self, word: &str) -> Option<T> {
        self.0.iter().find(|w| w.spelling == word).map(|w| w.value)
    }

    /// The word of `value`.
    pub fn word(&self, value: T) -> &'static Word<T> {
        (self.0.iter().find(|w| w.value == value)).expect("every value is spelled in its table")
    }

    pub fn spellings(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.0.iter().map(|w| w.spelling)
    }

    /// The word `typo` likely meant, if one is close.
    pub fn closest(&self, typo: &str) -> Option<&'static str> {
        closest(typo, self.spellings())
    }

    /// The spellings joined by `separator`.
    pub fn joined(&self, separator: &str) -> String {
        self.spellings().collect::<Vec<_>>().join(separator)
    }

    /// "`a`, `b` or `c`".
    pub fn alternatives(&self) -> String {
        let quoted: Vec<String> = self.spellings().map(|s| format!("`{s}`")).collect();
        match quoted.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
            _ => quoted.concat(),
        }
    }

    /// One line per word: "`word`: what it gives".
    pub fn described(&self) -> String {
        let lines: Vec<String> = (self.0.iter())
            .map(|w| format!("  `{}`: {}", w.spelling, w.about))
            .collect();
        lines.join("\n")
    }
}

/// A top-level key of `#[lagrange(...)]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Key {
    Urdf,
    Coordinates,
    Orientation,
    Inputs,
    Define,
    Point,
    Body,
    Gravity,
    Potential,
    Force,
    Torque,
    GeneralizedForce,
    Dissipation,
    Holonomic,
    Nonholonomic,
    Speeds,
    Formulation,
    Emit,
    Shape,
    Contact,
    Stop,
    Joint,
}

const fn word<T>(spelling: &'static str, value: T, about: &'static str) -> Word<T> {
    Word {
        spelling,
        value,
        about,
    }
}

/// The keys, with the form each takes.
pub(super) const KEYS: Words<Key> = Words(&[
    word("urdf", Key::Urdf, "urdf(\"path\", ..)"),
    word("coordinates", Key::Coordinates, "coordinates(q1, q2, ...)"),
    word("orientation", Key::Orientation, "orientation(name, ...)"),
    word("inputs", Key::Inputs, "inputs(u1, u2, ...)"),
    word("define", Key::Define, "define(name = expr, ...)"),
    word("point", Key::Point, "point(name, mass = m, at = [x, y, z])"),
    word(
        "body",
        Key::Body,
        "body(name, mass = m, inertia = [..], at = [..], rotation = ..)",
    ),
    word("gravity", Key::Gravity, "gravity = [gx, gy, gz]"),
    word("potential", Key::Potential, "potential = expr"),
    word("force", Key::Force, "force(point, [fx, fy, fz])"),
    word("torque", Key::Torque, "torque(body, [tx, ty, tz])"),
    word(
        "generalized_force",
        Key::GeneralizedForce,
        "generalized_force(q = expr, ...)",
    ),
    word("dissipation", Key::Dissipation, "dissipation = expr"),
    word(
        "holonomic",
        Key::Holonomic,
        "holonomic(name = f(q, t), ...)",
    ),
    word(
        "nonholonomic",
        Key::Nonholonomic,
        "nonholonomic(name = a(q, t)·q̇ + b, ...)",
    ),
    word("speeds", Key::Speeds, "speeds(name = expr, ...)"),
    word("formulation", Key::Formulation, "formulation(..)"),
    word("emit", Key::Emit, "emit(..)"),
    word(
        "shape",
        Key::Shape,
        "shape(body, cylinder(radius = r, length = l, axis = y))",
    ),
    word(
        "contact",
        Key::Contact,
        "contact(name, on = point, normal = [0, 0, 1], restitution = e, friction = mu)",
    ),
    word("stop", Key::Stop, "stop(name, q >= lower, restitution = e)"),
    word(
        "joint",
        Key::Joint,
        "joint(q, damping = b, friction = fc, armature = Ia, motor = u, gear = n, rotor = Ir)",
    ),
]);

/// An option of `joint(...)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum JointOption {
    Damping,
    Friction,
    Armature,
    Motor,
    Gear,
    Rotor,
}

/// The options of `joint(...)`.
pub(super) const JOINT_OPTIONS: Words<JointOption> = Words(&[
    word(
        "damping",
        JointOption::Damping,
        "damping = b: viscous damping, −b q̇ in the coordinate's generalized force (b ≥ 0)",
    ),
    word(
        "friction",
        JointOption::Friction,
        "friction = fc: Coulomb friction at the joint, |τ_f| ≤ fc (a number ≥ 0), run by `run_contacts`",
    ),
    word(
        "armature",
        JointOption::Armature,
        "armature = Ia: a rotor's reflected inertia, added to M's diagonal entry (q, q) (Ia ≥ 0)",
    ),
    word(
        "motor",
        JointOption::Motor,
        "motor = u: the input u is a motor's torque, n u on the coordinate through the gear",
    ),
    word(
        "gear",
        JointOption::Gear,
        "gear = n: the gear ratio, motor turns per joint turn (n > 0; 1 when left out)",
    ),
    word(
        "rotor",
        JointOption::Rotor,
        "rotor = Ir: the motor's rotor inertia, n² Ir added to M's diagonal entry (q, q) (Ir ≥ 0)",
    ),
]);

/// An option of `contact(...)` or `stop(...)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ContactOption {
    On,
    Radius,
    Normal,
    Offset,
    Against,
    AgainstRadius,
    Restitution,
    Friction,
}

/// The options of `contact(...)` (a `stop(...)` takes `restitution` alone).
pub(super) const CONTACT_OPTIONS: Words<ContactOption> = Words(&[
    word(
        "on",
        ContactOption::On,
        "on = point: the point, or the body whose centre carries the sphere",
    ),
    word(
        "radius",
        ContactOption::Radius,
        "radius = r: a sphere of radius r around it (0 if not written)",
    ),
    word(
        "normal",
        ContactOption::Normal,
        "normal = [nx, ny, nz]: the plane's normal, as numbers, towards the free side",
    ),
    word(
        "offset",
        ContactOption::Offset,
        "offset = d: the plane n·x = d (0 if not written)",
    ),
    word(
        "against",
        ContactOption::Against,
        "against = other: a second point or body, whose sphere the first one's meets (no `normal`)",
    ),
    word(
        "against_radius",
        ContactOption::AgainstRadius,
        "against_radius = r: the second sphere's radius (0 if not written)",
    ),
    word(
        "restitution",
        ContactOption::Restitution,
        "restitution = e: Newton's coefficient, a number in [0, 1]",
    ),
    word(
        "friction",
        ContactOption::Friction,
        "friction = mu: Coulomb's coefficient, a number ≥ 0 (0 if not written)",
    ),
]);

/// The outputs `emit(...)` asks for.
pub(super) const OUTPUTS: Words<Extra> = Words(&[
    word(
        "reactions",
        Extra::Reactions,
        "the Cartesian reactions on points and bodies, from the multipliers",
    ),
    word(
        "coriolis",
        Extra::Coriolis,
        "the Coriolis matrix C(q, q̇), with Ṁ − 2C skew-symmetric",
    ),
    word(
        "jacobians",
        Extra::Jacobians,
        "the right-hand side's Jacobians, for the implicit integrators and the linearisation",
    ),
    word(
        "hamiltonian",
        Extra::Hamiltonian,
        "Hamilton's form: the momentum ∂T/∂q̇ and ∂T/∂q, for the symplectic integrators",
    ),
    word(
        "articulated",
        Extra::Articulated,
        "q̈ as one program on a kinematic tree: the articulated-body algorithm or M factorised, the one with fewer operations",
    ),
    word(
        "inverse_dynamics",
        Extra::InverseDynamics,
        "τ = M q̈ + h − Q and the gravity torques",
    ),
    word(
        "kinematics",
        Extra::Kinematics,
        "the bodies' frame Jacobians and J̇ q̇, the centre of mass and its Jacobian",
    ),
    word(
        "atlas",
        Extra::Atlas,
        "a second chart for each rotation in Euler angles, through the free twin",
    ),
    word(
        "batched",
        Extra::Batched,
        "q̈ (and, with `jacobians`, its derivatives) over four states per call, in SIMD lanes",
    ),
    word(
        "regressor",
        Extra::Regressor,
        "the dynamics regressor Y(q, q̇, q̈) with τ = Y π, π the bodies' inertial parameters (and the joints' damping, friction and armature), the energy and momentum regressors",
    ),
]);

/// The forms `formulation(...)` chooses.
pub(super) const FORMULATIONS: Words<Formulation> = Words(&[
    word(
        "multipliers",
        Formulation::Multipliers,
        "M q̈ + h = Q + Gᵀν with G q̈ = γ, which gives the reactions",
    ),
    word(
        "reduced",
        Formulation::Reduced,
        "the equations projected onto independent speeds (Maggi, Gibbs–Appell)",
    ),
]);

impl Key {
    /// The form a key written with its entries in parentheses takes, for the
    /// error when it is written `key = ...` (`None` for a key that takes a
    /// value). The lists of words are written out from their tables.
    pub fn list_form(self) -> Option<String> {
        let Word {
            spelling, about, ..
        } = KEYS.word(self);
        match self {
            Key::Emit => Some(format!("emit({})", OUTPUTS.joined(", "))),
            Key::Formulation => Some(format!("formulation({})", FORMULATIONS.joined(", "))),
            Key::Urdf => None,
            _ => about
                .starts_with(&format!("{spelling}("))
                .then(|| about.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_word_is_spelled_once() {
        fn once<T: Copy + PartialEq>(words: &Words<T>) {
            let all: Vec<&str> = words.spellings().collect();
            for (i, w) in all.iter().enumerate() {
                assert!(!all[..i].contains(w), "`{w}` spelled twice");
                let value = words.find(w).unwrap();
                assert_eq!(words.word(value).spelling, *w);
            }
        }
        once(&KEYS);
        once(&OUTPUTS);
        once(&FORMULATIONS);
        once(&CONTACT_OPTIONS);
        once(&JOINT_OPTIONS);
    }

    #[test]
    fn the_lists_are_written_from_the_tables() {
        assert_eq!(FORMULATIONS.alternatives(), "`multipliers` or `reduced`");
        let emit = Key::Emit.list_form().unwrap();
        for output in OUTPUTS.spellings() {
            assert!(emit.contains(output), "{emit} leaves out {output}");
        }
        assert_eq!(Key::Gravity.list_form(), None);
        assert_eq!(Key::Urdf.list_form(), None);
        assert_eq!(
            Key::Coordinates.list_form().as_deref(),
            Some("coordinates(q1, q2, ...)")
        );
    }
}

//! Unilateral contacts with Coulomb friction, run event by event
//! ([`Simulation::run_contacts`](crate::Simulation::run_contacts)), or
//! time-stepped when the run's integrator is
//! [`MoreauJean`](crate::MoreauJean) (below, **Time stepping**).
//!
//! The scheme is the active-set, event-driven one of Pfeiffer and Glocker.
//! Between events each contact is in one mode ([`ContactState`]): apart,
//! sliding or sticking. A closed contact is a constraint on the
//! accelerations, M q̈ + h = Q + Jᵀλ with J q̈ = −J̇ q̇, whose normal force
//! must stay compressive; a sliding one adds Coulomb's force −μ λ_n û along
//! its slip; a sticking one holds its tangent rows too, while the friction
//! force stays inside the isotropic cone |λ_t| ≤ μ λ_n. The modes change at
//! events located on the integrator's dense output like any other event
//! ([`Event`](crate::Event)), each the zero of a function of the state:
//!
//! - **touching**: an open contact's gap falls to zero; the contacts at the
//!   surface then take one impulse problem together (`impact`): Newton's law
//!   per contact, a plastic one for a contact that closes, and Coulomb's
//!   cone on the impulses where a contact rubs (a stick impulse stops its
//!   slip while the cone holds it, a sliding one is μ times the normal
//!   impulse against the slip after);
//! - **lifting off**: a closed contact's normal force falls to zero;
//! - **stopping**: a sliding contact's slip speed falls to zero (its slip
//!   along the direction it started with crosses zero), after which it
//!   sticks if the cone can hold it, or slides on in the new direction;
//! - **slipping**: a sticking contact's friction reaches the cone's edge
//!   (μ λ_n − |λ_t| falls to zero).
//!
//! At each event the modes are chosen again: contacts whose force would
//! pull are opened, sticking ones whose friction would leave the cone slide
//! (opposite to the force that would have held them), until every closed
//! contact pushes and every sticking one is inside its cone. When no choice
//! does, or a sliding contact presses the harder the more it is pushed
//! (Painlevé's paradox), the run stops with a [`ContactError`]
//! saying so; rigid contact then has no answer, or several, and none is
//! picked silently.
//!
//! **Zeno.** A bouncing ball's impacts accumulate at a finite time. When an
//! impact would leave a contact slower than the rest speed
//! ([`ContactSettings::rest_speed`]) while the free motion presses it back,
//! the contact closes plastically instead, and the run records
//! ([`ChangeKind::Rests`]) where the bounces would have accumulated,
//! t + 2u / (|a_n| (1 − e)) for an impact leaving at u under the normal
//! acceleration a_n (exact while a_n is constant over the remaining
//! bounces). The energy dropped is ½ m u² at most.
//!
//! **Dry friction at a joint** ([`ContactKind::DryFriction`]) runs through
//! the same modes: a contact with no gap and no normal force, always in
//! force, its friction bounded by a fixed fc instead of μ λ_n; it sticks
//! and slips at the same events, and takes no impulse at an impact.
//!
//! **Scope.** Contacts are points or spheres against planes, two spheres
//! (with or without friction) and stops on coordinates. On a system with free orientations the rows are
//! in the velocities v (ω in body axes), the state moves on the group, and
//! the time stepper's midpoint is q ⊕ h/2 v.
//!
//! **Time stepping.** With [`MoreauJean`](crate::MoreauJean) as the
//! integrator, the run takes fixed steps instead (`stepping`): at each
//! step's midpoint the contacts whose gap is closed (below the gap
//! tolerance) take one impulse problem (`coulomb`): Newton's law at the
//! velocity level and Coulomb's cone on the impulses, solved by nonsmooth
//! Gauss–Seidel. The changes are read off the impulses at the midpoint of
//! the step they happen in: an impulse on a contact that was apart is an
//! impact (or a closing, without speed), a contact whose impulse vanishes
//! lifts off, and the local solution's branch says sticking or sliding.
//! No event is located, nothing stalls, and the answers are of order one
//! in the step; impacts there have friction.
//!
//! **Compliant contacts.** With
//! [`Simulation::compliant_contacts`](crate::Simulation::compliant_contacts)
//! the contacts are springs and dampers instead (`compliant`,
//! [`Compliant`]), and the run is one smooth integration by the
//! simulation's integrator, its touches and releases located as events
//! that restart it.
//!
//! **Allocation.** Unlike the other runs, which allocate only their growing
//! [`Trajectory`](crate::Trajectory), a contact run allocates at every
//! evaluation of the accelerations (every stage of its integrator): the
//! per-contact vectors of the forces, and while a contact is closed the
//! rows of the contacts in force, their responses
//! M⁻¹ Jᵀ, and the k × k matrix J M⁻¹ Jᵀ with its right-hand side as
//! `Vec`s and a `DMatrix` (k the unknown forces: one normal and up to two
//! tangential per closed contact; k is known only when the modes are
//! chosen), and each impact's impulse problem likewise. For the few
//! contacts these runs are for, that is a few small heap blocks a stage;
//! moving them to the stack, sized by the system's contacts, is not done.
//!
//! [`ContactError`]: crate::error::ContactError
//! [`ContactKind::DryFriction`]: crate::ContactKind::DryFriction

mod compliant;
mod coulomb;
mod driver;
mod form;
mod impact;
mod modes;
mod run;
mod stepping;

pub use compliant::Compliant;
pub use run::{ChangeKind, ContactChange, ContactForce, ContactRun, ContactSettings, ContactState};

pub(crate) use driver::run_contacts;

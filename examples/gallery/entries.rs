//! The gallery's systems in the order of its table: each one's name, what it
//! demonstrates, and the function that runs it.

use crate::row::Entry;
use crate::{
    cavity, constrained, contact, control, free, identification, legged, minimal, nonholonomic,
    planning,
};

/// The cavity row's name (its animation is looked up by it).
pub(crate) const CAVITY: &str = "C10 point in a spherical cavity, e = 0.7";
/// The double pendulum's row name (its animation is looked up by it).
pub(crate) const DOUBLE_PENDULUM: &str = "double pendulum";
/// The steady rolling disk's row name (its animation is looked up by it).
pub(crate) const ROLLING_DISK: &str = "rolling disk, steady circle";

const fn entry(
    name: &'static str,
    about: &'static str,
    run: fn(&'static str) -> Result<crate::row::Row, lagrange::Error>,
) -> Entry {
    Entry { name, about, run }
}

pub(crate) const ENTRIES: &[Entry] = &[
    // Free rotations: a quaternion in q, no chart.
    entry(
        "tumbling brick, intermediate-axis flip",
        "orientation(turn): a unit quaternion and the body-axis angular velocity; the flip period against the elliptic closed form",
        free::intermediate_axis,
    ),
    entry(
        "tumbling body, 200 flips, symplectic on the group",
        "emit(hamiltonian) with a quaternion: Gauss steps each quaternion as four coordinates with four momenta; the energy error stays where it started",
        free::symplectic_tumbling,
    ),
    entry(
        "heavy top spun exactly upright",
        "θ = 0, where Euler angles stop, is an ordinary state; stability from the tangent-space linearisation",
        free::upright_top,
    ),
    entry(
        "heavy top in Euler angles through θ = 0 (atlas)",
        "emit(atlas): the user's z-x-z angles, a second chart where they stop, switched with hysteresis; the run matches the quaternion top",
        free::atlas_top,
    ),
    // Minimal coordinates.
    entry(
        "simple pendulum, 179°, period by events",
        "events located on the dense output; the period against the elliptic-integral closed form",
        minimal::pendulum_period,
    ),
    entry(
        "C1 spherical pendulum (θ, φ)",
        "minimal coordinates; p_φ conserved (cyclic coordinate)",
        minimal::spherical,
    ),
    entry(
        "C2 ellipsoid with growing axes",
        "rheonomic position maps ξ(q, t)",
        minimal::ellipsoid,
    ),
    entry(
        "C3 dumbbell (rod, free)",
        "a rigid rod as two particles; free fall of the centre of mass",
        minimal::dumbbell,
    ),
    entry(
        "C7 heavy particle, vertical plane",
        "the textbook parabola",
        minimal::heavy_particle,
    ),
    entry(
        DOUBLE_PENDULUM,
        "chaos with the energy kept to the tolerance",
        minimal::double_pendulum,
    ),
    entry(
        "5-link pendulum (relative angles)",
        "a longer chain, relative angles",
        minimal::chain,
    ),
    entry(
        "damped driven pendulum",
        "dissipation and a time-dependent force",
        minimal::driven,
    ),
    // Constraints with multipliers, rigid bodies.
    entry(
        "C1 spherical pendulum, Cartesian + λ",
        "holonomic constraint with a multiplier, drift projection, the rod tension",
        constrained::cartesian_pendulum,
    ),
    entry(
        "C3 rod as a constraint (6 coords + λ)",
        "the dumbbell again, the rod as a constraint",
        constrained::rod_pair,
    ),
    entry(
        "C4 body as three particles",
        "rigid-body inertia tensor against three particles",
        constrained::three_particles,
    ),
    entry(
        "C5 rolling sphere, multipliers",
        "nonholonomic rolling with multipliers",
        constrained::sphere_multipliers,
    ),
    entry(
        "C5 rolling sphere, reduced (Maggi)",
        "the same sphere in reduced form (independent speeds)",
        constrained::sphere_reduced,
    ),
    entry(
        "C6 tops joined by an untwistable thread",
        "a nonholonomic coupling of two rigid bodies",
        constrained::threaded_tops,
    ),
    // Reduced forms, impacts.
    entry(
        "C8 polar, quasi-velocity x ẏ − y ẋ",
        "Gibbs–Appell equations on a quasi-velocity",
        nonholonomic::polar,
    ),
    entry(
        "C9 sphere on a turning plane",
        "rheonomic rolling; the velocity turns at 2Ω/7",
        nonholonomic::turntable,
    ),
    entry(
        ROLLING_DISK,
        "steady circular rolling from the closed-form condition",
        nonholonomic::rolling_disk,
    ),
    entry(
        CAVITY,
        "impacts by events, then sliding on the wall with a multiplier",
        cavity::row,
    ),
    entry(
        "Chaplygin sleigh",
        "a knife edge in reduced form",
        nonholonomic::sleigh,
    ),
    // Unilateral contacts: run_contacts, event by event.
    entry(
        "ball bouncing to rest, e = 0.5",
        "contact(floor, radius, restitution): Newton's impacts, then the Zeno rest at the accumulation time t₁(1+e)/(1−e)",
        contact::bouncing_ball,
    ),
    entry(
        "ball thrown with backspin, μ = 0.3",
        "Coulomb friction slipping, then sticking: it rolls back at (5v₀ − 2rω₀)/7 from t = 2(v₀ + rω₀)/(7μg)",
        contact::backspin_ball,
    ),
    entry(
        "block sliding to a stop, μ = 0.4",
        "pushed obliquely: the isotropic cone keeps the slip's direction; stops at |v₀|/(μg)",
        contact::sliding_block,
    ),
    entry(
        "pendulum against a stop, e = 0.6",
        "stop(wall, theta >= 0): impacts when the elliptic-integral periods say",
        contact::stopped_pendulum,
    ),
    entry(
        "box tossed onto the floor, μ = 0.5",
        "four corners by Moreau–Jean time stepping (h = 1 ms): frictional impacts, rocking, at rest flat",
        contact::tossed_box,
    ),
    entry(
        "Solo 12 dropped, standing under PD",
        "its URDF on a free root, four point feet (μ = 1), twelve PD-held joints; Moreau–Jean (h = 0.5 ms) beside the event-driven run",
        legged::solo_12,
    ),
    // Control and linearisation.
    entry(
        "two-link arm, computed-torque tracking",
        "a controller in a closure, inverse dynamics from the model",
        control::arm,
    ),
    entry(
        "UR5 from its URDF, computed torque to a target",
        "a robot read from its URDF file at compile time, driven by its own recursive Newton–Euler inverse dynamics",
        control::ur5,
    ),
    entry(
        "UR5 operational-space control, tool on a circle",
        "task-space computed torque through the frame Jacobian, J̇ q̇ and inverse dynamics: position and orientation (log R_d Rᵀ) tracked with the designed error dynamics",
        control::ur5_circle,
    ),
    entry(
        "cart-pole, LQR from the linearisation",
        "LQR gain from the symbolic linearisation, continuous feedback",
        control::cart_pole_continuous,
    ),
    entry(
        "cart-pole, LQR sampled at 100 Hz (ZOH)",
        "the same gain, sampled with zero-order hold",
        control::cart_pole_sampled,
    ),
    entry(
        "rolling disk upright, critical spin",
        "critical spin from the eigenvalues against √(g/3a); wobble above it",
        control::disk,
    ),
    entry(
        "Whipple bicycle at 5 m/s, roll-rate kick",
        "weave and capsize speeds against the published benchmark; self-stability",
        control::bicycle,
    ),
    // Plans: DDP on the model's one-step map and its derivatives, flown
    // on the continuous model with the plan's feedback.
    entry(
        "cart-pole swing-up, planned by DDP",
        "plan::Ddp with the input bounded at 5 N; the plan flown with its own gains at 50 Hz, then caught by LQR",
        planning::cart_pole_swing_up,
    ),
    entry(
        "acrobot swing-up, planned by DDP",
        "driven only at the elbow: DDP from a pumping guess, flown with the plan's gains, held upright by LQR",
        planning::acrobot_swing_up,
    ),
    entry(
        "planar quadrotor flip, planned by DDP",
        "one turn from hover to hover in 2 s, each thrust between zero and the weight",
        planning::quadrotor_flip,
    ),
    entry(
        "quadrotor flip in 3-D, planned by DDP on the group",
        "a free orientation: one roll from hover to hover in 2 s through two attitude waypoints, thrusts between zero and twice the hover's; flown with the plan's tangent gains, held by LQR",
        planning::quadrotor_flip_3d,
    ),
    entry(
        "UR5 reaching a point within ±40 N·m, planned by DDP",
        "a cost on the tool frame's position through the emitted kinematics; torque bounds a quarter of the file's",
        planning::ur5_reach,
    ),
    entry(
        "cart-pole swung up by MPC, pole 50 % heavier than the model",
        "plan::Mpc re-planning at 20 Hz within 10 iterations a sample, on a model that is wrong",
        planning::cart_pole_mpc,
    ),
    // Identification: the model fitted to measured motion.
    entry(
        "UR5 with an unknown 1.3 kg payload, identified",
        "an exciting trajectory within limits, torques measured with 0.05 N·m of noise: the base parameters by least squares, the payload's mass and centre with the arm known, estimated again as the samples come in",
        identification::ur5_payload,
    ),
];

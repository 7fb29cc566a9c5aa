//! # lagrange
//!
//! Describe a mechanical system declaratively; get its equations of motion compiled
//! into specialised Rust at build time; integrate them at run time.
//!
//! ```
//! use lagrange::prelude::*;
//!
//! /// A spherical pendulum in the chart (θ, φ), θ measured from the downward vertical.
//! #[derive(Lagrangian)]
//! #[lagrange(
//!     coordinates(theta, phi),
//!     point(bob, mass = m, at = [l * sin(theta) * cos(phi),
//!                                l * sin(theta) * sin(phi),
//!                                -l * cos(theta)]),
//!     gravity = [0, 0, -g],
//! )]
//! pub struct SphericalPendulum { pub m: f64, pub l: f64, pub g: f64 }
//!
//! let sys = SphericalPendulum { m: 1.0, l: 2.0, g: 9.81 };
//! let traj = Simulation::new(&sys)
//!     .integrator(Dopri5::tol(1e-10))
//!     .run(Vector2::new(1.0, 0.0), Vector2::new(0.0, 1.0), 0.0..10.0)
//!     .unwrap();
//! assert!(traj.integral_drift() < 1e-8);
//! ```
//!
//! New here? Read the [guide] (nine short chapters); what follows is the reference.
//!
//! ## The description language
//!
//! All items go in `#[lagrange(...)]` (several such attributes are concatenated).
//! The fields are the parameters, all of one float type (`f64`, `f32` or a
//! type parameter `T`), the type the generated code computes in.
//!
//! | item | meaning |
//! |---|---|
//! | `coordinates(q1, q2, ...)` | generalized coordinates, in order |
//! | `orientation(name, ...)` | a free rotation without a chart (see *Free rotations* below): a unit quaternion in q, the angular velocity in body axes in v; `rotation = name` (or a factor of a product: `rotation = parent * name`) |
//! | `inputs(u1, u2, ...)` | named signals supplied at run time (forces, torques, set-points): the system implements [`Driven`]; allowed in `force`, `generalized_force`, `potential`, `dissipation` and the `define`s used there, an error in positions, rotations, masses, inertias, gravity, constraints and speeds (which would need the input's time derivative) |
//! | `define(r = expr, ...)` | intermediate definitions, usable by later expressions |
//! | `point(name, mass = m, at = [x, y(, z)])` | a point mass at ξ(q, t); planar or spatial |
//! | `gravity = [gx, gy(, gz)]` | uniform gravity acting on every point |
//! | `potential = expr` | potential energy V(q, t) |
//! | `force(point, [fx, fy(, fz)])`, `torque(body, [tx, ty, tz])` | a Cartesian force at a point; a torque on a body, in world axes (or its own, `axes = body`); both may read q, `dot(q)`, t and inputs |
//! | `generalized_force(q = expr)` | a generalized force on one coordinate; several entries on one coordinate are added |
//! | `dissipation = expr` | Rayleigh dissipation function D(q, q̇), Q −= ∂D/∂q̇ |
//! | `body(name, mass = m, inertia = [A, B, C], at = [x, y, z], rotation = R, com = [..], about = [..])` | a rigid body: reference point `at` (the centre of mass unless `com = [bx, by, bz]` places it in body axes), principal moments (or six entries `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]`, entries of the inertia tensor: I_xy = −∫xy dm) in body axes about the centre of mass, or about the body point `about = [ax, ay, az]` (relative to `at`; the macro applies the parallel-axis theorem), orientation R(q, t) body → world |
//! | `point(name, on = body, at = [bx, by, bz])` | a point fixed in a body, in body coordinates; `mass = m` optional |
//! | `holonomic(name = f, ...)` | constraints f(q, t) = 0, kept with multipliers λ |
//! | `nonholonomic(name = e, ...)` | constraints e = a(q, t)·q̇ + b(q, t) = 0; must be linear in the velocities |
//! | `speeds(u = expr, ...)` | independent speeds / quasi-velocities u = U(q, t) q̇ + u₀ for the reduced form |
//! | `formulation(multipliers, reduced)` | which constrained equations to emit (default: multipliers, or reduced when `speeds` are given; `reduced` alone picks independent velocities itself) |
//! | `emit(reactions, coriolis, jacobians, hamiltonian, articulated, inverse_dynamics, kinematics, batched, regressor)` | optional outputs: `reactions(q, v, t, ν)` per point and `generalized_reactions(q, t, ν)` (G_αᵀ ν_α) per constraint, on points or coordinates; `coriolis_matrix(q, v, t)`; [`Lagrangian::rhs_jacobians`] (used by [`Radau5`] instead of finite differences), for a system without constraints [`Differentiable`] (q̈ and ∂q̈/∂q, ∂q̈/∂q̇, ∂q̈/∂τ = M⁻¹ as one program, M factorised in it, or, on a chain whose program passes 8,000 operations, around M's factorisation at run time: [`acceleration_derivatives`], Pinocchio's `computeABADerivatives`) and, for the constrained forms, [`Constrained::constraint_derivatives`] and [`Reduced::row_derivatives`] (linearisation); [`Lagrangian::momentum`] and [`Lagrangian::kinetic_gradient`] (Hamilton's form, needed by the symplectic [`Gauss`] method); [`Lagrangian::forward_dynamics`] (q̈ as one program on a kinematic tree: the articulated-body algorithm or M factorised in the program, whichever has fewer operations, [`Lagrangian::FORWARD_ROUTE`]; the unconstrained dynamics then use it instead of M and Cholesky); `inverse_dynamics` overrides `Lagrangian::inverse_dynamics` (τ = M q̈ + h − Q, by recursive Newton–Euler on a kinematic tree, O(n); the default computes M) and `Lagrangian::gravity_torques` (∂V_gravity/∂q); `kinematics` implements `Kinematics`: each body frame's geometric Jacobian at its origin in world-aligned or its own axes and J̇ q̇ (`frame_jacobian`, `frame_jacobian_local`, `frame_bias`, by `body_index("tool0")`), the moving masses' centre of mass and its Jacobian; `batched` (beside `articulated` or `jacobians`, on an `f64` system without constraints) implements [`Batched`] and, with `jacobians`, [`BatchedDifferentiable`]: the same q̈ and derivative programs over four states per call in [`F64x4`] lanes, read checked through [`batched_accelerations`] and [`batched_acceleration_derivatives`]; `regressor` (a kinematic tree) overrides [`Lagrangian::regressor`], [`Lagrangian::inertial_parameters`] and [`Lagrangian::REGRESSOR_PARAMETERS`]: Y(q, q̇, q̈) with M q̈ + h − Q_gravity = Y π, π each body's ten inertial parameters in Pinocchio's order, for [`identify`] |
//!
//! Rotations are products of `rot_x(a)`, `rot_y(a)`, `rot_z(a)`,
//! `euler_zxz(ψ, θ, φ)` (= rot_z(ψ)·rot_x(θ)·rot_z(φ), Suslov's precession, nutation,
//! spin), `euler_zyx(yaw, pitch, roll)` and explicit 3×3 matrices `[[..], [..], [..]]`.
//! In expressions, `P.x`, `P.y`, `P.z` are the world coordinates of a point or a
//! body's centre, `dot(P.x)` their rates, `B.omega_x/y/z` (world axes) and
//! `B.omega_1/2/3` (body axes) a body's angular velocity, and `B.axis_x.x` …
//! `B.axis_z.z` the world components of a body's unit axes (R_ij =
//! `B.axis_<j>.<i>`, for attachments and contacts). Constraints written in
//! point coordinates give Cartesian reactions R = Σ ν ∂f/∂ξ on those points.
//!
//! Bodies that form a kinematic tree — each body's rotation its parent's followed
//! by `rot_x/y/z` of coordinates, its reference point a point fixed in the parent
//! (`at = [j.x, j.y, j.z]` with `point(j, on = parent, ..)`) or a fixed point —
//! are derived by the recursive algorithms: M by composite rigid bodies, h and
//! gravity by recursive Newton–Euler, O(n²) and O(n) operations instead of the
//! O(n³) of differentiating ξ(q) in 3-D. The same tree with its poses written
//! out (rotations as explicit matrices, often of `define`s, reference points
//! as ξ(q)) is read back: relative to the body whose coordinates its own
//! extend, each body must turn about a constant axis or slide along a fixed
//! line by one more coordinate (or not move: a fixed joint), which the derive
//! reads at q = 0 and checks at random configurations. Nothing needs
//! declaring; a small tree is derived both ways and the cheaper program kept,
//! and `ROUTE` and `EQUATIONS` say which route a system got and, for the
//! generic one, which body kept it there and why. The parameter-only parts of the
//! emitted programs are split off into [`Lagrangian::parameter_terms`], which
//! [`Simulation`] runs compute once per run.
//!
//! A constrained system implements [`Constrained`] (multipliers) and/or
//! [`Reduced`] (Maggi / Gibbs–Appell equations on the speeds).
//! [`Simulation::run`] is the one way to run any derived system: it integrates
//! the form the description emitted (the multiplier form when there is one,
//! else the reduced form); [`Simulation::run_constrained`] and
//! [`Simulation::run_reduced`] choose a form explicitly when both are emitted.
//!
//! ```
//! use lagrange::prelude::*;
//!
//! /// The spherical pendulum in Cartesian coordinates: no chart, no pole; the
//! /// thread is a constraint and its tension a reaction.
//! #[derive(Lagrangian)]
//! #[lagrange(
//!     coordinates(x, y, z),
//!     point(bob, mass = m, at = [x, y, z]),
//!     gravity = [0, 0, -g],
//!     holonomic(thread = (bob.x^2) + (bob.y^2) + (bob.z^2) - (l^2)),
//!     emit(reactions),
//! )]
//! pub struct Bob { pub m: f64, pub l: f64, pub g: f64 }
//!
//! let sys = Bob { m: 1.0, l: 1.0, g: 9.81 };
//! let traj = Simulation::new(&sys)
//!     .integrator(Dopri5::tol(1e-10))
//!     .drift(Drift::projection())
//!     .run([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0.0..5.0)
//!     .unwrap();
//! assert!(traj.max_residuals()[0] < 1e-11);
//!
//! // Released horizontally at rest length: the tension is m v²/l = 1 N at t = 0.
//! let (q, v) = (traj.positions()[0], traj.velocities()[0]);
//! let nu = ConstrainedDynamics::new(&sys).solve(0.0, &q, &v).unwrap().multipliers;
//! let tension = sys.reactions(&q, &v, 0.0, &nu)[0].norm();
//! assert!((tension - 1.0).abs() < 1e-12);
//! ```
//!
//! A constrained system cannot be run as if it were free:
//! [`Simulation::run_unconstrained`] (and anything else built on the
//! unconstrained [`Dynamics`]) on it is a compile error ("this system has
//! constraints, which the unconstrained dynamics would ignore: run it with
//! `run_constrained` ... or `run_reduced` ..."), reported when the code is built
//! (`cargo build`/`cargo test`; `cargo check` does not instantiate generic code
//! and so does not see it):
//!
//! ```compile_fail,E0080
//! use lagrange::prelude::*;
//!
//! #[derive(Lagrangian)]
//! #[lagrange(
//!     coordinates(x, y),
//!     point(bob, mass = m, at = [x, y]),
//!     gravity = [0, -g],
//!     holonomic(rod = (x^2) + (y^2) - 1),
//! )]
//! pub struct Bob { pub m: f64, pub g: f64 }
//!
//! let bob = Bob { m: 1.0, g: 9.81 };
//! let traj = Simulation::new(&bob).run_unconstrained([1.0, 0.0], [0.0, 0.0], 0.0..1.0);
//! ```
//!
//! With `inputs(u1, ...)` the derive implements [`Driven`]:
//! [`Driven::input_forces`] is ΔQ = Q(u) − Q(0), [`Driven::input_jacobians`]
//! gives ∂Q/∂u, ∂ΔQ/∂q and ∂ΔQ/∂q̇, and the [`Lagrangian`] methods are the
//! unforced system (every input at zero).
//!
//! ```
//! use lagrange::prelude::*;
//! use lagrange::Driven;
//!
//! /// A cart on a spring whose anchor `xs` is moved, pushed by `push`.
//! #[derive(Lagrangian)]
//! #[lagrange(
//!     coordinates(x),
//!     inputs(push, xs),
//!     point(cart, mass = m, at = [x, 0]),
//!     potential = k / 2 * ((x - xs)^2),
//!     generalized_force(x = push),
//! )]
//! pub struct Cart { pub m: f64, pub k: f64 }
//!
//! let sys = Cart { m: 2.0, k: 3.0 };
//! let (q, v) = (Vector1::new(0.5), Vector1::new(0.0));
//! let u = Vector2::new(1.0, 0.2);
//! // Q(u) − Q(0) = push + k xs; the unforced Q is −k x.
//! assert_eq!(sys.input_forces(&q, &v, &u, 0.0)[0], 1.0 + 3.0 * 0.2);
//! assert_eq!(sys.generalized_forces(&q, &v, 0.0)[0], -1.5);
//! let (dq_du, _, _) = sys.input_jacobians(&q, &v, &u, 0.0);
//! assert_eq!(dq_du, SMatrix::<f64, 1, 2>::new(1.0, 3.0));
//! ```
//!
//! Driven systems run under a controller — [`Simulation::feedback`]
//! (continuous, inside the right-hand side), [`Simulation::sampled`] (a digital
//! controller with zero-order hold), [`Simulation::open_loop`] or an
//! [`InputTable`] — in any of the three forms, with events and drift control;
//! the inputs are recorded with the trajectory. [`linear`] linearises about an
//! equilibrium or a steady motion from the emitted derivatives, analyses the
//! eigenvalues and designs LQR gains. A cart-pole caught from a 0.3 rad tilt:
//!
//! ```
//! use lagrange::prelude::*;
//! use lagrange::linear::linearize;
//! use lagrange::nalgebra::{DMatrix, DVector};
//!
//! #[derive(Lagrangian)]
//! #[lagrange(
//!     coordinates(x, theta),
//!     inputs(force),
//!     point(cart, mass = m_c, at = [x, 0]),
//!     point(bob, mass = m_p, at = [x + l * sin(theta), l * cos(theta)]),
//!     gravity = [0, -g],
//!     generalized_force(x = force),
//!     emit(jacobians),
//! )]
//! pub struct CartPole { pub m_c: f64, pub m_p: f64, pub l: f64, pub g: f64 }
//!
//! let cp = CartPole { m_c: 1.0, m_p: 0.1, l: 0.5, g: 9.81 };
//! let upright = OperatingPoint::new(Vector2::zeros(), Vector2::zeros()).input(Vector1::zeros());
//! let lin = linearize(&cp, &upright)?;
//! assert_eq!(lin.stability(1e-9)?.verdict, Verdict::Unstable);
//! let weights = DMatrix::from_diagonal(&DVector::from_vec(vec![10.0, 100.0, 1.0, 1.0]));
//! let k = lin.lqr(&weights, &DMatrix::from_element(1, 1, 0.1))?.gain;
//! let run = Simulation::new(&cp)
//!     .integrator(Dopri5::tol(1e-10))
//!     .sampled(0.01, |_, q, v| [-(&k * DVector::from_vec(vec![q[0], q[1], v[0], v[1]]))[0]])
//!     .run([0.0, 0.3], [0.0, 0.0], 0.0..10.0)?;
//! let (q, _) = run.trajectory().final_state();
//! assert!(q.abs().max() < 1e-4);
//! # Ok::<(), lagrange::Error>(())
//! ```
//!
//! Expressions use numbers (decimals are exact rationals), the names above, time
//! `t`, `pi`, velocities `dot(q)`, `+ - * /`, powers `pow(x, n)` or `x^n` (Rust
//! parses `a + b^2` as `(a + b)^2`, so an operand of `^` that is itself an
//! operation must be parenthesised — the macro rejects the ambiguous form), and the
//! functions `sin cos tan asin acos atan atan2 sinh cosh tanh exp ln sqrt abs`
//! (also in method form: `x.sin()`, `x.powi(2)`). Positions, gravity and the
//! potential cannot depend on velocities. A function of constants outside its
//! domain (`sqrt(-2)`, `ln(0)`, `asin(2)`) is a compile error, not a NaN in the
//! equations.
//!
//! Piecewise forms: `sign(x)` (−1, 0 at 0, 1), `min(a, b)`, `max(a, b)` (both give
//! `a` at a tie), `clamp(x, lo, hi)` = min(max(x, lo), hi) (literal bounds
//! must have lo < hi, else a compile error: the result would be a constant;
//! bounds computed from parameters are not checked, and with lo > hi the
//! result is hi whatever x, where `f64::clamp` would panic), and Rust's own
//! conditional, `if a > b { x } else { y }` with `>`, `<`, `>=`, `<=` joined by
//! `&&`, `||`, `!`, and `else if` chains (`==` is refused: floats are not
//! compared exactly). They are
//! differentiated branch by branch (d sign = 0, d|x| = sign x, 0 at 0), so Coulomb
//! friction `-mu * m * g * sign(dot(x))`, a saturated actuator
//! `clamp(-k * x, -f, f)` or a one-sided contact spring `k * (min(x, 0)^2) / 2`
//! need no `tanh` smoothing.
//!
//! **Switches and events.** An adaptive integrator that steps across a
//! discontinuous force sees both sides in one step: it shrinks the step around
//! the switch (costly), and a force that flips with the motion, like friction at
//! rest, chatters. Where that matters, put an [`Event`] on the switching surface
//! so each smooth piece is integrated on its own: `.restart()` cuts the step at
//! the crossing and restarts just past the surface with the state unchanged (a
//! switch the motion passes through), `.terminal()` ends the run there
//! (`Event::new(|_, _, v| v[0]).falling().terminal()` for a block coming to
//! rest), and an action changes the mode; `tests/piecewise.rs` locates the stop of a block under Coulomb friction
//! this way within 1e-9 of v0/(μg). A force that is continuous with a kink (the
//! contact spring, a saturation) needs no event: the error control handles it.
//!
//! ## Free rotations
//!
//! A rotation written with coordinates — `euler_zxz(phi, theta, psi)`, three
//! `rot_*` — has a chart, and its singular set (θ = 0 for z-x-z) stops a run.
//! `orientation(name)` declares a rotation with none:
//!
//! - **q** holds a unit quaternion **(w, x, y, z), scalar first**, that turns
//!   body axes into the world's (p_world = R(q) p_body), after the
//!   coordinates: [`Lagrangian::COORDINATES`] names its components
//!   `name.w`, `name.x`, `name.y`, `name.z`. (Pinocchio stores (x, y, z, w);
//!   MuJoCo and Drake (w, x, y, z), as here.)
//! - **v** holds the angular velocity **in body axes**, `name.wx`,
//!   `name.wy`, `name.wz` ([`Lagrangian::VELOCITIES`]). So q has one number
//!   more than v per orientation: the system is `Lagrangian<T, N, Q>` with
//!   Q = N + 1 per orientation, and [`Lagrangian::ORIENTATIONS`] says where.
//! - **The equations have no chart.** The derive works in the chart that
//!   moves with the body, R₀·exp(θ) with R₀ the quaternion's rotation, and
//!   takes them at its centre θ = 0, where θ̇ is ω: M, h and Q are Euler's
//!   equations for a lone body (`EQUATIONS` shows M = diag(A, A, C) and
//!   h = ω × Iω for the top below), read from the quaternion.
//! - **Integration on the group.** Every integrator steps q̇ = ½ q ⊗ (0, ω) in
//!   R⁴ and scales the quaternion back to unit norm after each step: the
//!   exact flow keeps |q| = 1, so the normalisation moves the state by the
//!   step's own local error and keeps the method's order. The unit-norm error
//!   is recorded with the residuals ([`Trajectory::max_unit_error`]); dense
//!   output, events and recordings read normalised quaternions. A quaternion
//!   in an initial state within 1e-6 of unit norm is normalised, further off
//!   is [`Error::NonUnitQuaternion`] naming the orientation. [`Gauss`]
//!   (with `emit(hamiltonian)`) is the symplectic method on the group: it
//!   takes each quaternion u as four coordinates with a four-number momentum
//!   P, π = ½ Im(ū ⊗ P) the body angular momentum, where |u|² is a quadratic
//!   first integral that the method keeps exactly, so it needs no
//!   normalisation; it also keeps the angular momenta of symmetries (a free
//!   body's world angular momentum, a top's vertical and axial momenta) to
//!   round-off, and its energy error stays bounded. [`StormerVerlet`]
//!   drifts by the exponential map and takes its first kick implicitly
//!   (order 2; on a free body's Euler equations the implicit midpoint rule,
//!   which keeps its kinetic energy).
//! - **Linearisation in the tangent space**: [`linearize`] takes δθ ∈ R³ per
//!   orientation (`name.θx`, then `name.wx`), so a steady spin linearises to
//!   a constant A. With constraints, [`Linearizer::constrained_tangent`] (about
//!   [`OperatingPoint::on_group`](linear::OperatingPoint::on_group)) chooses
//!   independent tangent directions and speeds as
//!   [`Linearizer::constrained`] chooses coordinates and speeds, and reads an
//!   orientation's δθ and δω in its body axes at the operating point held
//!   fixed in space, so that a body spinning steadily about an axis of
//!   symmetry (a disk rolling upright, a sphere rolling straight) is an
//!   equilibrium of a constant A: the quaternion disk's A is the Euler-angle
//!   disk's in these states to 1e-11, and its critical spin is √(g/3a)
//!   (`tests/constrained_tangent.rs`). Its derivatives are central
//!   differences on the group (relative error about 1e-10), not symbolic.
//!
//! Events on such a system are [`Event::new`] (`g` reads q with its quaternions);
//! an action's result is normalised.
//!
//! **Floating bases on the recursive route.** An orientation is a spherical
//! joint to the tree route (its motion subspace is the identity on ω, the
//! velocity product reads only the velocity entering the joint), and a free
//! body's `at = [x, y, z]` is three sliding joints, so a floating-base tree
//! (a quadruped, a satellite with an arm) gets composite-rigid-body M,
//! recursive Newton–Euler h and, with `emit(articulated, inverse_dynamics,
//! jacobians)`, the O(n) articulated-body q̈, τ and the derivatives of τ
//! in the tangent space (what [`Linearizer::tangent`] reads when they are
//! emitted); `tests/floating_bases.rs` checks them against Pinocchio's free
//! flyer to 1e-12. A body that an orientation turns
//! alone must have a positive-definite inertia (a compile error at the
//! inertia otherwise). A robot from its URDF goes on a free root with
//! `urdf("robots/solo12.urdf", base = floating)` (or a file's floating joint
//! from a bare world link): coordinates `<base>_x`, `_y`, `_z` first, then the
//! joints, and the orientation `<base>_turn`, as Pinocchio's
//! `JointModelFreeFlyer` root (with its own conventions, stated above).
//!
//! **Constraints** (`holonomic`, `nonholonomic`) run in the multiplier form
//! ([`Constrained`]`<T, N, K, Q>`): G is K × N, an orientation's columns the
//! coefficients of ω (∂/∂θ at θ = 0, the velocity rows G v + g = 0 read in
//! the body-axis ω), and γ is taken at θ = 0 too, where θ̈ = ω̇; the position
//! projection steps q ⊕ δ (the quaternion turned by exp of a rotation vector),
//! and `emit(reactions)` gives the Cartesian reactions. A sphere rolling with
//! a quaternion (`examples/catalog/rolling.rs`) rolls through the state
//! where euler_zxz stops, its z axis vertical.
//!
//! **Inputs** work as without orientations ([`Driven`]`<T, N, P, Q>`): the
//! forces they add are in v's tangent space (an orientation's three entries
//! torques in body axes; a torque is written as forces at body points, see
//! `Satellite` in `examples/catalog/free.rs`), a controller reads q with its
//! quaternions, and [`Linearizer::tangent_driven`] linearises with
//! B = [0; M⁻¹ ∂Q/∂u] (2·N × P).
//!
//! `emit(kinematics)` gives the frames' Jacobians with v's columns (an
//! orientation's three: body-axis ω) and J̇ q̇ at v̇ = 0.
//!
//! [`StateFeedback`] applies a gain designed on the tangent linearisation
//! (e.g. LQR) to q ⊖ q₀ ([`orientation::minus`], in body axes): a
//! satellite's attitude held by LQR follows the linear closed loop to second
//! order in the error (`tests/torqued_body.rs`).
//!
//! `emit(coriolis)` gives C with h = C v and Ṁ − 2C skew-symmetric, Ṁ the
//! rate of M along the motion: the Christoffel factorisation in the chart
//! that moves with each body, plus ½ M W (W the \[ω\]× blocks) for the chart's
//! own turning.
//!
//! The reduced form (`speeds(...)`, `formulation(reduced)`) takes
//! orientations too: a speed may be a body's `omega_1/2/3` (body axes),
//! `omega_x/y/z` or `dot(x)` of a coordinate; the rows A = [U; G], b and
//! their rates c = −(Ȧ q̇ + ḃ) are derived in the moving chart and taken at
//! its centre, so that A v + b = (u, 0) in v, and the system is
//! [`Reduced<T, N, K, Q>`](Reduced) ([`ReducedDynamics`] steps the quaternion
//! on the group; [`Linearizer::reduced_tangent`] linearises it in the tangent
//! space, as [`Linearizer::constrained_tangent`] does the multiplier form,
//! while [`Linearizer::reduced`] stays with Q = N). The rolling
//! sphere and disk with a quaternion on their angular velocities match the
//! multiplier form and the Euler-angle versions (`tests/reduced_orientation.rs`).
//!
//! Hamilton's form (`emit(hamiltonian)`) takes orientations: p = M v (an
//! orientation's entries the body angular momentum π), and ∂T/∂θ along
//! body-axis turns at fixed ω (π̇ = π × ω + ∂T/∂θ + Q). [`Gauss`] on it keeps
//! a tumbling body's world angular momentum to 1.4e-14 and its unit norm to
//! 4e-15 over 50 flips, its energy error bounded (4e-9).
//!
//! ```
//! use lagrange::prelude::*;
//!
//! /// A heavy top on a fixed pivot, spun exactly upright: θ = 0, where
//! /// euler_zxz stops, is an ordinary state here.
//! #[derive(Lagrangian)]
//! #[lagrange(
//!     orientation(spin),
//!     body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
//!          at = [0, 0, 0], rotation = spin),
//!     gravity = [0, 0, -g],
//! )]
//! pub struct Top { pub m: f64, pub a: f64, pub c: f64, pub l: f64, pub g: f64 }
//!
//! let top = Top { m: 1.5, a: 0.8, c: 0.5, l: 0.4, g: 9.81 };
//! // q = (w, x, y, z), v = ω in body axes: upright, spinning at 30 rad/s.
//! let traj = Simulation::new(&top)
//!     .integrator(Dop853::tol(1e-10))
//!     .run([1.0, 0.0, 0.0, 0.0], [0.01, 0.0, 30.0], 0.0..5.0)?;
//! assert!(traj.max_unit_error() < 1e-15 && traj.integral_drift() < 1e-8);
//! // Above C²n² = 4 A m g l the sleeping top is stable: the tangent-space
//! // linearisation's eigenvalues have no positive real part.
//! let lin = Linearizer::new().tangent(&top, &Vector4::new(1.0, 0.0, 0.0, 0.0), &Vector3::new(0.0, 0.0, 30.0), 0.0)?;
//! assert!(lin.eigenvalues()[0].re < 1e-9);
//!
//! /// A gimbal's payload in yaw–pitch–roll, turned by a torque about its
//! /// body y axis.
//! #[derive(Lagrangian)]
//! #[lagrange(
//!     coordinates(yaw, pitch, roll),
//!     inputs(tau),
//!     body(load, mass = m, inertia = [a, b, c], at = [0, 0, 0],
//!          rotation = euler_zyx(yaw, pitch, roll)),
//!     point(arm, on = load, at = [0, 0, 1]),
//!     force(arm, [tau * load.axis_x.x, tau * load.axis_x.y, tau * load.axis_x.z]),
//!     emit(atlas),
//! )]
//! pub struct Payload { pub m: f64, pub a: f64, pub b: f64, pub c: f64 }
//!
//! // A pitch-rate loop drives the pitch through π/2 and on; an event
//! // marks where the pitch, read on the user's angles, passes 2 rad.
//! let load = Payload { m: 2.0, a: 0.1, b: 0.2, c: 0.25 };
//! let run = Simulation::new(&load)
//!     .feedback(|_, _, v| [0.5 * (2.0 - v[1])])
//!     .event(Event::new(|_, q, _| q[1] - 2.0))
//!     .run_atlas([0.0, 1.0, 0.0], [0.0, 2.0, 0.0], 0.0..2.5)?;
//! assert_eq!(run.switches().len(), 3);
//! assert!((run.times(0)[0] - 0.5).abs() < 1e-9);
//! assert_eq!(run.inputs().len(), run.charted().len());
//! # Ok::<(), lagrange::Error>(())
//! ```
//!
//! ## Charts that switch: the atlas
//!
//! A user who writes a rotation in Euler angles keeps them with
//! `emit(atlas)`: the run no longer stops at the chart's singular set.
//! Each rotation written as three Euler angles of coordinates about one
//! point (`euler_zxz(ψ, θ, φ)`, `euler_zyx(..)`, or three successive `rot_*`
//! whose middle axis differs from both ends) gets a second chart, the same
//! sequence after the constant turn R_b(π/2) about its middle axis. A
//! chart of the sequence (a, b, c) is singular where the body's c axis lies
//! along e_a (θ = 0 for z-x-z, pitch ±π/2 for z-y-x); the turn moves e_a to
//! a perpendicular axis, so the two singular sets are disjoint, and where
//! one chart's conditioning s (|sin θ| for z-x-z, |cos θ| for z-y-x) is
//! poor the other's is good: s₁² + s₂² ≥ 1 (`lagrange::numeric::euler`; the
//! derive checks it for each rotation).
//!
//! [`Simulation::run_atlas`] starts in the user's chart, moves a rotation to
//! its second chart when s₁ falls below 0.6 and back when it rises above
//! 0.8 (the gap is the hysteresis; the chart in use always has s ≥ 0.6), each switch an event located on the
//! dense output, after which the integrator restarts. A switch keeps the
//! rotation matrix and the body angular velocity ω = E q̇: the speeds do not
//! change, only the chart reading them, so it is exact. In the user's chart
//! the equations are the user's own; in the second they come from the
//! description's free twin (each rotation a quaternion and ω, derived as
//! for `orientation`), whose M and h have no chart: q̈ = E⁻¹(ω̇ − Ė q̇).
//! The [`AtlasRun`] gives each point with its charts ([`AtlasRun::charted`],
//! never a bare `Trajectory` a scene would misread), the orientation
//! chart-free ([`AtlasRun::rotation`], [`AtlasRun::quaternion`]), the user's
//! coordinates where valid ([`AtlasRun::user_state`]), and draws and writes
//! every rotation in the user's chart ([`AtlasRun::scene`], [`AtlasRun::table`]). [`Linearizer::atlas`]
//! linearises in charts regular at the operating point, and
//! [`Linearizer::atlas_driven`] adds B for the inputs held there (in a
//! second chart through the twin's forces). [`Simulation::run`]
//! on the same system stays in the user's chart and stops at its singular
//! set with [`Error::SingularMassMatrix`]: that is the opt-out.
//!
//! **Inputs and events.** A description with `inputs(..)` keeps them with
//! the atlas: the twin derives the same inputs (their generalized forces
//! in its coordinates, `DrivenAtlas`), and every control of
//! [`Simulation::run`] runs through the atlas with
//! [`Simulation::run_atlas`] (`feedback`, `sampled`, `open_loop`,
//! an [`InputTable`]), and so do events, with or without inputs. Controllers, event functions, terminal tests and
//! actions all read the user's coordinates: in the second chart, each
//! rotation's user's angles nearest those it had when it left the user's
//! chart (so they run on continuously, pitch past π/2 rather than back
//! from it) and their rates E⁻¹ ω, which grow as 1/s near the user's
//! singular set and read NaN on it (a controller or event that passes them
//! on ends the run with a typed error). An action's state goes back into
//! the charts. [`AtlasRun::inputs`] and [`AtlasRun::occurrences`] hold the
//! inputs and the user's events, in the user's coordinates.
//!
//! **Constraints.** Holonomic and nonholonomic constraints
//! (`holonomic(..)`, `nonholonomic(..)`) run with the atlas in the
//! multiplier form: the twin carries the same rows written on its free
//! orientation (a nonholonomic row on the bodies' velocities and ω, such
//! as a ball's `dot(ball.x) - a * ball.omega_y`), so a body pinned by a
//! point of it, a chain closed by a rod or a ball rolling without slipping
//! passes its Euler angles' singular set like a free one. A description
//! emitted in both constrained forms (`formulation(multipliers, reduced)`)
//! runs its multiplier form through the atlas; one emitted only in the
//! reduced form (`speeds(..)`, `formulation(reduced)`) is refused. The
//! start is checked for consistency in the user's coordinates, as
//! [`Simulation::run`] checks it; drift control (`drift`) and
//! `least_squares` are refused (the residuals drift at the integrator's
//! tolerance, recorded in the trajectory). [`Linearizer::atlas`] gives a
//! constrained system's model on independent states of the charts (the
//! pinned top at the upright: the pivoted top's A, to 5e-10, the
//! accuracy of the central differences both are read by).
//!
//! The atlas covers descriptions without free orientations, a URDF or the
//! reduced form alone; an angle of such a rotation may appear only as that
//! rotation's angle (a potential written in θ itself has no meaning in the
//! second chart: write it from positions, e.g. `gravity`; an input's force
//! from points of the body, not as a generalized force on an angle; a
//! constraint, holonomic or nonholonomic, on points and velocities of the
//! body, not on θ or θ̇). Each is a compile error at its token.
//!
//! ```
//! use lagrange::prelude::*;
//!
//! /// The heavy top in the user's Euler angles z-x-z, with an atlas.
//! #[derive(Lagrangian)]
//! #[lagrange(
//!     coordinates(psi, theta, phi),
//!     body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
//!          at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
//!     gravity = [0, 0, -g],
//!     emit(atlas),
//! )]
//! pub struct Top { pub m: f64, pub a: f64, pub c: f64, pub l: f64, pub g: f64 }
//!
//! let top = Top { m: 1.5, a: 0.8, c: 0.5, l: 0.4, g: 9.81 };
//! // Swung over the top through θ = 0: the user's chart alone stops there.
//! let sim = Simulation::new(&top).integrator(Dop853::tol(1e-10));
//! let run = sim.run_atlas([0.2, 0.6, -0.4], [0.0, -6.0, 2.0], 0.0..4.0)?;
//! assert!(run.switches().len() >= 4 && run.charted().integral_drift() < 1e-8);
//! let upright = run.quaternion(0, 0); // (w, x, y, z) of the first point
//! assert!((upright[0] - 0.9505).abs() < 1e-4);
//! // Spun exactly upright, the sleeping top linearises in the second chart.
//! let lin = Linearizer::new().atlas(&top, &Vector3::zeros(), &Vector3::new(0.0, 0.0, 30.0), 0.0)?;
//! assert_eq!(lin.states()[1], "theta@2");
//! assert!(lin.eigenvalues()[0].re < 1e-9);
//!
//! /// A gimbal's payload in yaw–pitch–roll, turned by a torque about its
//! /// body y axis.
//! #[derive(Lagrangian)]
//! #[lagrange(
//!     coordinates(yaw, pitch, roll),
//!     inputs(tau),
//!     body(load, mass = m, inertia = [a, b, c], at = [0, 0, 0],
//!          rotation = euler_zyx(yaw, pitch, roll)),
//!     point(arm, on = load, at = [0, 0, 1]),
//!     force(arm, [tau * load.axis_x.x, tau * load.axis_x.y, tau * load.axis_x.z]),
//!     emit(atlas),
//! )]
//! pub struct Payload { pub m: f64, pub a: f64, pub b: f64, pub c: f64 }
//!
//! // A pitch-rate loop drives the pitch through π/2 and on; an event
//! // marks where the pitch, read on the user's angles, passes 2 rad.
//! let load = Payload { m: 2.0, a: 0.1, b: 0.2, c: 0.25 };
//! let run = Simulation::new(&load)
//!     .feedback(|_, _, v| [0.5 * (2.0 - v[1])])
//!     .event(Event::new(|_, q, _| q[1] - 2.0))
//!     .run_atlas([0.0, 1.0, 0.0], [0.0, 2.0, 0.0], 0.0..2.5)?;
//! assert_eq!(run.switches().len(), 3);
//! assert!((run.times(0)[0] - 0.5).abs() < 1e-9);
//! assert_eq!(run.inputs().len(), run.charted().len());
//! # Ok::<(), lagrange::Error>(())
//! ```
//!
//! **Ensembles.** With the feature `parallel`, `lagrange::ensemble::Ensemble`
//! (also in [`prelude`] as `Ensemble`) runs many independent simulations —
//! initial conditions, parameter sets, a Monte Carlo sweep — on all cores with
//! a progress bar, the results in input order whatever the number of threads:
//! `Ensemble::new().run(&inputs, |i, x| ...)`. Sweeps larger than one machine
//! split into shards with `lagrange::ensemble::shard`.

#![warn(missing_docs)]

pub use lagrange_macros::Lagrangian;
pub use lagrange_runtime::*;
pub use nalgebra;
pub mod guide;

/// Everything a typical program needs: the derive, the traits, the simulation
/// builder, the integrators and nalgebra's fixed-size vectors (`Ensemble` too
/// with the feature `parallel`).
pub mod prelude {
    pub use lagrange_macros::Lagrangian;
    /// Many independent runs on all cores (feature `parallel`).
    #[cfg(feature = "parallel")]
    pub use lagrange_runtime::ensemble::Ensemble;
    pub use lagrange_runtime::linear::{Linear, Linearizer, OperatingPoint, Verdict};
    pub use lagrange_runtime::study::{Method, Sweep};
    pub use lagrange_runtime::{
        Atlas, AtlasRun, Constrained, ConstrainedDynamics, ControlRun, Direction, Dop853, Dopri5,
        Drift, Driven, Error, Event, EventRun, Failure, Gauss, InputTable, Integrator,
        Interpolation, Lagrangian, LimitPolicy, Occurrence, Radau5, Rattle, Real, Record, Reduced,
        ReducedDynamics, ReducedForm, Rk4, Scene, SettingsError, Simulation, StateFeedback,
        StormerVerlet, Study, Trajectory, WorkPrecision,
    };
    pub use nalgebra::{SMatrix, SVector, Vector1, Vector2, Vector3, Vector4, Vector5, Vector6};
}

/// The README's code examples, run as doctests (`cargo test --doc -p lagrange`).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// Paths the generated code uses; not a public API.
#[doc(hidden)]
#[path = "generated_paths.rs"]
pub mod __private;

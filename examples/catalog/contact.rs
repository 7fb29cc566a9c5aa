//! Systems with unilateral contacts (`contact(...)`, `stop(...)`), run by
//! `Simulation::run_contacts`: a solid ball on a floor (bouncing to rest, or
//! thrown with backspin), a block sliding to a stop, a pendulum against a
//! stop. Each has a closed form for its events (`tests/contact.rs`, the
//! gallery's contact rows).

use lagrange::Lagrangian;

/// A solid ball of radius r in the vertical plane (x, z), turning about y,
/// on the floor z = 0 with restitution 0.5 and friction 0.3. Rolling without
/// slip is ẋ = r θ̇; θ̇ < 0 while ẋ > 0 is backspin. The floor is drawn as
/// a line between two points without mass.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, z, theta),
    body(ball, mass = m, inertia = [0.4 * m * r * r, 0.4 * m * r * r, 0.4 * m * r * r],
         at = [x, 0, z], rotation = rot_y(theta)),
    gravity = [0, 0, -g],
    contact(floor, on = ball, radius = r, normal = [0, 0, 1], restitution = 0.5, friction = 0.3),
    point(floor_start, mass = 0, at = [-0.5, 0, 0]),
    point(floor_end, mass = 0, at = [2.5, 0, 0]),
    shape(ball, sphere(radius = r)),
    // A slab through the centre, so that the scene shows the ball turn.
    shape(ball, box(size = [1.9 * r, 0.3 * r, 0.2 * r])),
    shape(line(floor_start, floor_end)),
)]
pub struct Ball {
    pub m: f64,
    pub r: f64,
    pub g: f64,
}

/// The ball's friction coefficient and restitution, as its description
/// writes them (for the closed forms).
pub const BALL_FRICTION: f64 = 0.3;
/// See [`BALL_FRICTION`].
pub const BALL_RESTITUTION: f64 = 0.5;

/// A block on the floor z = 0 with friction 0.4 and no bounce: a point mass
/// at the bottom face's centre, where the contact is, drawn as a cube of
/// side a above it (it does not turn: the friction acts at that point).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    point(block, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    contact(floor, on = block, normal = [0, 0, 1], restitution = 0, friction = 0.4),
    point(floor_start, mass = 0, at = [-0.5, -0.5, 0]),
    point(floor_end, mass = 0, at = [2.5, 3.5, 0]),
    shape(block, box(size = [a, a, a]), at = [0, 0, a / 2]),
    shape(line(floor_start, floor_end)),
)]
pub struct SlidingBlock {
    pub m: f64,
    pub a: f64,
    pub g: f64,
}

/// The block's friction coefficient.
pub const BLOCK_FRICTION: f64 = 0.4;

/// A pendulum against a wall along its downward vertical, θ ≥ 0, with
/// restitution 0.6.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    stop(wall, theta >= 0, restitution = 0.6),
    point(pivot, mass = 0, at = [0, 0]),
    point(wall_top, mass = 0, at = [0, -0.5 * l]),
    point(wall_bottom, mass = 0, at = [0, -1.2 * l]),
    shape(bob, sphere(radius = 0.06)),
    shape(line(pivot, bob)),
    shape(line(wall_top, wall_bottom)),
)]
pub struct StoppedPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// The stop's restitution.
pub const STOP_RESTITUTION: f64 = 0.6;

/// A box of width a and height b in the vertical plane (x, z), turning
/// about y, tossed onto the floor z = 0: its four corners are points
/// without mass, each a contact with restitution 0.2 and friction 0.5. Its
/// landings hit two corners at once and rock between corners, with contacts
/// closing and opening every few milliseconds, which is what the
/// time-stepping scheme (`MoreauJean`) is for.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, z, theta),
    body(block, mass = m, inertia = [m * b * b / 12, m * (a * a + b * b) / 12, m * a * a / 12],
         at = [x, 0, z], rotation = rot_y(theta)),
    gravity = [0, 0, -g],
    point(c1, mass = 0, at = [x + a / 2 * cos(theta) + b / 2 * sin(theta), 0,
                             z - a / 2 * sin(theta) + b / 2 * cos(theta)]),
    point(c2, mass = 0, at = [x - a / 2 * cos(theta) + b / 2 * sin(theta), 0,
                             z + a / 2 * sin(theta) + b / 2 * cos(theta)]),
    point(c3, mass = 0, at = [x - a / 2 * cos(theta) - b / 2 * sin(theta), 0,
                             z + a / 2 * sin(theta) - b / 2 * cos(theta)]),
    point(c4, mass = 0, at = [x + a / 2 * cos(theta) - b / 2 * sin(theta), 0,
                             z - a / 2 * sin(theta) - b / 2 * cos(theta)]),
    contact(corner1, on = c1, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(corner2, on = c2, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(corner3, on = c3, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    contact(corner4, on = c4, normal = [0, 0, 1], restitution = 0.2, friction = 0.5),
    point(floor_start, mass = 0, at = [-1, 0, 0]),
    point(floor_end, mass = 0, at = [3, 0, 0]),
    shape(block, box(size = [a, 0.4 * a, b])),
    shape(line(floor_start, floor_end)),
)]
pub struct TossedBox {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub g: f64,
}

/// The box's friction coefficient and restitution.
pub const BOX_FRICTION: f64 = 0.5;
/// See [`BOX_FRICTION`].
pub const BOX_RESTITUTION: f64 = 0.2;

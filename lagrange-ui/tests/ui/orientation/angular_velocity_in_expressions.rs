use lagrange::Lagrangian;

// An orientation's angular velocity has the name the runtime gives it
// (`turn.wz`, `VELOCITIES`), but an expression reads it from a body the
// orientation turns: both spellings below say so.
#[derive(Lagrangian)]
#[lagrange(
    orientation(turn),
    body(b, mass = m, inertia = [1, 2, 3], at = [0, 0, 0], rotation = turn),
    torque(b, [0, 0, -c * turn.wz], axes = body),
    torque(b, [0, -c * dot(turn), 0], axes = body),
)]
struct Damped {
    m: f64,
    c: f64,
}

fn main() {}

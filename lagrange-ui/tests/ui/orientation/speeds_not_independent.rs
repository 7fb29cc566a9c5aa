use lagrange::Lagrangian;

// The reduced form takes a free orientation; speeds that leave an angular
// velocity undetermined are refused at derive time, the velocity named as
// `VELOCITIES` names it (`turn.wx` …, body axes).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, z),
    orientation(turn),
    body(b, mass = m, inertia = [1, 1, 1], at = [x, y, z], rotation = turn),
    holonomic(height = z - 1),
    nonholonomic(slip_x = dot(x) - b.omega_y, slip_y = dot(y) + b.omega_x),
    speeds(u = dot(x), v = dot(y), w = dot(z)),
)]
struct Rolled {
    m: f64,
}

fn main() {}

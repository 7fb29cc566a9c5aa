use lagrange::Lagrangian;

// A spherical pendulum in two angles: no rotation here is three Euler angles
// about one point, so there is no second chart to switch to (model it with a
// free orientation, or with Cartesian coordinates and a constraint).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(phi, theta),
    body(bob, mass = 1.0, inertia = [0.1, 0.1, 0.1], com = [0, 0, -1],
         at = [0, 0, 0], rotation = rot_z(phi) * rot_x(theta)),
    gravity = [0, 0, -9.81],
    emit(atlas),
)]
struct SphericalPendulum {}

fn main() {}

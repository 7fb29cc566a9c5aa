use lagrange::Lagrangian;

// A joint's friction is a contact named `<q>_friction`; a contact item that
// already has the name is reported at the joint.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x),
    point(cart, mass = m, at = [x, 0]),
    stop(x_friction, x >= 0, restitution = 0),
    joint(x, friction = 0.5),
)]
struct Cart {
    m: f64,
}

fn main() {}

use lagrange::Lagrangian;

// A joint's dry friction runs as a contact, and contacts do not run on a
// description with a free orientation yet: refused at the joint's
// coordinate, naming the contact it would make.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(yaw),
    orientation(attitude),
    body(sat, mass = 1, inertia = [1, 2, 3], at = [0, 0, 0], rotation = attitude),
    body(wheel, mass = 1, inertia = [1, 1, 1], at = [0, 0, 1],
         rotation = attitude * rot_z(yaw)),
    joint(yaw, friction = 0.2),
)]
struct Satellite;

fn main() {}

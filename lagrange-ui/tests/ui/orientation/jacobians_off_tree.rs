use lagrange::Lagrangian;

// A free body on a circular track is not a kinematic tree (its reference
// point moves along a circle, not a fixed line), so the tangent-space
// Jacobians, which come from the tree's recursion, cannot be emitted.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(s),
    orientation(turn),
    body(car, mass = 1.0, inertia = [1, 2, 2.5], at = [cos(s), sin(s), 0], rotation = turn),
    emit(jacobians),
)]
struct Car {}

fn main() {}

use lagrange::Lagrangian;
use lagrange::linear::{OperatingPoint, linearize};
use lagrange::nalgebra::SVector;

// A body with a quaternion is linearised on its group (`tangent_driven`),
// not by `linearize`, which takes a system in N coordinates: the message
// says so instead of miscounting its inputs.
#[derive(Lagrangian)]
#[lagrange(
    orientation(turn),
    inputs(push),
    body(top, mass = 1.0, inertia = [1.0, 1.0, 0.5], at = [0, 0, 0], rotation = turn),
    point(tip, on = top, at = [0, 0, 1]),
    force(tip, [push, 0, 0]),
)]
struct Top {}

fn main() {
    let q = SVector::<f64, 4>::new(1.0, 0.0, 0.0, 0.0);
    let v = SVector::<f64, 3>::zeros();
    let _ = linearize(&Top {}, &OperatingPoint::on_group(q, v));
}

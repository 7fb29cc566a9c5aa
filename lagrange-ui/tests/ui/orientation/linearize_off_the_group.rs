use lagrange::Lagrangian;
use lagrange::linear::{OperatingPoint, linearize};
use lagrange::nalgebra::SVector;

// A body with a quaternion is linearised at a point on its group
// (`OperatingPoint::on_group`, four numbers per quaternion in q); a point
// made with `OperatingPoint::new` holds N numbers in q, and the error says
// that the point's q must hold the system's Q = 4 (not a miscount of its
// inputs).
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
    let q = SVector::<f64, 3>::zeros();
    let v = SVector::<f64, 3>::zeros();
    let _ = linearize(&Top {}, &OperatingPoint::new(q, v));
}

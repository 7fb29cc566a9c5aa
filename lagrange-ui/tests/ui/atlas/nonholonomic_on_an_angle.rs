use lagrange::Lagrangian;

// A nonholonomic constraint written on Euler angles and their rates: in the
// second chart there are no such coordinates. The error points at the first
// angle the row names; write the row on the body's velocities and ω
// (`dot(disk.x)`, `disk.omega_y`) instead.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y, psi, theta, phi),
    body(disk, mass = 1.0, inertia = [0.25, 0.25, 0.5], at = [x, y, 0],
         rotation = euler_zxz(psi, theta, phi)),
    nonholonomic(roll = dot(x) - cos(psi) * dot(phi)),
    emit(atlas),
)]
struct Disk {}

fn main() {}

use lagrange::Lagrangian;

// A satellite on a quaternion carrying a camera on Euler angles: the atlas
// runs coordinates alone, so the camera's rotation gets an orientation too.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(yaw, pitch, roll),
    orientation(attitude),
    body(sat, mass = 1, inertia = [1, 2, 3], at = [0, 0, 0], rotation = attitude),
    body(camera, mass = 1, inertia = [1, 1, 1], at = [0, 0, 1],
         rotation = attitude * euler_zyx(yaw, pitch, roll)),
    emit(atlas),
)]
struct Satellite;

fn main() {}

//! A rigid body's ten inertial parameters from its mass, centre and
//! inertia, and back: what one writes to add a tool or a payload to a known
//! π, and reads off an estimate.

use nalgebra::{DVector, Matrix3, Vector3};

use crate::error::IdentifyError;

/// A body's ten parameters in π's order (Pinocchio's
/// `Inertia::toDynamicParameters`): m, m c, and the inertia about the
/// frame's origin, Ixx, Ixy, Iyy, Ixz, Iyz, Izz, from its mass, its centre
/// `centre` in the frame and its inertia `about_centre` about that centre,
/// both in the frame's axes (the parallel-axis theorem moves it). A point
/// mass has a zero `about_centre`.
///
/// # Errors
/// [`IdentifyError::NotABody`] for what no rigid body has: a mass that is
/// negative or not finite, a centre or an inertia entry that is not
/// finite, an inertia that is not symmetric, or one whose principal moments
/// are negative or break the triangle inequalities (each at most the sum
/// of the other two).
pub fn body_parameters(
    mass: f64,
    centre: Vector3<f64>,
    about_centre: Matrix3<f64>,
) -> Result<[f64; 10], IdentifyError> {
    check_body(mass, &centre, &about_centre)?;
    let c = centre;
    let i = about_centre + (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * mass;
    Ok([
        mass,
        mass * c.x,
        mass * c.y,
        mass * c.z,
        i[(0, 0)],
        i[(0, 1)],
        i[(1, 1)],
        i[(0, 2)],
        i[(1, 2)],
        i[(2, 2)],
    ])
}

/// The rules a rigid body's mass, centre and inertia about its centre keep.
fn check_body(
    mass: f64,
    centre: &Vector3<f64>,
    inertia: &Matrix3<f64>,
) -> Result<(), IdentifyError> {
    let refuse = |what, value, rule| Err(IdentifyError::NotABody { what, value, rule });
    if !(mass.is_finite() && mass >= 0.0) {
        return refuse("the mass", mass, "a mass is finite and not negative");
    }
    if let Some(&x) = centre.iter().find(|x| !x.is_finite()) {
        return refuse(
            "a coordinate of the centre",
            x,
            "a centre is a finite point",
        );
    }
    if let Some(&x) = inertia.iter().find(|x| !x.is_finite()) {
        return refuse(
            "an entry of the inertia",
            x,
            "an inertia's entries are finite",
        );
    }
    // Round-off of a matrix computed as R I Rᵀ is allowed, relative to its
    // largest entry.
    let tol = 1e-12 * inertia.amax();
    let asymmetry = (inertia - inertia.transpose()).amax();
    if asymmetry > tol {
        return refuse(
            "the inertia's asymmetry (largest |I - Iᵀ| entry)",
            asymmetry,
            "an inertia matrix is symmetric",
        );
    }
    let moments = inertia.symmetric_eigenvalues();
    let sum = moments.sum();
    for &moment in moments.iter() {
        if moment < -tol {
            return refuse(
                "a principal moment",
                moment,
                "principal moments are not negative",
            );
        }
        if moment > sum - moment + tol {
            return refuse(
                "a principal moment",
                moment,
                "each principal moment is at most the sum of the other two",
            );
        }
    }
    Ok(())
}

/// The mass, centre and inertia about the centre of ten parameters in π's
/// order; `None` for a mass that is not positive (the centre is then not
/// defined).
pub fn body_from_parameters(block: &[f64; 10]) -> Option<(f64, Vector3<f64>, Matrix3<f64>)> {
    let mass = block[0];
    if mass.is_nan() || mass <= 0.0 {
        return None;
    }
    let c = Vector3::new(block[1], block[2], block[3]) / mass;
    let about_origin = Matrix3::new(
        block[4], block[5], block[7], block[5], block[6], block[8], block[7], block[8], block[9],
    );
    let shift = (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * mass;
    Some((mass, c, about_origin - shift))
}

/// `pi` with `block` added to body `body`'s ten parameters (a tool or a
/// payload fixed to it, its parameters about the body's frame), π's
/// layout as `names` ([`crate::Lagrangian::REGRESSOR_PARAMETERS`]) gives it.
///
/// # Errors
/// [`IdentifyError::UnknownParameter`] when `names` has no `<body>.m`
/// followed by the body's other nine; [`IdentifyError::Lengths`] when `pi`
/// is not as long as `names`.
pub fn add_to_body(
    pi: &mut DVector<f64>,
    names: &[&str],
    body: &str,
    block: &[f64; 10],
) -> Result<(), IdentifyError> {
    if pi.len() != names.len() {
        return Err(IdentifyError::Lengths {
            what: "π",
            got: pi.len(),
            expected: names.len(),
        });
    }
    let first = names.iter().position(|n| *n == format!("{body}.m"));
    let whole = first.filter(|&k| names.get(k + 9) == Some(&format!("{body}.Izz").as_str()));
    let Some(first) = whole else {
        return Err(IdentifyError::UnknownParameter {
            name: format!("{body}.m"),
        });
    };
    for (k, x) in block.iter().enumerate() {
        pi[first + k] += x;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_and_back_round_trip() {
        let c = Vector3::new(0.02, 0.15, -0.01);
        let i = Matrix3::new(0.01, 0.001, 0.0, 0.001, 0.02, 0.002, 0.0, 0.002, 0.015);
        let block = body_parameters(1.3, c, i).expect("a body");
        assert_eq!(block[0], 1.3);
        assert!((block[2] - 1.3 * 0.15).abs() < 1e-15);
        // Izz about the origin: Izz_c + m (cx² + cy²).
        assert!((block[9] - (0.015 + 1.3 * (0.02f64.powi(2) + 0.15f64.powi(2)))).abs() < 1e-15);
        let (m, c2, i2) = body_from_parameters(&block).expect("massive");
        assert_eq!(m, 1.3);
        assert!((c2 - c).amax() < 1e-15 && (i2 - i).amax() < 1e-15);
        assert!(body_from_parameters(&[0.0; 10]).is_none());
    }

    #[test]
    fn a_block_is_added_where_its_body_is() {
        let names = [
            "a.m", "a.mx", "a.my", "a.mz", "a.Ixx", "a.Ixy", "a.Iyy", "a.Ixz", "a.Iyz", "a.Izz",
            "p.m",
        ];
        let mut pi = DVector::from_element(11, 1.0);
        let block = body_parameters(2.0, Vector3::new(0.0, 0.0, 0.5), Matrix3::zeros())
            .expect("a point mass");
        add_to_body(&mut pi, &names, "a", &block).expect("a is a body");
        assert_eq!(pi[0], 3.0);
        assert_eq!(pi[3], 2.0);
        assert_eq!(pi[10], 1.0);
        let e = add_to_body(&mut pi, &names, "p", &block).unwrap_err();
        assert!(matches!(e, IdentifyError::UnknownParameter { .. }), "{e}");
        let e = add_to_body(&mut DVector::zeros(3), &names, "a", &block).unwrap_err();
        assert!(matches!(e, IdentifyError::Lengths { .. }), "{e}");
    }

    #[test]
    fn what_no_body_has_is_refused_and_says_which() {
        let c = Vector3::new(0.0, 0.1, 0.0);
        let i = Matrix3::from_diagonal(&Vector3::new(0.01, 0.02, 0.025));
        let refused = |mass: f64, c: Vector3<f64>, i: Matrix3<f64>| -> String {
            let e = body_parameters(mass, c, i).unwrap_err();
            assert!(matches!(e, IdentifyError::NotABody { .. }), "{e}");
            e.to_string()
        };
        assert!(refused(-1.0, c, i).contains("the mass is -1"));
        assert!(refused(f64::NAN, c, i).contains("the mass is NaN"));
        assert!(refused(1.0, Vector3::new(0.0, f64::INFINITY, 0.0), i).contains("centre"));
        let mut lopsided = i;
        lopsided[(0, 1)] = 0.003;
        assert!(refused(1.0, c, lopsided).contains("symmetric"));
        // 0.04 > 0.01 + 0.02: no mass distribution has these moments.
        let flat = Matrix3::from_diagonal(&Vector3::new(0.01, 0.02, 0.04));
        assert!(refused(1.0, c, flat).contains("sum of the other two"));
        let negative = Matrix3::from_diagonal(&Vector3::new(-0.01, 0.02, 0.025));
        assert!(refused(1.0, c, negative).contains("not negative"));
        // A rod's moments (0, I, I) and a point mass's (0, 0, 0) are bodies;
        // so is a massless block, which adds nothing.
        let rod = Matrix3::from_diagonal(&Vector3::new(0.0, 0.02, 0.02));
        assert!(body_parameters(1.0, c, rod).is_ok());
        assert_eq!(body_parameters(0.0, c, Matrix3::zeros()), Ok([0.0; 10]));
    }
}

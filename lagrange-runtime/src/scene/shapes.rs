//! What the page draws, fixed for the whole scene: the description's shapes,
//! and the defaults for what it left undrawn. A body without a solid is drawn
//! as the box with its mass and inertia (as Drake's and MuJoCo's viewers do), a
//! point as a dot, and, when the description draws no line, each point fixed
//! in a body is joined to the body's reference point.

use crate::error::SettingsError;
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

use crate::error::Error;
use crate::numeric::Real;
use crate::pose::{Anchor, BodyInertia, Posed, Shape, Solid};

/// A shape in f64, with the axes of its solid in the anchor's axes (the
/// identity but for a default box, turned to the principal axes).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Drawn {
    pub on: Anchor,
    pub at: Vector3<f64>,
    pub axes: Matrix3<f64>,
    pub solid: Solid<f64>,
    /// Whether the scene chose it (drawn a little fainter than the user's).
    pub default: bool,
}

/// The description's shapes and the defaults, in drawing order; the sizes
/// checked positive and finite.
///
/// # Errors
/// [`Error::Settings`] for a size from a parameter that is not positive.
pub(super) fn drawn<T: Real, const N: usize, const Q: usize, S: Posed<T, N, Q>>(
    sys: &S,
    centres: &[Vector3<f64>],
) -> Result<Vec<Drawn>, Error> {
    let mut user = Vec::new();
    sys.shapes(&mut |s: Shape<T>| user.push(s));
    let mut out = Vec::new();
    for s in &user {
        out.push(to_f64(s)?);
    }
    let mut inertias = vec![BodyInertia::default(); S::BODIES.len()];
    sys.inertias(&mut inertias);
    for (i, inertia) in inertias.iter().enumerate() {
        let solid = |d: &Drawn| d.on == Anchor::Body(i) && !matches!(d.solid, Solid::Line { .. });
        if !out.iter().any(solid) {
            let centre = centres.get(i).copied().unwrap_or_else(Vector3::zeros);
            out.push(equivalent_box(i, inertia, centre));
        }
    }
    let has_lines = out.iter().any(|d| matches!(d.solid, Solid::Line { .. }));
    for (j, body) in S::POINT_BODIES.iter().enumerate() {
        if let (Some(b), false) = (body, has_lines) {
            out.push(default(
                Anchor::Body(*b),
                Solid::Line {
                    to: Anchor::Point(j),
                },
            ));
        }
    }
    Ok(out)
}

fn default(on: Anchor, solid: Solid<f64>) -> Drawn {
    Drawn {
        on,
        at: Vector3::zeros(),
        axes: Matrix3::identity(),
        solid,
        default: true,
    }
}

fn to_f64<T: Real>(s: &Shape<T>) -> Result<Drawn, Error> {
    let f = |x: T| x.to_f64();
    let solid = match s.solid {
        Solid::Box { size } => Solid::Box { size: size.map(f) },
        Solid::Sphere { radius } => Solid::Sphere { radius: f(radius) },
        Solid::Cylinder {
            radius,
            length,
            axis,
        } => Solid::Cylinder {
            radius: f(radius),
            length: f(length),
            axis,
        },
        Solid::Capsule {
            radius,
            length,
            axis,
        } => Solid::Capsule {
            radius: f(radius),
            length: f(length),
            axis,
        },
        Solid::Line { to } => Solid::Line { to },
    };
    let sizes: Vec<f64> = match solid {
        Solid::Box { size } => size.iter().copied().collect(),
        Solid::Sphere { radius } => vec![radius],
        Solid::Cylinder { radius, length, .. } | Solid::Capsule { radius, length, .. } => {
            vec![radius, length]
        }
        Solid::Line { .. } => Vec::new(),
    };
    if let Some(bad) = sizes.iter().find(|x| !(x.is_finite() && **x > 0.0)) {
        return Err(SettingsError::Value {
            owner: "shape",
            setting: "size (check the parameters it is written in)",
            value: *bad,
            requirement: "positive and finite".into(),
        }
        .into());
    }
    Ok(Drawn {
        on: s.on,
        at: s.at.map(|x| x.to_f64()),
        axes: Matrix3::identity(),
        solid,
        default: false,
    })
}

/// The solid box with the body's mass and principal moments A, B, C: edges
/// a² = 6 (B + C − A) / m and so on, along the principal axes, centred on the
/// centre of mass. A massless body (or one without inertia) gets a box of
/// size zero, which the page draws as a dot.
pub(super) fn equivalent_box(
    body: usize,
    inertia: &BodyInertia<impl Real>,
    centre: Vector3<f64>,
) -> Drawn {
    let m = inertia.mass.to_f64();
    let tensor = inertia.inertia.map(|x| x.to_f64());
    let eigen = SymmetricEigen::new(tensor);
    let [a, b, c] = [0, 1, 2].map(|i| eigen.eigenvalues[i]);
    let edge = |x: f64| (6.0 * x / m).max(0.0).sqrt();
    let mut size = Vector3::new(edge(b + c - a), edge(a + c - b), edge(a + b - c));
    let marker = m.is_nan() || m <= 0.0 || !size.iter().all(|x| x.is_finite()) || size.max() <= 0.0;
    if marker {
        size = Vector3::repeat(0.0);
    }
    // A flat body (a disc's thickness is zero) keeps a sliver so that it shows.
    let thinnest = size.max() * 0.02;
    size = size.map(|x| x.max(thinnest));
    let mut axes = eigen.eigenvectors;
    if axes.determinant() < 0.0 {
        axes.set_column(2, &(-axes.column(2)));
    }
    Drawn {
        on: Anchor::Body(body),
        at: centre,
        axes,
        solid: Solid::Box { size },
        default: true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A box of edges (a, b, c) and mass m has A = m (b² + c²) / 12: the
    /// equivalent box of those moments is that box again.
    #[test]
    fn the_box_of_a_box_s_inertia_is_that_box() {
        let m = 3.0_f64;
        let a = 0.4;
        let b = 1.0;
        let c = 2.5;
        let moment = |y: f64, z: f64| m * (y * y + z * z) / 12.0;
        let inertia = BodyInertia {
            mass: m,
            inertia: Matrix3::from_diagonal(&Vector3::new(
                moment(b, c),
                moment(a, c),
                moment(a, b),
            )),
        };
        let d = equivalent_box(0, &inertia, Vector3::zeros());
        let Solid::Box { size } = d.solid else {
            panic!("not a box: {d:?}")
        };
        // The principal axes come sorted by moment; compare the edges as a set.
        let mut edges: Vec<f64> = size.iter().copied().collect();
        edges.sort_by(f64::total_cmp);
        for (e, want) in edges.iter().zip([a, b, c]) {
            assert!((e - want).abs() < 1e-12, "{edges:?}");
        }
        // Each edge lies along the axis whose moment it leaves out.
        let world = d.axes * Matrix3::from_diagonal(&size);
        let along_x = world.column_iter().map(|c| c[0].abs()).fold(0.0, f64::max);
        assert!((along_x - a).abs() < 1e-12, "{world}");
    }

    #[test]
    fn a_massless_body_is_a_marker() {
        let inertia = BodyInertia::<f64>::default();
        let d = equivalent_box(2, &inertia, Vector3::zeros());
        assert_eq!(d.on, Anchor::Body(2));
        assert_eq!(
            d.solid,
            Solid::Box {
                size: Vector3::zeros()
            }
        );
    }
}

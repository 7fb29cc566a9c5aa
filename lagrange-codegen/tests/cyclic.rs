//! Cyclic coordinates, found from the derived expressions, on catalog systems
//! (read from `examples/catalog`, so the descriptions tested are the ones
//! shipped; the root crate's tests check the emitted `CYCLIC` of the same types).

mod common;
use common::model;

const MOD: &str = include_str!("../../examples/catalog/mod.rs");
const EXTREMES: &str = include_str!("../../examples/catalog/extremes.rs");
const CONSTRAINED: &str = include_str!("../../examples/catalog/constrained.rs");
const BICYCLE: &str = include_str!("../../examples/catalog/bicycle.rs");

/// The description of `name` in a catalog file: its `#[lagrange]` attribute and
/// its fields (the other derives dropped).
fn catalog(source: &str, name: &str) -> syn::DeriveInput {
    let file = syn::parse_file(source).expect("catalog parses");
    let mut item = file
        .items
        .into_iter()
        .find_map(|item| match item {
            syn::Item::Struct(s) if s.ident == name => Some(s),
            _ => None,
        })
        .unwrap_or_else(|| panic!("{name} in the catalog"));
    item.attrs.retain(|a| a.path().is_ident("lagrange"));
    syn::parse2(quote::quote!(#item)).expect("a derive input")
}

/// The cyclic coordinates of a catalog system, by name.
fn cyclic(source: &str, name: &str) -> Vec<String> {
    let input = catalog(source, name);
    let m = model(&quote::quote!(#input).to_string());
    m.variables
        .coordinates
        .iter()
        .zip(&m.variables.cyclic)
        .filter(|&(_, &c)| c)
        .map(|(q, _)| q.clone())
        .collect()
}

/// Precession ψ and spin φ of the heavy symmetric top are cyclic; nutation θ is not.
#[test]
fn heavy_top_precession_and_spin() {
    assert_eq!(cyclic(EXTREMES, "HeavyTop"), ["psi", "phi"]);
}

/// The rolling disk's contact point (x, y) on the plane and its spin φ are
/// cyclic; its heading and tilt enter the rolling constraints and gravity.
#[test]
fn rolling_disk_contact_point_and_spin() {
    assert_eq!(cyclic(CONSTRAINED, "RollingDisk"), ["x", "y", "phi"]);
}

/// The Whipple bicycle: the rear contact (x, y) and both wheels' rotations are
/// cyclic; roll, steer and pitch are not (nor yaw, which the rolling
/// constraints read). The wheels' angles stay in M's expressions (sin² + cos²
/// of an axisymmetric wheel, unfolded) and are found cyclic by evaluation.
#[test]
fn bicycle_contact_and_wheel_angles() {
    assert_eq!(cyclic(BICYCLE, "Bicycle"), ["x", "y", "theta_r", "theta_f"]);
}

/// A double pendulum has no cyclic coordinate, and its expansion keeps the
/// trait's default `CYCLIC`.
#[test]
fn double_pendulum_has_none() {
    assert!(cyclic(MOD, "DoublePendulum").is_empty());
    let tokens = lagrange_codegen::expand(&catalog(MOD, "DoublePendulum")).to_string();
    assert!(!tokens.contains("CYCLIC"), "{tokens}");
}

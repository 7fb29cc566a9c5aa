//! The gallery's choice of motion panels (examples/gallery/layout.rs): cyclic
//! coordinates apart and as rates. The module is pure, so it is included here
//! on its own and tested without building the gallery and its catalog.

#[path = "../examples/gallery/layout.rs"]
mod layout;

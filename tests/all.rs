//! Every integration test of the facade in one binary: the catalog and the
//! shared helpers are compiled once, not once per file (27 files read the
//! catalog). Each file is a module; `cargo test --test all <file>::` runs one.
//! Two stay binaries of their own: `state_feedback` installs a counting
//! global allocator, and `prelude_ensemble` needs the feature `parallel`.

#[path = "../examples/catalog/mod.rs"]
mod catalog;
#[path = "../examples/catalog/floating.rs"]
mod floating;
#[path = "../examples/catalog/legged.rs"]
mod legged;
#[path = "../examples/catalog/operational.rs"]
mod operational;
// The gallery's choice of motion panels, pure, with its tests inside.
mod common;
#[path = "../examples/gallery/layout.rs"]
mod layout;
#[path = "common/rolling.rs"]
mod rolling;

mod architecture;
mod atlas;
mod atlas_constraints;
mod atlas_events;
mod atlas_inputs;
mod atlas_rolling;
mod batched;
mod bicycle;
mod bodies;
mod cavity;
mod closed_forms;
mod complete_state;
mod constrained;
mod constrained_control;
mod constrained_tangent;
mod contact;
mod contact_compliant;
mod contact_impact_friction;
mod contact_inputs;
mod contact_legged;
mod contact_oriented;
mod contact_refused;
mod contact_sphere_friction;
mod contact_spheres;
mod contact_stepping;
mod control;
mod derivatives;
mod emitted;
mod emitted_derivatives;
mod events;
mod extremes;
mod failures;
mod floating_bases;
mod forward_route;
mod free_bodies;
mod identify_consistent;
mod identify_excite;
mod identify_payload;
mod inputs;
mod joint_friction;
mod joint_motor;
mod joints;
mod operational_space;
mod order;
mod physical;
mod piecewise;
mod planning;
mod planning_group;
mod rattle;
mod reactions;
mod recording;
mod reduced_breakdown;
mod reduced_orientation;
mod regressor;
mod regressor_joints;
mod regressor_momentum;
mod regressor_pinocchio;
mod rolling_quaternion;
mod scene;
mod scene_browser;
mod stability;
mod study;
mod symplectic_orientation;
mod task_space;
mod torqued_body;
mod torques;
mod trim_constrained;
mod urdf;
mod urdf_arms;
mod urdf_derivatives;
mod urdf_limits;
mod urdf_repair;

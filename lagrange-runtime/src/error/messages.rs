//! The parts of [`Error`](super::Error)'s messages that are computed: what a
//! singular mass matrix lacks, coordinates by name, what a step budget needs.
//! Kept apart from the enum so that its variants read as a list.

/// What a singular M has no inertia along, for its message.
pub(super) fn no_inertia(direction: &str) -> String {
    if direction.is_empty() {
        "; no inertia along some direction (a chart singularity of angle coordinates, \
         a massless body, an orientation no body turns)"
            .to_string()
    } else {
        format!(
            "; no inertia along {direction}: if those are angles, their chart is singular \
             here; otherwise give that direction a mass or an inertia"
        )
    }
}

/// "(x = 1, y = -2)" when the names fit, else the bare numbers.
pub(super) fn named(names: &[&str], q: &[f64]) -> String {
    if names.len() != q.len() {
        return format!("{q:?}");
    }
    let parts: Vec<String> = names
        .iter()
        .zip(q)
        .map(|(n, x)| format!("{n} = {x:?}"))
        .collect();
    format!("({})", parts.join(", "))
}

/// The message of [`Error::TooManySteps`]: what ran out, what the run needs
/// when that is known, and the setting that raises it.
pub(super) fn too_many_steps(t: f64, max_steps: usize, needed: Option<usize>) -> String {
    match needed {
        Some(n) => format!(
            "the run needs {n} steps but the step budget is {max_steps}: refused at the start \
             time t = {t}; raise it with `.max_steps({n})` on the integrator, or take a \
             larger step"
        ),
        None => format!(
            "the step budget `.max_steps({max_steps})` ran out at t = {t}, before the end of \
             the span; raise it with `.max_steps(n)` on the integrator (the adaptive step \
             control decides how many it needs), or loosen the tolerance"
        ),
    }
}

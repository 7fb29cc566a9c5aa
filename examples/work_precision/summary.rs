//! The guidance table: per scene and target accuracy, the fastest methods.

use super::*;

/// The guidance table: per scene and target accuracy, the three fastest methods
/// (each at its cheapest setting that reaches the target).
pub(crate) fn summary(scenes: &[Scene]) -> String {
    let mut md = String::from(
        "# Work-precision summary (generated)\n\n\
         Per scene and target accuracy (max error of the positions at the final time), \
         the fastest runs that reach it, one per method, each at its cheapest setting: \
         wall time, RHS evaluations.\n\n\
         | scene | target | fastest | second | third |\n|---|---|---|---|---|\n",
    );
    for scene in scenes {
        let floor = scene.study.reference().uncertainty().unwrap_or(0.0);
        for target in TARGETS {
            let cells: Vec<String> = if target < floor {
                vec![format!(
                    "not measurable: the reference is only good to {floor:.0e}"
                )]
            } else {
                let best = scene.study.cheapest_per_method(target);
                if best.is_empty() {
                    vec!["no run reaches it".into()]
                } else {
                    best.iter()
                        .take(3)
                        .map(|r| {
                            let m = r.measurement().expect("cheapest rows succeeded");
                            format!(
                                "{} {} ({:.3} ms, {} evals)",
                                r.method,
                                r.setting,
                                m.wall_time.as_secs_f64() * 1e3,
                                m.stats.evaluations
                            )
                        })
                        .collect()
                }
            };
            let mut cells = cells;
            cells.resize(3, String::new());
            md += &format!(
                "| {} | {target:.0e} | {} |\n",
                scene.title,
                cells.join(" | ")
            );
        }
    }
    md
}

//! Which coordinates a system's motion plot draws where: the coordinates that
//! carry the behaviour as values on the main panel, the cyclic ones (no
//! equation of motion reads them: wheel angles, positions on a plane) as rates
//! on a panel of their own, since their values grow without bound and would
//! flatten everything else drawn beside them.
//!
//! Pure and free of the gallery's other modules, so that a test of the root
//! crate (tests/gallery_layout.rs) includes it without building the gallery.

/// How a coordinate is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Shown {
    /// Its value q_i(t).
    Value,
    /// Its rate q̇_i(t).
    Rate,
}

/// One panel of the motion plot: its y-axis label and its series.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Panel {
    pub y_label: &'static str,
    /// (coordinate index, legend label, what is drawn of it).
    pub series: Vec<(usize, String, Shown)>,
}

/// The y-axis label of the main panel.
pub(crate) const COORDINATES: &str = "coordinates";
/// The y-axis label of the panel of cyclic coordinates' rates.
pub(crate) const RATES: &str = "rates of cyclic coordinates";

/// The motion panels for coordinates `names` of which `cyclic[i]` marks the
/// cyclic ones (a missing entry counts as not cyclic): the others as values
/// on a first panel, the cyclic ones as rates on a second. A panel with no
/// series is left out, so with no cyclic coordinates there is the one panel of
/// all the values.
pub(crate) fn motion_panels(names: &[&str], cyclic: &[bool]) -> Vec<Panel> {
    let is_cyclic = |i: usize| cyclic.get(i).copied().unwrap_or(false);
    let values = Panel {
        y_label: COORDINATES,
        series: (0..names.len())
            .filter(|&i| !is_cyclic(i))
            .map(|i| (i, names[i].to_string(), Shown::Value))
            .collect(),
    };
    let rates = Panel {
        y_label: RATES,
        series: (0..names.len())
            .filter(|&i| is_cyclic(i))
            .map(|i| (i, format!("d{}/dt", names[i]), Shown::Rate))
            .collect(),
    };
    [values, rates]
        .into_iter()
        .filter(|p| !p.series.is_empty())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn indices(panel: &Panel) -> Vec<usize> {
        panel.series.iter().map(|s| s.0).collect()
    }

    #[test]
    fn no_cyclic_coordinate_is_one_panel_of_values() {
        let panels = motion_panels(&["theta", "phi"], &[false, false]);
        assert_eq!(panels.len(), 1);
        assert_eq!(panels[0].y_label, COORDINATES);
        assert_eq!(
            panels[0].series,
            vec![
                (0, "theta".to_string(), Shown::Value),
                (1, "phi".to_string(), Shown::Value)
            ]
        );
    }

    #[test]
    fn cyclic_coordinates_go_apart_as_rates_in_order() {
        // The Whipple bicycle: the position on the plane, the heading and the
        // wheel angles are cyclic; roll, pitch and steer carry the behaviour.
        let names = [
            "x", "y", "psi", "phi", "pitch", "theta_r", "delta", "theta_f",
        ];
        let mask = [true, true, true, false, false, true, false, true];
        let panels = motion_panels(&names, &mask);
        assert_eq!(panels.len(), 2);
        assert_eq!(panels[0].y_label, COORDINATES);
        assert_eq!(indices(&panels[0]), [3, 4, 6]);
        assert!(panels[0].series.iter().all(|s| s.2 == Shown::Value));
        assert_eq!(panels[1].y_label, RATES);
        assert_eq!(indices(&panels[1]), [0, 1, 2, 5, 7]);
        assert!(panels[1].series.iter().all(|s| s.2 == Shown::Rate));
        assert_eq!(panels[1].series[3].1, "dtheta_r/dt");
    }

    #[test]
    fn all_cyclic_is_one_panel_of_rates() {
        let panels = motion_panels(&["x", "y"], &[true, true]);
        assert_eq!(panels.len(), 1);
        assert_eq!(panels[0].y_label, RATES);
        assert_eq!(indices(&panels[0]), [0, 1]);
    }

    #[test]
    fn a_short_mask_counts_the_rest_as_not_cyclic() {
        let panels = motion_panels(&["a", "b", "c"], &[true]);
        assert_eq!(indices(&panels[0]), [1, 2]);
        assert_eq!(indices(&panels[1]), [0]);
    }

    #[test]
    fn no_coordinates_no_panels() {
        assert!(motion_panels(&[], &[]).is_empty());
    }
}

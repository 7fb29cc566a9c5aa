//! `Clone` for [`Error`]: every variant field by field, except the i/o error,
//! which `std::io::Error` cannot clone: its copy keeps the kind, the OS error
//! code and the message.

use super::Error;

/// The match arms cloning each listed struct variant field by field (the
/// fields are listed in full, so that a new field fails to compile here
/// rather than being lost) and each listed tuple variant.
macro_rules! clone_variants {
    ($value:expr, $io:ident => $io_clone:expr;
     $($name:ident { $($field:ident),* $(,)? }),* $(,)?;
     $($tuple:ident),* $(,)?) => {
        match $value {
            $(Error::$name { $($field),* } => Error::$name { $($field: $field.clone()),* },)*
            $(Error::$tuple(inner) => Error::$tuple(inner.clone()),)*
            Error::Io($io) => Error::Io($io_clone),
        }
    };
}

impl Clone for Error {
    fn clone(&self) -> Self {
        clone_variants!(self, e => clone_io(e);
            SingularMassMatrix { t, q, ratio, direction, atlas },
            NonFiniteState { t, q, v },
            NonFinitePose { t, name },
            RedundantConstraints { t, q, coordinates, ratio, dependent },
            InconsistentInitialConditions {
                t, q, coordinates, position_residual, velocity_residual, tolerance, constraint,
            },
            ProjectionFailed { t, q, coordinates, residual, iterations, tolerance },
            StepSizeUnderflow { t, h },
            ProbablyStiff { method, t, h_lambda, tests },
            ReducedFormBreakdown { t, q, coordinates, rows, ratio },
            TooManySteps { t, max_steps, needed },
            NewtonFailure { t, h, iterations },
            EventFunction { event, t, q, v },
            TooManyEvents { t, event, max_events },
            EventsAccumulate { t, event, count },
            NonFiniteInput { t, input, value, q, v },
            MissingDerivatives { method, needed_for },
            NonPhysicalParameter { body, entry, value, reason },
            NonUnitQuaternion { orientation, norm, tolerance },
            JointLimit { joint, coordinate, value, lower, upper, t },
            UnknownBody { body, count, bodies },
            InverseKinematics { body, iterations, residual, tolerance };
            Settings, Linear, Plan, Contact, Identify
        )
    }
}

/// An i/o error with the same kind, OS error code and message.
fn clone_io(e: &std::io::Error) -> std::io::Error {
    match e.raw_os_error() {
        Some(code) => std::io::Error::from_raw_os_error(code),
        None => std::io::Error::new(e.kind(), e.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clones_keep_the_message() {
        let errors = [
            Error::TooManySteps {
                t: 0.5,
                max_steps: 10,
                needed: Some(20),
            },
            Error::Settings(crate::error::SettingsError::ZeroCount {
                owner: "events",
                setting: "max_events",
            }),
            std::io::Error::other("disk full").into(),
            std::io::Error::from(std::io::ErrorKind::NotFound).into(),
            std::io::Error::from_raw_os_error(2).into(),
        ];
        for e in &errors {
            assert_eq!(e.clone().to_string(), e.to_string());
        }
        let Error::Io(io) = errors[3].clone() else {
            panic!()
        };
        assert_eq!(io.kind(), std::io::ErrorKind::NotFound);
        let Error::Io(io) = errors[4].clone() else {
            panic!()
        };
        assert_eq!(io.raw_os_error(), Some(2));
    }
}

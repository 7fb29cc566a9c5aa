//! The events of a configuration typed with Q entries seen as one with N,
//! when Q = N: what lets one event builder serve the constrained forms (whose
//! configurations have no orientations) and the systems with orientations.

use super::{Event, Events, Terminal};
use crate::numeric::Real;
use nalgebra::SVector;

/// q read as the other configuration type of the same length.
fn cast<T: Real, const A: usize, const B: usize>(q: &SVector<T, A>) -> SVector<T, B> {
    SVector::from_fn(|i, _| q[i])
}

impl<'a, T: Real, const N: usize, const Q: usize> Events<'a, T, N, Q> {
    /// These events over q of N entries, borrowing their functions; `None`
    /// unless Q = N.
    pub(crate) fn square(&self) -> Option<Events<'_, T, N, N>> {
        if Q != N {
            return None;
        }
        let events = self.events.iter().map(Event::square).collect();
        Some(Events {
            events,
            max_events: self.max_events,
        })
    }
}

impl<T: Real, const N: usize, const Q: usize> Event<'_, T, N, Q> {
    /// This event over q of N entries (Q = N, checked by the caller).
    fn square(&self) -> Event<'_, T, N, N> {
        let g = &self.g;
        let terminal = match &self.terminal {
            Terminal::Never => Terminal::Never,
            Terminal::Always => Terminal::Always,
            Terminal::If(test) => Terminal::If(Box::new(move |t, q: &SVector<T, N>, v| {
                test(t, &cast(q), v)
            })),
        };
        let action = self.action.as_ref().map(|act| {
            Box::new(move |t, q: &mut SVector<T, N>, v: &mut SVector<T, N>| {
                let mut wide = cast::<T, N, Q>(q);
                act(t, &mut wide, v);
                *q = cast(&wide);
            }) as Box<dyn Fn(T, &mut SVector<T, N>, &mut SVector<T, N>) + '_>
        });
        Event {
            name: self.name.clone(),
            g: Box::new(move |t, q: &SVector<T, N>, v| g(t, &cast(q), v)),
            direction: self.direction,
            terminal,
            action,
            restart: self.restart,
        }
    }
}

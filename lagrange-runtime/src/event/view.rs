//! An event read through a change of coordinates: what lets a run held in
//! other coordinates than the user's (the atlas's charts of the moment)
//! watch the user's events on the user's coordinates.

use super::{Event, Terminal};
use crate::numeric::Real;
use nalgebra::SVector;

/// A map of the state into the coordinates an event reads, at time t.
pub(crate) type ViewFn<'v, T, const N: usize> =
    &'v dyn Fn(T, &SVector<T, N>, &SVector<T, N>) -> (SVector<T, N>, SVector<T, N>);
/// The map back, at time t, of a state the event's action changed; the
/// second argument is the configuration held before the action.
pub(crate) type BackFn<'v, T, const N: usize> =
    &'v dyn Fn(T, &SVector<T, N>, &mut SVector<T, N>, &mut SVector<T, N>);

impl<T: Real, const N: usize> Event<'_, T, N> {
    /// This event with g, the terminal test and the action reading the state
    /// through `into`; an action's result is mapped back through `back`.
    /// Borrows the event's functions.
    pub(crate) fn viewed<'v>(
        &'v self,
        into: ViewFn<'v, T, N>,
        back: BackFn<'v, T, N>,
    ) -> Event<'v, T, N> {
        let g = &self.g;
        let terminal = match &self.terminal {
            Terminal::Never => Terminal::Never,
            Terminal::Always => Terminal::Always,
            Terminal::If(test) => Terminal::If(Box::new(move |t, q: &SVector<T, N>, v| {
                let (q, v) = into(t, q, v);
                test(t, &q, &v)
            })),
        };
        let action = self.action.as_ref().map(|act| {
            Box::new(move |t, q: &mut SVector<T, N>, v: &mut SVector<T, N>| {
                let held = *q;
                let (mut qu, mut vu) = into(t, q, v);
                act(t, &mut qu, &mut vu);
                back(t, &held, &mut qu, &mut vu);
                (*q, *v) = (qu, vu);
            }) as Box<dyn Fn(T, &mut SVector<T, N>, &mut SVector<T, N>) + 'v>
        });
        Event {
            name: self.name.clone(),
            g: Box::new(move |t, q: &SVector<T, N>, v: &SVector<T, N>| {
                let (q, v) = into(t, q, v);
                g(t, &q, &v)
            }),
            direction: self.direction,
            terminal,
            action,
            restart: self.restart,
        }
    }
}

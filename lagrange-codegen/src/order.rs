//! The order in which definitions, bodies and points are lowered.
//!
//! Users write items in whatever order reads best (a body placed at a point of
//! another body, a definition that uses a point's coordinates, a point declared
//! after the body it sits on). Each of these items is lowered once every item it
//! names has been, so the order written does not matter; a cycle is an error that
//! names it.

use std::collections::BTreeMap;

use proc_macro2::Span;
use syn::{Expr, Ident};

use crate::ast::System;
use crate::ctxt::Ctxt;

/// One item that brings a name into scope.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Item {
    /// `define(..)` item k.
    Definition(usize),
    /// `body(..)` item k.
    Body(usize),
    /// `point(..)` item k.
    Point(usize),
}

/// The items in an order where each comes after the items it names: the order
/// written where it already is (the earliest ready item goes first). Items on a
/// cycle are reported and left out.
pub fn lowering_order(cx: &Ctxt, system: &System) -> Vec<Item> {
    let items = items(system);
    let index: BTreeMap<String, usize> = items
        .iter()
        .enumerate()
        .map(|(i, e)| (e.name.to_string(), i))
        .collect();
    // A name used inside its own item (`at = [B.x, ..]` in body `B`) is a cycle
    // of one, reported like any other.
    let deps: Vec<Vec<usize>> = items
        .iter()
        .map(|e| {
            let mut names = e.also.clone();
            for x in &e.exprs {
                names_in(x, &mut names);
            }
            let mut d: Vec<usize> = names.iter().filter_map(|n| index.get(n).copied()).collect();
            d.sort_unstable();
            d.dedup();
            d
        })
        .collect();
    let mut done = vec![false; items.len()];
    let mut order = Vec::with_capacity(items.len());
    while let Some(i) = (0..items.len()).find(|&i| !done[i] && deps[i].iter().all(|&j| done[j])) {
        done[i] = true;
        order.push(items[i].item);
    }
    if order.len() < items.len() {
        report_cycle(cx, &items, &deps, &done);
    }
    order
}

/// An item with what it refers to: its expressions, and names given as plain
/// identifiers (the body of `point(P, on = B, ..)`).
struct Entry<'a> {
    name: &'a Ident,
    item: Item,
    exprs: Vec<&'a Expr>,
    also: Vec<String>,
}

fn items(system: &System) -> Vec<Entry<'_>> {
    let mut out = Vec::new();
    for (i, d) in system.definitions.iter().enumerate() {
        out.push(Entry {
            name: &d.name,
            item: Item::Definition(i),
            exprs: vec![&d.value],
            also: Vec::new(),
        });
    }
    for (i, b) in system.bodies.iter().enumerate() {
        let exprs = [&b.mass, &b.inertia, &b.at, &b.com, &b.rotation];
        out.push(Entry {
            name: &b.name,
            item: Item::Body(i),
            exprs: exprs.into_iter().flatten().collect(),
            also: Vec::new(),
        });
    }
    for (i, p) in system.points.iter().enumerate() {
        out.push(Entry {
            name: &p.name,
            item: Item::Point(i),
            exprs: [&p.mass, &p.at].into_iter().flatten().collect(),
            also: p.on.iter().map(|b| b.to_string()).collect(),
        });
    }
    out
}

/// Names used in an expression: plain identifiers and the bases of field accesses
/// (`P.x`), not function names.
fn names_in(e: &Expr, out: &mut Vec<String>) {
    match e {
        Expr::Path(p) => {
            if let Some(id) = p.path.get_ident() {
                out.push(id.to_string());
            }
        }
        Expr::Field(f) => names_in(&f.base, out),
        Expr::Paren(p) => names_in(&p.expr, out),
        Expr::Group(g) => names_in(&g.expr, out),
        Expr::Unary(u) => names_in(&u.expr, out),
        Expr::Binary(b) => {
            names_in(&b.left, out);
            names_in(&b.right, out);
        }
        Expr::Call(c) => c.args.iter().for_each(|a| names_in(a, out)),
        Expr::MethodCall(m) => {
            names_in(&m.receiver, out);
            m.args.iter().for_each(|a| names_in(a, out));
        }
        Expr::Array(a) => a.elems.iter().for_each(|x| names_in(x, out)),
        _ => {}
    }
}

/// Reports one cycle among the items not lowered, at the first item on it.
fn report_cycle(cx: &Ctxt, items: &[Entry<'_>], deps: &[Vec<usize>], done: &[bool]) {
    let Some(start) = (0..items.len()).find(|&i| !done[i]) else {
        return;
    };
    // Walk undone dependencies until a node repeats: that stretch is a cycle.
    let mut path = vec![start];
    let mut at = start;
    loop {
        let Some(&next) = deps[at].iter().find(|&&j| !done[j]) else {
            return;
        };
        if let Some(pos) = path.iter().position(|&p| p == next) {
            let cycle: Vec<String> = path[pos..]
                .iter()
                .chain(std::iter::once(&next))
                .map(|&i| format!("`{}`", items[i].name))
                .collect();
            let first = items[path[pos]].name;
            let span: Span = first.span();
            cx.error_at(
                span,
                format!(
                    "`{first}` depends on itself through {}; break the cycle by writing one of these positions in the coordinates directly",
                    cycle.join(" -> ")
                ),
            );
            return;
        }
        path.push(next);
        at = next;
    }
}

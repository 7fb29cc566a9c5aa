//! The derived equations as text, for rustdoc and the `EQUATIONS` constant.

use std::fmt::Write;

use crate::mechanics::{BiasRoute, Model};

pub fn equations(model: &Model) -> String {
    let ctx = &model.ctx;
    let n = model.dof();
    let mut s = String::new();
    let args = if model.rheonomic { "q, t" } else { "q" };
    match &model.inputs {
        None => {
            let _ = writeln!(s, "M({args}) q'' + h({args}, q') = Q({args}, q')");
        }
        Some(_) => {
            let _ = writeln!(
                s,
                "M({args}) q'' + h({args}, q') = Q({args}, q', u) = Q({args}, q', 0) + dQ({args}, q', u)"
            );
        }
    }
    let _ = writeln!(s, "q = ({})", model.coordinates.join(", "));
    if let Some(inputs) = &model.inputs {
        let _ = writeln!(
            s,
            "u = ({}): inputs supplied at run time; M, h, Q and the energies below are at u = 0",
            inputs.names.join(", ")
        );
    }
    let _ = writeln!(
        s,
        "{}",
        if model.rheonomic {
            "rheonomic: the position maps depend on t; conserved (if forces are conservative): Jacobi integral T2 - T0 + V"
        } else {
            "scleronomic: conserved (if forces are conservative): T + V"
        }
    );
    let _ = writeln!(s);
    for i in 0..n {
        for j in i..n {
            let _ = writeln!(s, "M[{i}][{j}] = {}", ctx.display(model.mass[i][j]));
        }
    }
    let route = match model.bias_route {
        BiasRoute::Projection => "d'Alembert projection",
        BiasRoute::Christoffel => "Christoffel symbols",
    };
    let _ = writeln!(s, "\nh (by {route}):");
    for (i, h) in model.bias.iter().enumerate() {
        let _ = writeln!(s, "h[{i}] = {}", ctx.display(*h));
    }
    let _ = writeln!(s, "\nQ:");
    for (i, f) in model.forces.iter().enumerate() {
        let _ = writeln!(s, "Q[{i}] = {}", ctx.display(*f));
    }
    if let Some(inputs) = &model.inputs {
        let _ = writeln!(s, "\ninputs: dQ = Q(u) - Q(0):");
        for (i, f) in inputs.forces.iter().enumerate() {
            let _ = writeln!(s, "dQ[{i}] = {}", ctx.display(*f));
        }
        let _ = writeln!(s, "dQ/du:");
        for (i, row) in inputs.jacobian_u.iter().enumerate() {
            for (j, d) in row.iter().enumerate() {
                let name = &inputs.names[j];
                let _ = writeln!(s, "dQ[{i}]/d{name} = {}", ctx.display(*d));
            }
        }
    }
    let _ = writeln!(s, "\nT = {}", ctx.display(model.kinetic));
    let _ = writeln!(s, "V = {}", ctx.display(model.potential));
    if let Some(c) = &model.constraints {
        let _ = writeln!(
            s,
            "\nconstraints (multipliers): G q' + g = 0, G q'' = gamma; the first {} holonomic",
            c.holonomic
        );
        for (k, name) in c.names.iter().enumerate() {
            if k < c.holonomic {
                let _ = writeln!(s, "{name}: Phi = {}", ctx.display(c.phi[k]));
            }
            let row: Vec<String> = c.jacobian[k].iter().map(|&e| ctx.display(e)).collect();
            let _ = writeln!(
                s,
                "{name}: G = [{}], g = {}",
                row.join(", "),
                ctx.display(c.velocity_term[k])
            );
            let _ = writeln!(s, "{name}: gamma = {}", ctx.display(c.gamma[k]));
        }
    }
    if let Some(r) = &model.reduced {
        let _ = writeln!(
            s,
            "\nreduced form on the speeds u = ({}):",
            r.names.join(", ")
        );
        for (k, name) in r.names.iter().enumerate() {
            let _ = writeln!(s, "{name} = {}", ctx.display(r.speeds[k]));
        }
        let _ = writeln!(
            s,
            "rows A q' + b = (u, 0), solved with pivoting at run time:"
        );
        for (k, name) in r.rows.iter().enumerate() {
            let row: Vec<String> = r.matrix[k].iter().map(|&e| ctx.display(e)).collect();
            let _ = writeln!(
                s,
                "{name}: A = [{}], b = {}",
                row.join(", "),
                ctx.display(r.free[k])
            );
            let _ = writeln!(s, "{name}: c = {}", ctx.display(r.rates[k]));
        }
    }
    s
}

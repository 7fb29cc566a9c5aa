//! The gallery on disk: per system a CSV and a PNG, three animations, and an
//! `index.html` that shows them beside the summary table.

use crate::plot;
use crate::row::Row;
use lagrange::Error;
use lagrange::picture::{StillPicture, segments_png};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Where each animation's data comes from: (file, the row's system name).
pub(crate) struct Animations<'a> {
    pub double_pendulum: Option<(&'a Row, f64, f64)>,
    pub rolling_disk: Option<(&'a Row, f64)>,
    pub cavity: Option<(&'a Row, f64)>,
}

/// A file name for a system: lower case, words joined by '-'.
pub(crate) fn slug(name: &str) -> String {
    let mut s = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.ends_with('-') && !s.is_empty() {
            s.push('-');
        }
    }
    s.trim_end_matches('-').to_string()
}

/// Writes everything under `out` and returns the path of `index.html`.
pub(crate) fn write(out: &Path, rows: &[Row], animations: &Animations) -> Result<PathBuf, Error> {
    std::fs::create_dir_all(out)?;
    lagrange::picture::register_font()?;
    for row in rows {
        let Some(fig) = &row.figure else { continue };
        let name = slug(row.system);
        std::fs::write(out.join(format!("{name}.csv")), &fig.csv)?;
        plot::system_png(&out.join(format!("{name}.png")), row.system, fig)?;
    }
    for row in rows {
        if let Some(page) = &row.scene {
            std::fs::write(out.join(scene_file(row.system)), page)?;
        }
        if let Some(segments) = &row.still {
            // The table's thumbnail: small, without a title.
            let thumbnail = StillPicture::new().size(180, 120).line_width(1);
            segments_png(out.join(still_file(row.system)), segments, &thumbnail)?;
        }
    }
    let mut gifs = Vec::new();
    if let Some((row, l1, l2)) = animations.double_pendulum
        && let Some(fig) = &row.figure
    {
        plot::double_pendulum_gif(&out.join("double-pendulum.gif"), fig, l1, l2)?;
        gifs.push(("double-pendulum.gif".to_string(), row.system));
    }
    if let Some((row, radius)) = animations.rolling_disk
        && let Some(fig) = &row.figure
    {
        plot::rolling_disk_gif(&out.join("rolling-disk.gif"), fig, radius)?;
        gifs.push(("rolling-disk.gif".to_string(), row.system));
    }
    if let Some((row, radius)) = animations.cavity
        && let Some(fig) = &row.figure
    {
        plot::cavity_gif(&out.join("cavity.gif"), fig, radius)?;
        gifs.push(("cavity.gif".to_string(), row.system));
    }
    for row in rows {
        if let Some((frames, captions)) = &row.frames {
            let file = format!("{}.gif", slug(row.system));
            crate::still::gif(&out.join(&file), frames, |k| captions[k].clone())?;
            gifs.push((file, row.system));
        }
    }
    let index = out.join("index.html");
    std::fs::write(&index, html(rows, &gifs))?;
    Ok(index)
}

/// The file of a system's 3D scene.
pub(crate) fn scene_file(system: &str) -> String {
    format!("{}-scene.html", slug(system))
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The file of a system's still (the table's picture of its scene).
fn still_file(system: &str) -> String {
    format!("{}-still.png", slug(system))
}

/// A link to the row's scene, if it has one (its still as the link, if drawn).
fn scene_link(r: &Row, text: &str, picture: bool) -> String {
    match (&r.scene, &r.still) {
        (Some(_), Some(_)) if picture => format!(
            "<a href=\"{}\"><img src=\"{}\" width=\"90\" alt=\"{text}\" title=\"open the 3D scene\"></a>",
            scene_file(r.system),
            still_file(r.system)
        ),
        (Some(_), _) => format!("<a href=\"{}\">{text}</a>", scene_file(r.system)),
        _ => String::new(),
    }
}

/// The catalog id ("C5") and the human name of a gallery system name.
fn split_id(system: &str) -> (&str, &str) {
    match system.split_once(' ') {
        Some((id, rest)) if id.starts_with('C') && id[1..].chars().all(|c| c.is_ascii_digit()) => {
            (id, rest)
        }
        _ => ("", system),
    }
}

fn html(rows: &[Row], gifs: &[(String, &str)]) -> String {
    let mut s = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>lagrange gallery</title><style>\
         body{font-family:sans-serif;margin:2em;max-width:1200px;color:#222}\
         table{border-collapse:collapse;font-size:14px}td,th{border:1px solid #ccc;padding:4px 8px}\
         th{background:#f2f2f2}td.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}\
         .anim{display:flex;gap:1em;flex-wrap:wrap}figure{margin:0}\
         section{margin-top:2em;border-top:1px solid #ddd}img{max-width:100%}</style></head><body>\n\
         <h1>lagrange gallery</h1>\n<p>Every catalog system simulated with DOPRI5 at \
         rtol = atol = 1e-10 in f64 (controlled and linearised systems included), \
         but for the 200 flips of the tumbling body, with the symplectic Gauss method. \
         <i>drift</i> is the largest relative change of the conserved quantity \
         (T + V, or the Jacobi integral); <i>residuals</i> the largest |&Phi;| and \
         |G q&#775; + g| along the run. Each system has a plot and its trajectory as CSV below, and a 3D scene \
         (a page of its own, offline: play, scrub, drag to orbit, wheel to zoom).</p>\n",
    );
    if !gifs.is_empty() {
        s.push_str("<h2>Animations</h2>\n<div class=\"anim\">\n");
        for (file, system) in gifs {
            let _ = writeln!(
                s,
                "<figure><img src=\"{file}\" alt=\"{0}\"><figcaption>{0}</figcaption></figure>",
                escape(system)
            );
        }
        s.push_str("</div>\n");
    }
    s.push_str(
        "<h2>Summary</h2>\n<table><tr><th>id</th><th>system</th><th>what it shows</th>\
         <th>dof</th><th>span</th><th>steps (rejected)</th><th>drift</th><th>residuals |&Phi;|, |Gv|</th>\
         <th>check</th><th>wall ms</th><th>scene</th></tr>\n",
    );
    for r in rows {
        let (id, name) = split_id(r.system);
        let link = if r.figure.is_some() {
            format!(
                "<a href=\"#{}\">{}</a>",
                crate::output::slug(r.system),
                escape(name)
            )
        } else {
            escape(name)
        };
        let _ = writeln!(
            s,
            "<tr><td>{id}</td><td>{link}</td><td>{}</td><td class=\"n\">{}</td>\
             <td class=\"n\">{}</td><td class=\"n\">{} ({})</td><td class=\"n\">{}</td>\
             <td class=\"n\">{}</td><td>{}</td><td class=\"n\">{:.1}</td><td>{}</td></tr>",
            escape(r.about),
            r.dof,
            span(r.span),
            r.accepted,
            r.rejected,
            r.drift.map_or("—".into(), |d| format!("{d:.1e}")),
            r.residuals
                .map_or("—".into(), |[p, v]| format!("{p:.1e}, {v:.1e}")),
            escape(&r.note),
            r.wall_ms,
            scene_link(r, "3D", true)
        );
    }
    s.push_str("</table>\n");
    for r in rows.iter().filter(|r| r.figure.is_some()) {
        let name = slug(r.system);
        let _ = writeln!(
            s,
            "<section id=\"{name}\"><h3>{}</h3><p>{} <a href=\"{name}.csv\">trajectory CSV</a> {}</p>\
             <img src=\"{name}.png\" alt=\"{}\"></section>",
            escape(r.system),
            escape(r.about),
            scene_link(r, "3D scene", false),
            escape(r.system)
        );
    }
    s.push_str("</body></html>\n");
    s
}

/// A run's span for the table: as written when it is a round number, else
/// to four significant figures (a span of whole flip periods is not).
fn span(x: f64) -> String {
    if x == x.round() {
        return format!("{x}");
    }
    let decimals = (3 - x.abs().log10().floor() as i32).max(0) as usize;
    let text = format!("{x:.decimals$}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

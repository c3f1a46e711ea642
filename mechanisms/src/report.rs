//! The validation report as one self-contained HTML page: per case its title and problem,
//! the mechanism drawn and animated from its generated geometry, the compared quantity's
//! curve with the theory, RecurDyn and mbd values marked, the manual's table, and where the
//! manual is wrong. Inline SVG, CSS and a few lines of JavaScript; no network.

use crate::drawing::Added;
use crate::plot::{self, Mark, Series};
use crate::validation::{Animation, Case, OFF_CURVE, Outcome, Read};
use serde::Serialize;
use std::fmt::Write as _;

/// One row of the report (the `--json` schema of `validate`).
#[derive(Serialize, Debug, Clone)]
pub struct ReportRow {
    pub case: String,
    pub quantity: String,
    pub unit: String,
    pub theory: Option<f64>,
    pub recurdyn: Option<f64>,
    pub value: f64,
    pub error_pct: f64,
    pub recurdyn_error_pct: Option<f64>,
    pub reference: f64,
    pub method: String,
    pub runtime_s: f64,
}

/// One case as run: what the page shows of it.
#[derive(Debug)]
pub struct CaseRun {
    pub case: Case,
    pub outcome: Outcome,
    pub rows: Vec<ReportRow>,
    pub runtime_s: f64,
    /// The drawing, or why there is none.
    pub animation: Result<Animation, String>,
}

/// `v` to `n` significant figures, without trailing zeros after the point.
pub fn sig(v: f64, n: usize) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".into();
    }
    let mag = v.abs().log10().floor() as i32;
    if !(-4..6).contains(&mag) {
        return format!("{v:.*e}", n.saturating_sub(1));
    }
    let decimals = (n as i32 - 1 - mag).max(0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// An error in percent: two significant figures (it says how many digits agree).
fn pct(e: f64) -> String {
    if e == 0.0 {
        "0".into()
    } else if e < 1e-3 {
        format!("{e:.1e}")
    } else {
        sig(e, 2)
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Markdown's `code` and **bold** as HTML, after escaping.
fn inline(s: &str) -> String {
    let mut out = String::new();
    for (i, part) in esc(s).split('`').enumerate() {
        if i % 2 == 1 {
            let _ = write!(out, "<code>{part}</code>");
        } else {
            for (j, p) in part.split("**").enumerate() {
                if j % 2 == 1 {
                    let _ = write!(out, "<b>{p}</b>");
                } else {
                    out.push_str(p);
                }
            }
        }
    }
    out
}

/// The plot of a case's `i`-th compared quantity: its curve from the case's run, with the
/// theory, RecurDyn and mbd values (and the exact one where the manual's theory is
/// corrected) marked where the quantity is compared; or why there is none.
pub fn row_plot(run: &CaseRun, i: usize) -> Result<String, String> {
    let (Some(row), Some(r)) = (run.outcome.rows.get(i), run.rows.get(i)) else {
        return Err(format!("no row {i}"));
    };
    let c = &row.curve;
    let what = match c.read {
        Read::Ordinate { .. } => r.quantity.clone(),
        Read::Abscissa { .. } => format!("{} (abscissa)", r.quantity),
    };
    let mark = |name: &str, v: f64| {
        let (x, y) = c.point(v);
        (format!("{name}: {}", sig(v, 6)), x, y)
    };
    let mut marks: Vec<Mark> = vec![mark(&format!("mbd {what}"), r.value)];
    marks.extend(r.theory.map(|v| mark("theory", v)));
    marks.extend(r.recurdyn.map(|v| mark("RecurDyn", v)));
    if corrected(r) {
        marks.push(mark("exact", r.reference));
    }
    let curve = Series {
        name: "mbd".into(),
        points: c.points.clone(),
        line: true,
        markers: false,
    };
    let title = format!("Case {}: {} [{}]", run.case.id, r.quantity, r.unit);
    plot::line_plot(&title, c.x_label, c.y_label, &[curve], &marks)
}

/// Whether mbd's value of the `i`-th row lies on its curve (to [`OFF_CURVE`] of the curve's
/// height): else the row and the run it is plotted from disagree, and the page says so.
pub fn off_curve(run: &CaseRun, i: usize) -> Option<String> {
    let row = run.outcome.rows.get(i)?;
    match row.curve.offset(row.value) {
        Some(d) if d <= OFF_CURVE => None,
        Some(d) => Some(format!(
            "mbd's {} lies off its curve by {} % of the curve's height",
            row.quantity,
            sig(100.0 * d, 2)
        )),
        None => Some(format!(
            "mbd's {} is compared outside its curve",
            row.quantity
        )),
    }
}

/// What the columns of the validation tables mean, one item each, for readers new to the
/// report (the text table and `report.md`; the HTML page says the same in its introduction).
pub const LEGEND: &[&str] = &[
    "quantity, unit: the manual's name of the compared value (its symbols: case NN's section \
     of report.html) and its unit, in which theory, RecurDyn, mbd and reference are all given.",
    "theory, RecurDyn: the validation manual's values as printed there. The manual solves 30 \
     textbook problems (Meriam & Kraige, Engineering Mechanics: Dynamics, 7th ed.; each case \
     names its problem) by hand and with the commercial code RecurDyn; its tables are \
     transcribed in mechanisms/data/comparison-tables.csv.",
    "reference: the exact value every error is measured against: the manual's theory to full \
     precision or, where the theory is marked *, a corrected value the theory does not round \
     to (report.html and the case's source, mechanisms/src/caseNN_*.rs, say why).",
    "mbd: mbd's value (10 significant figures). RD err %, mbd err % (RecurDyn's and mbd's): \
     |value - reference| / |reference| x 100; where \
     the reference is 0, |value| x 100 in the row's unit.",
    "method: how mbd obtained the value. time [us]: wall-clock time of the whole case run, \
     shared by its rows.",
];

/// The report's bottom line, one sentence each: how many rows and cases were compared, the
/// largest mbd and RecurDyn errors with their rows, and every case that failed to run with
/// its error (its rows are missing from the table).
pub fn summary(rows: &[ReportRow], failed: &[(String, String)]) -> Vec<String> {
    let mut cases: Vec<&str> = rows.iter().map(|r| r.case.as_str()).collect();
    cases.dedup();
    let n = |k: usize, one: &str, many: &str| format!("{k} {}", if k == 1 { one } else { many });
    let mut out = vec![format!(
        "{} of {} compared.",
        n(rows.len(), "quantity", "quantities"),
        n(cases.len(), "case", "cases")
    )];
    let largest = |who: &str, err: &dyn Fn(&ReportRow) -> Option<f64>| {
        let (e, r) = (rows.iter())
            .filter_map(|r| err(r).map(|e| (e, r)))
            .max_by(|a, b| a.0.total_cmp(&b.0))?;
        let (e, case, quantity) = (pct(e), &r.case, &r.quantity);
        Some(format!(
            "Largest {who} error: {e} % (case {case} {quantity})."
        ))
    };
    out.extend(largest("mbd", &|r| Some(r.error_pct)));
    out.extend(largest("RecurDyn", &|r| r.recurdyn_error_pct));
    out.extend(failed.iter().map(|(case, error)| failure(case, error)));
    out
}

/// The summary's sentence for a case that failed to run.
fn failure(case: &str, error: &str) -> String {
    format!("Case {case} FAILED and is not in the table: {error}")
}

/// Whether the row's reference is a corrected value (the manual's theory does not round to
/// it).
pub fn corrected(r: &ReportRow) -> bool {
    r.theory.is_some_and(|t| !rounds_to(r.reference, t))
}

/// Whether `exact` rounds to `printed` at `printed`'s own digits (its shortest decimal form):
/// a theory value that does not is a corrected one.
fn rounds_to(exact: f64, printed: f64) -> bool {
    let text = format!("{printed}");
    let decimals = text.split_once('.').map_or(0, |(_, d)| d.len());
    let half_unit = 0.5 * 10f64.powi(-(decimals as i32));
    (exact - printed).abs() <= half_unit * (1.0 + 1e-9)
}

fn table(rows: &[ReportRow]) -> String {
    let mut s = String::from(
        "<table><tr><th>quantity</th><th>unit</th><th>theory</th><th>RecurDyn</th>\
         <th>RecurDyn err %</th><th>mbd</th><th>mbd err %</th><th>method</th><th>case run time [µs]</th></tr>\n",
    );
    let opt = |v: Option<f64>| v.map_or_else(|| "–".to_string(), |v| format!("{v}"));
    for r in rows {
        let reference = if corrected(r) {
            format!(
                r#"<br><span class="corr">exact {}</span>"#,
                sig(r.reference, 7)
            )
        } else {
            String::new()
        };
        let _ = writeln!(
            s,
            "<tr><td>{}</td><td>{}</td><td>{}{reference}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"m\">{}</td><td>{}</td></tr>",
            esc(&r.quantity),
            esc(&r.unit),
            opt(r.theory),
            opt(r.recurdyn),
            r.recurdyn_error_pct.map_or_else(|| "–".to_string(), pct),
            sig(r.value, 7),
            pct(r.error_pct),
            esc(&r.method),
            sig(r.runtime_s * 1e6, 3),
        );
    }
    s.push_str("</table>\n");
    s
}

/// The animation's data as JSON: kinds and names once, then per frame `t` and the points;
/// the guides' paths and the ground pivots. The sketch's elements come first (drawn under
/// the model's); a body it draws through its joints replaces the bar of its inertia.
fn animation_json(a: &Animation) -> String {
    #[derive(Serialize)]
    struct Frame {
        t: f64,
        p: Vec<Vec<[f64; 3]>>,
    }
    #[derive(Serialize)]
    struct Data<'a> {
        kinds: Vec<&'static str>,
        names: Vec<&'static str>,
        frames: Vec<Frame>,
        stills: Vec<Frame>,
        guides: Vec<&'a [[f64; 3]]>,
        pivots: &'a [[f64; 3]],
    }
    let shown = |f: &crate::validation::Frame| -> Vec<(&'static str, &'static str, Vec<[f64; 3]>)> {
        let through = |n: &str| f.added.iter().any(|d| d.kind == Added::Body && d.name == n);
        let own = f.shapes.iter().filter(|s| !through(s.name));
        let added = f
            .added
            .iter()
            .map(|d| (d.kind.name(), d.name, d.points.clone()));
        added
            .chain(own.map(|s| (s.kind.name(), s.name, s.points.clone())))
            .collect()
    };
    let first = a.frames.first().map(shown).unwrap_or_default();
    let frames = |fs: &[crate::validation::Frame]| {
        fs.iter()
            .map(|f| Frame {
                t: f.t,
                p: shown(f).into_iter().map(|s| s.2).collect(),
            })
            .collect()
    };
    let data = Data {
        kinds: first.iter().map(|s| s.0).collect(),
        names: first.iter().map(|s| s.1).collect(),
        frames: frames(&a.frames),
        stills: frames(&a.stills),
        guides: a.guides.iter().map(|g| g.path.as_slice()).collect(),
        pivots: &a.pivots,
    };
    serde_json::to_string(&data).unwrap_or_else(|_| "null".into())
}

fn section(run: &CaseRun) -> String {
    let c = &run.case;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<section id=\"case{0}\"><h2>Case {0}: {1}</h2>\n<p class=\"ref\">{2}</p>",
        c.id,
        esc(c.title),
        inline(&c.summary())
    );
    s.push_str("<div class=\"figs\">");
    match &run.animation {
        Ok(a) if !a.frames.is_empty() => {
            let _ = write!(
                s,
                "<figure class=\"mech\"><svg viewBox=\"0 0 320 320\" width=\"320\" height=\"320\"></svg>\
                 <figcaption><button>pause</button> <span class=\"t\"></span></figcaption>\
                 <script type=\"application/json\">{}</script></figure>",
                animation_json(a).replace("</", "<\\/")
            );
        }
        Ok(_) => s.push_str("<p>(no frames)</p>"),
        Err(e) => {
            let _ = write!(s, "<p>Not drawn: {}</p>", esc(e));
        }
    }
    for (i, r) in run.rows.iter().enumerate() {
        match row_plot(run, i) {
            Ok(svg) => {
                let _ = write!(s, "<figure class=\"plot\">{svg}");
                if let Some(e) = off_curve(run, i) {
                    let _ = write!(s, "<figcaption class=\"corr\">{}</figcaption>", esc(&e));
                }
                s.push_str("</figure>");
            }
            Err(e) => {
                let _ = write!(s, "<p>No plot of {}: {}</p>", esc(&r.quantity), esc(&e));
            }
        }
    }
    s.push_str("</div>\n");
    s.push_str(&table(&run.rows));
    if let Some(d) = c.discrepancies() {
        let class = if d.starts_with("None") { "ok" } else { "wrong" };
        let _ = writeln!(
            s,
            "<p class=\"{class}\"><b>The manual:</b> {}</p>",
            inline(&d)
        );
    }
    s.push_str("</section>\n");
    s
}

/// The whole page; `failed` are the cases that did not run, with their errors (named under
/// the summary: they have no section).
pub fn html(runs: &[CaseRun], failed: &[(String, String)]) -> String {
    let mut s = String::from(HEAD);
    s.push_str("<h1>mbd validation report</h1>\n<p>Each case of the validation manual (30 textbook problems from Meriam &amp; Kraige, \
        <i>Engineering Mechanics: Dynamics</i>, 7th ed., each solved by hand and with the commercial code RecurDyn) \
        run with mbd: the theory and RecurDyn columns are the manual's; errors are relative to the exact value \
        (the manual's theory where it is right, else the corrected value its case documents, shown \
        under it), in percent (where the exact value is 0, the absolute value times 100). Every compared quantity is plotted from the case's own run (over time, or over the \
        parameter its axis names) with the theory, RecurDyn and mbd values marked where it is compared. The drawings come from each model's generated geometry (<code>#[mechanism(geometry)]</code>): \
        rigid bodies as the slender bar of their mass and inertia (or through their joints where they are not uniform bars), \
        massless links (light blue) between the points they join, springs as zigzags, named points as small circles, \
        points that never move as hatched pivots, guides along the paths of the points that run on them, \
        spatial models in an isometric projection; faint copies show the compared instants.</p>\n<nav>");
    for r in runs {
        let worst = r.rows.iter().map(|x| x.error_pct).fold(0.0, f64::max);
        let _ = write!(
            s,
            "<a href=\"#case{0}\" title=\"{1}\">{0}<small>{2}</small></a>",
            r.case.id,
            esc(r.case.title),
            pct(worst)
        );
    }
    s.push_str("</nav>\n<p class=\"small\">Under each case number: its largest mbd error, in percent.</p>\n");
    let rows: Vec<ReportRow> = runs.iter().flat_map(|r| r.rows.iter().cloned()).collect();
    let _ = writeln!(
        s,
        "<p class=\"ok\">{}</p>",
        esc(&summary(&rows, &[]).join(" "))
    );
    for (case, error) in failed {
        let _ = writeln!(s, "<p class=\"wrong\">{}</p>", esc(&failure(case, error)));
    }
    for r in runs {
        s.push_str(&section(r));
    }
    s.push_str(SCRIPT);
    s.push_str("</body></html>\n");
    s
}

const HEAD: &str = r##"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>mbd validation report</title>
<style>
body { font-family: sans-serif; max-width: 1100px; margin: 1em auto; color: #222; }
section { border-top: 1px solid #ccc; margin-top: 1.5em; }
.ref { color: #444; font-size: 0.92em; }
.figs { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; }
figure { margin: 0; }
.mech svg { border: 1px solid #ddd; background: #fcfcfc; }
/* Two plots a row (plotters' SVG has a viewBox: it scales). */
.plot svg { width: 540px; height: auto; }
figcaption { font-size: 0.85em; }
table { border-collapse: collapse; font-size: 0.9em; margin: 0.6em 0; }
td, th { border: 1px solid #ccc; padding: 2px 6px; text-align: right; }
td:first-child, th:first-child, td.m { text-align: left; }
td.m { font-size: 0.85em; color: #555; }
.corr { color: #b00; font-size: 0.85em; }
.wrong { background: #fff4e5; padding: 6px; border-left: 4px solid #e69f00; }
.ok { color: #555; font-size: 0.92em; }
nav a { display: inline-block; width: 4.2em; margin: 2px; padding: 2px; border: 1px solid #ccc; text-align: center; text-decoration: none; }
nav small { display: block; font-size: 0.7em; color: #555; }
.small { font-size: 0.85em; color: #555; }
[hidden] { display: none !important; }
body.drawings { max-width: none; }
body.drawings > :not(section):not(script), body.drawings section > :not(h2):not(.figs),
body.drawings figure.plot, body.drawings .figs > p { display: none; }
body.drawings section { display: inline-block; width: 330px; margin: 4px; border: none; vertical-align: top; }
body.drawings h2 { font-size: 0.8em; height: 2.4em; overflow: hidden; margin: 0; }
</style></head><body>
"##;

/// Draws and animates every `.mech` figure from its JSON: a shape per model element,
/// moved frame by frame (about five seconds a run), with the stills drawn faintly.
const SCRIPT: &str = r##"<script>
(function () {
  // `report.html?case=28` shows case 28 alone (for links and screenshots); `case=5` is
  // case 05, and a case the report does not have leaves the whole page shown.
  const query = new URLSearchParams(location.search);
  const only = (query.get("case") || "").trim().padStart(2, "0");
  if (document.getElementById("case" + only)) {
    document.querySelectorAll("body > *:not(script)").forEach(e => {
      e.hidden = e.id !== "case" + only;
    });
  }
  // `report.html?drawings`: every case's drawing alone, in a grid (to check them at a glance).
  if (query.has("drawings")) document.body.classList.add("drawings");
  // `report.html?at=0.5`: every drawing stopped at that fraction of its run (screenshots).
  const at = query.has("at") ? Math.min(1, Math.max(0, parseFloat(query.get("at")) || 0)) : null;
  const NS = "http://www.w3.org/2000/svg";
  function el(svg, tag, attrs) {
    const e = document.createElementNS(NS, tag);
    for (const k in attrs) e.setAttribute(k, attrs[k]);
    svg.appendChild(e);
    return e;
  }
  function zigzag(a, b, n, w) {
    const dx = b[0] - a[0], dy = b[1] - a[1], len = Math.hypot(dx, dy) || 1;
    const nx = -dy / len * w, ny = dx / len * w;
    const pts = [a];
    for (let i = 1; i < 2 * n; i++) {
      const f = i / (2 * n), s = i % 2 ? 1 : -1;
      pts.push([a[0] + dx * f + s * nx, a[1] + dy * f + s * ny]);
    }
    pts.push(b);
    return pts.map(p => p[0].toFixed(1) + "," + p[1].toFixed(1)).join(" ");
  }
  document.querySelectorAll("figure.mech").forEach(fig => {
    const data = JSON.parse(fig.querySelector("script").textContent);
    const svg = fig.querySelector("svg"), label = fig.querySelector(".t");
    // A spatial model (any z) is drawn in an isometric projection, z up.
    const all = data.frames.concat(data.stills);
    const spatial = all.some(f => f.p.some(s => s.some(p => Math.abs(p[2]) > 1e-12)));
    const c30 = Math.cos(Math.PI / 6), s30 = 0.5;
    const view = spatial ? p => [(p[1] - p[0]) * c30, p[2] - (p[0] + p[1]) * s30] : p => [p[0], p[1]];
    // A spatial body given by its axes' ends: a plate (two axes) as the disk they span
    // (its box half-lengths times 2/sqrt(3): a uniform disk's radius), with a spoke to show
    // its spin and its normal as an axle; a bar (one axis) as the bar.
    function body3(p) {
      const c = p[0], ax = p.slice(1).map(e => [e[0] - c[0], e[1] - c[1], e[2] - c[2]]);
      const len = a => Math.hypot(a[0], a[1], a[2]);
      const order = [0, 1, 2].sort((i, j) => len(ax[j]) - len(ax[i]));
      const [u, v] = [ax[order[0]], ax[order[1]]];
      const at = (a, k) => [c[0] + k * a[0], c[1] + k * a[1], c[2] + k * a[2]];
      if (len(v) <= 1e-6 * len(u)) return { rim: [at(u, -1), at(u, 1)], spoke: null, axle: null, c: c };
      const k = 2 / Math.sqrt(3), rim = [];
      for (let i = 0; i <= 36; i++) {
        const a = 2 * Math.PI * i / 36, cs = k * Math.cos(a), sn = k * Math.sin(a);
        rim.push([c[0] + cs * u[0] + sn * v[0], c[1] + cs * u[1] + sn * v[1], c[2] + cs * u[2] + sn * v[2]]);
      }
      const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
      const w = 0.5 * k * len(u) / (len(n) || 1);
      return { rim: rim, spoke: [c, at(u, k)], axle: [at(n, -w), at(n, w)], c: c };
    }
    const is3 = (kind, p) => spatial && kind === "rigid" && p.length === 4;
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    const grow = q => {
      const p = view(q);
      x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]); y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]);
    };
    for (const f of all) f.p.forEach((s, i) => {
      (is3(data.kinds[i], s) ? body3(s).rim.concat([s[0]]) : s).forEach(grow);
    });
    data.guides.forEach(g => g.forEach(grow));
    data.pivots.forEach(grow);
    const span = Math.max(x1 - x0, y1 - y0, 1e-9), k = 280 / span;
    const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
    const map = q => { const p = view(q); return [160 + (p[0] - cx) * k, 160 - (p[1] - cy) * k]; };
    const line = (e, a, b) => { e.setAttribute("x1", a[0]); e.setAttribute("y1", a[1]); e.setAttribute("x2", b[0]); e.setAttribute("y2", b[1]); };
    const pts = a => a.map(p => p[0].toFixed(1) + "," + p[1].toFixed(1)).join(" ");
    const RIGID = ["#0072b2", "#e69f00", "#6a3d9a", "#0097a7"];
    const colours = { rigid: "#0072b2", link: "#0072b2", body: "#0072b2", bar: "#56b4e9", particle: "#d55e00", point: "#555", spring: "#009e73", damper: "#cc79a7" };
    // Ground: each guide along its point's path (extended a little at both ends, hatched
    // on its lower side, or its left where it is vertical), each pivot as a hatched wedge.
    const ground = el(svg, "g", { stroke: "#777", "stroke-width": 1.2, fill: "none" });
    data.guides.forEach(g => {
      const s = [];
      g.map(map).forEach(p => { if (!s.length || Math.hypot(p[0] - s[s.length - 1][0], p[1] - s[s.length - 1][1]) > 1) s.push(p); });
      if (s.length < 2) return;
      const ext = (a, b) => { const d = Math.hypot(a[0] - b[0], a[1] - b[1]); return [a[0] + (a[0] - b[0]) / d * 25, a[1] + (a[1] - b[1]) / d * 25]; };
      s.unshift(ext(s[0], s[1])); s.push(ext(s[s.length - 1], s[s.length - 2]));
      el(ground, "polyline", { points: pts(s), "stroke-width": 2 });
      // A hatch every 9 px of the path (`next`: the arc length of the next one).
      // One side for the whole guide: below its chord (left of a vertical one).
      const cx = s[s.length - 1][0] - s[0][0], cy = s[s.length - 1][1] - s[0][1];
      const side = cx > 1e-6 * Math.abs(cy) || (Math.abs(cx) <= 1e-6 * Math.abs(cy) && cy > 0) ? 1 : -1;
      let next = 0, walked = 0;
      for (let j = 1; j < s.length; j++) {
        const a = s[j - 1], b = s[j], d = Math.hypot(b[0] - a[0], b[1] - a[1]);
        const nx = -side * (b[1] - a[1]) / d, ny = side * (b[0] - a[0]) / d;
        for (; next < walked + d; next += 9) {
          const u = (next - walked) / d, x = a[0] + (b[0] - a[0]) * u, y = a[1] + (b[1] - a[1]) * u;
          el(ground, "line", { x1: x + nx * 2, y1: y + ny * 2, x2: x + nx * 8 - ny * 5, y2: y + ny * 8 + nx * 5 });
        }
        walked += d;
      }
    });
    data.pivots.forEach(q => {
      const [x, y] = map(q);
      el(ground, "polygon", { points: pts([[x, y], [x - 7, y + 11], [x + 7, y + 11]]), fill: "#ddd" });
      for (let u = -9; u <= 9; u += 4.5) el(ground, "line", { x1: x + u, y1: y + 11, x2: x + u - 4, y2: y + 16 });
    });
    function build(opacity) {
      const g = el(svg, "g", { opacity: opacity });
      let bodies = 0;
      return data.kinds.map((kind, i) => {
        // Rigid bodies in turns of colour, so that a slider on a link stands out.
        const c = kind === "rigid" || kind === "body" ? RIGID[bodies++ % RIGID.length] : colours[kind] || "#000";
        if (kind === "spring") return [el(g, "polyline", { fill: "none", stroke: c, "stroke-width": 1.5 })];
        if (kind === "damper") return [el(g, "line", { stroke: c, "stroke-width": 5, "stroke-dasharray": "2 2" })];
        if (kind === "point") return [el(g, "circle", { r: 3, fill: "#fff", stroke: c, "stroke-width": 1.5 })];
        if (kind === "bar") return [el(g, "line", { stroke: c, "stroke-width": 3.5, "stroke-linecap": "round" }),
          el(g, "circle", { r: 3, fill: "#fff", stroke: "#000" }), el(g, "circle", { r: 3, fill: "#fff", stroke: "#000" })];
        if (kind === "body") return [el(g, "polygon", { fill: c, "fill-opacity": 0.3, stroke: c, "stroke-width": 6, "stroke-linejoin": "round" }),
          el(g, "circle", { r: 3, fill: "#fff", stroke: "#000" })].concat(
          data.frames[0].p[i].slice(1).map(() => el(g, "circle", { r: 3, fill: "#fff", stroke: "#000" })));
        if (kind === "particle") return [el(g, "circle", { r: 6, fill: c })];
        if (kind === "link") return [el(g, "line", { stroke: "#999", "stroke-width": 1 }),
          el(g, "line", { stroke: c, "stroke-width": 5, "stroke-linecap": "round" }),
          el(g, "circle", { r: 3.5, fill: "#fff", stroke: "#000" })];
        if (is3(kind, data.frames[0].p[i])) return [
          el(g, "polygon", { fill: c, "fill-opacity": 0.25, stroke: c, "stroke-width": 2.5, "stroke-linejoin": "round" }),
          el(g, "line", { stroke: c, "stroke-width": 2 }), el(g, "line", { stroke: "#555", "stroke-width": 1.5 }),
          el(g, "circle", { r: 3, fill: "#fff", stroke: "#000" })];
        return [el(g, "line", { stroke: c, "stroke-width": 6, "stroke-linecap": "round" }),
          el(g, "circle", { r: 3, fill: "#fff", stroke: "#000" })];
      });
    }
    function place(shapes, frame) {
      shapes.forEach((parts, i) => {
        const p = frame.p[i].map(map), kind = data.kinds[i];
        if (is3(kind, frame.p[i])) {
          const b = body3(frame.p[i]);
          parts[0].setAttribute("points", pts(b.rim.map(map)));
          parts[0].setAttribute("stroke-width", b.spoke ? 2.5 : 6);
          if (b.spoke) { line(parts[1], map(b.spoke[0]), map(b.spoke[1])); line(parts[2], map(b.axle[0]), map(b.axle[1])); }
          parts[3].setAttribute("cx", p[0][0]); parts[3].setAttribute("cy", p[0][1]);
          return;
        }
        if (kind === "spring") {
          const [a, b] = beside(p, apart[i]), len = Math.hypot(b[0] - a[0], b[1] - a[1]);
          parts[0].setAttribute("points", zigzag(a, b, Math.max(3, Math.round(len / 10)), 5));
        }
        else if (kind === "damper") { const [a, b] = beside(p, apart[i]); line(parts[0], a, b); }
        else if (kind === "point") { parts[0].setAttribute("cx", p[0][0]); parts[0].setAttribute("cy", p[0][1]); }
        else if (kind === "bar") {
          line(parts[0], p[0], p[1]);
          [1, 2].forEach(j => { parts[j].setAttribute("cx", p[j - 1][0]); parts[j].setAttribute("cy", p[j - 1][1]); });
        } else if (kind === "body") {
          // Its joints, then back through its mass centre (a line where the centre is on it).
          parts[0].setAttribute("points", pts(p.slice(1).concat([p[0]])));
          p.forEach((q, j) => { parts[j + 1].setAttribute("cx", q[0]); parts[j + 1].setAttribute("cy", q[1]); });
        }
        else if (kind === "particle") { parts[0].setAttribute("cx", p[0][0]); parts[0].setAttribute("cy", p[0][1]); }
        else if (kind === "link") {
          const set = (e, a, b) => { e.setAttribute("x1", a[0]); e.setAttribute("y1", a[1]); e.setAttribute("x2", b[0]); e.setAttribute("y2", b[1]); };
          set(parts[0], p[0], p[1]); set(parts[1], p[1], p[3]);
          parts[2].setAttribute("cx", p[1][0]); parts[2].setAttribute("cy", p[1][1]);
        } else {
          const a = p.length > 2 ? p[1] : p[0], b = p.length > 2 ? p[2] : p[0];
          parts[0].setAttribute("x1", a[0]); parts[0].setAttribute("y1", a[1]);
          parts[0].setAttribute("x2", b[0]); parts[0].setAttribute("y2", b[1]);
          parts[1].setAttribute("cx", p[0][0]); parts[1].setAttribute("cy", p[0][1]);
        }
      });
    }
    // A spring and a damper between the same two points are drawn side by side, 7 px apart.
    const same = (a, b) => a.every((q, j) => q.every((x, k) => Math.abs(x - b[j][k]) <= 1e-12));
    const f0 = data.frames[0].p;
    const apart = data.kinds.map((kind, i) => {
      const other = kind === "spring" ? "damper" : kind === "damper" ? "spring" : null;
      const pair = other && data.kinds.some((k, j) => k === other && same(f0[i], f0[j]));
      return pair ? (kind === "spring" ? -7 : 7) : 0;
    });
    function beside(p, o) {
      const dx = p[1][0] - p[0][0], dy = p[1][1] - p[0][1], d = Math.hypot(dx, dy) || 1;
      return p.map(q => [q[0] - dy / d * o, q[1] + dx / d * o]);
    }
    // A roller where a guided point is (under the shapes: a particle covers it).
    const rollers = data.guides.map(() => el(svg, "circle", { r: 5, fill: "#fff", stroke: "#777", "stroke-width": 1.5 }));
    data.stills.forEach(f => place(build(0.3), f));
    const live = build(1);
    const n = data.frames.length;
    let i = at === null ? 0 : Math.round(at * (n - 1)), playing = at === null, last = 0;
    function show() {
      place(live, data.frames[i]);
      data.guides.forEach((g, j) => { const q = map(g[i]); rollers[j].setAttribute("cx", q[0]); rollers[j].setAttribute("cy", q[1]); });
      label.textContent = "t = " + data.frames[i].t.toPrecision(4) + " s";
    }
    show();
    if (!playing) fig.querySelector("button").textContent = "play";
    fig.querySelector("button").onclick = e => { playing = !playing; e.target.textContent = playing ? "pause" : "play"; };
    function tick(now) {
      if (playing && now - last > 5000 / n) { i = (i + 1) % n; show(); last = now; }
      requestAnimationFrame(tick);
    }
    requestAnimationFrame(tick);
  });
})();
</script>
"##;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_figures() {
        assert_eq!(sig(0.910158253959, 7), "0.9101583");
        assert_eq!(sig(74.04721448, 7), "74.04721");
        assert_eq!(sig(1714.0, 4), "1714");
        assert_eq!(sig(-0.0489, 3), "-0.0489");
        assert_eq!(sig(1.5e-7, 2), "1.5e-7");
        assert_eq!(pct(1.23e-8), "1.2e-8");
        assert_eq!(pct(1.0449), "1");
        assert_eq!(pct(0.012), "0.012");
        assert!(rounds_to(0.2142857, 0.214));
        assert!(!rounds_to(0.9101583, 0.909));
        assert!(rounds_to(1714.4, 1714.0));
        assert!(!rounds_to(74.047, 73.79));
    }
}

//! The reproduction report: one self-contained HTML page (figures inlined as SVG, no
//! script, no request: a Content-Security-Policy of `default-src 'none'`) that shows what
//! a pipeline reproduces. At the top, the claims verdict and the table of every claim; then
//! a section per chapter with each figure under its thesis number and caption, the claims
//! that read the tables it draws, and its provenance (code version, task key); then the
//! last run's cost per stage and its timeline, the stage graph, and the provenance of the
//! whole (repro version, the pipeline file's hash, the git commit when there is one).
//!
//! It reads what a run leaves behind: the pipeline file, the published figures and
//! `claims` table, and the record of the run that produced them (the latest run of the
//! pipeline file without `-S` settings, from `cache/runs/`).
//!
//! One file: the page's sections share one model of the run.

use crate::stages::claim::ClaimParams;
use anyhow::{Context, Result};
use pipeline::cache::read_regular;
use pipeline::report::{RunReport, Status};
use pipeline::spec::Pipeline;
use polars::prelude::{DataFrame, DataType};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Where the report's inputs are.
pub struct Sources {
    pub pipeline_file: PathBuf,
    pub figures_dir: PathBuf,
    pub tables_dir: PathBuf,
    /// The record of the run whose cost and timeline the report shows (`cache/runs/run-*.json`);
    /// absent: no cost or timeline section.
    pub run_report: Option<PathBuf>,
}

/// One claim's row of the `claims` table.
#[derive(Clone, Debug)]
struct ClaimRow {
    id: String,
    source: String,
    statement: String,
    stage: String,
    aggregate: String,
    value: f64,
    thesis: String,
    independent: Option<(f64, String)>,
    verdict: String,
    expected: String,
    reason: String,
    docs: String,
    /// What is compared (`claim::Quantity::describe`).
    quantity: String,
}

/// The verdict of a claim that the run did not evaluate.
const NOT_RUN: &str = "not run";

/// The chapter of a claim id ("ch3.k_7_5" -> 3; Appendix A after Chapter 5), for the
/// thesis' order.
fn claim_chapter(id: &str) -> u32 {
    match id.split('.').next().unwrap_or("") {
        "appA" => 7,
        ch => ch.strip_prefix("ch").and_then(|n| n.parse().ok()).unwrap_or(99),
    }
}

/// Every claim of the pipeline, in the thesis' order (by chapter, then as the file lists
/// them): its row of the claims table where the run evaluated it, else a row `not run`
/// built from its parameters.
fn pipeline_claims(p: &Pipeline, table: Vec<ClaimRow>) -> Vec<ClaimRow> {
    let mut rows: Vec<ClaimRow> = p
        .stages
        .iter()
        .filter(|st| st.kind == "claim")
        .filter_map(|st| serde_json::from_value::<ClaimParams>(st.points.first()?.params.clone()).ok())
        .map(|c| {
            let quantity = c.quantity.describe();
            match table.iter().find(|r| r.id == c.id) {
                Some(r) => ClaimRow { quantity, ..r.clone() },
                None => ClaimRow {
                    id: c.id.clone(),
                    source: c.source.clone(),
                    statement: c.statement.clone(),
                    stage: c.quantity.from.clone(),
                    aggregate: serde_json::to_value(c.quantity.aggregate)
                        .ok()
                        .and_then(|v| v.as_str().map(str::to_string))
                        .unwrap_or_default(),
                    value: f64::NAN,
                    thesis: c.thesis.describe(),
                    independent: None,
                    verdict: NOT_RUN.into(),
                    expected: serde_json::to_value(c.expect)
                        .ok()
                        .and_then(|v| v.as_str().map(str::to_string))
                        .unwrap_or_default(),
                    reason: c.reason.clone(),
                    docs: c.docs.clone(),
                    quantity,
                },
            }
        })
        .collect();
    rows.sort_by_key(|r| claim_chapter(&r.id));
    rows
}

fn strings(df: &DataFrame, name: &str) -> Result<Vec<String>> {
    let c = df.column(name).with_context(|| format!("column `{name}`"))?;
    Ok(c.str()?.iter().map(|s| s.unwrap_or_default().to_string()).collect())
}

fn numbers(df: &DataFrame, name: &str) -> Result<Vec<f64>> {
    let c = df.column(name).with_context(|| format!("column `{name}`"))?.cast(&DataType::Float64)?;
    Ok(c.f64()?.into_no_null_iter().collect())
}

fn read_claims(path: &Path) -> Result<Vec<ClaimRow>> {
    let df = pipeline::table::read_parquet(path)?;
    let (id, source, statement, stage) =
        (strings(&df, "id")?, strings(&df, "source")?, strings(&df, "statement")?, strings(&df, "stage")?);
    let (value, thesis, verdict, expected) =
        (numbers(&df, "value")?, strings(&df, "thesis")?, strings(&df, "verdict")?, strings(&df, "expected")?);
    let (has_ind, ind_value, ind_source) =
        (numbers(&df, "has_independent")?, numbers(&df, "independent_value")?, strings(&df, "independent_source")?);
    let (reason, docs, aggregate) = (strings(&df, "reason")?, strings(&df, "docs")?, strings(&df, "aggregate")?);
    Ok((0..df.height())
        .map(|i| ClaimRow {
            id: id[i].clone(),
            source: source[i].clone(),
            statement: statement[i].clone(),
            stage: stage[i].clone(),
            aggregate: aggregate[i].clone(),
            value: value[i],
            thesis: thesis[i].clone(),
            independent: (has_ind[i] != 0.0).then(|| (ind_value[i], ind_source[i].clone())),
            verdict: verdict[i].clone(),
            expected: expected[i].clone(),
            reason: reason[i].clone(),
            docs: docs[i].clone(),
            quantity: String::new(),
        })
        .collect())
}

/// The text of an SVG's `<title>` element, unescaped.
fn svg_title(svg: &str) -> Option<String> {
    let start = svg.find("<title>")? + "<title>".len();
    let end = start + svg[start..].find("</title>")?;
    Some(svg[start..end].replace("&lt;", "<").replace("&gt;", ">").replace("&amp;", "&"))
}

/// Text for HTML.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// A number to 6 significant digits (scientific notation below 1e-3 and from 1e6 on).
fn number(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || !a.is_finite() {
        return pipeline::table::format_number(x);
    }
    if !(1e-3..1e6).contains(&a) {
        return format!("{x:.5e}");
    }
    let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
    let t = format!("{x:.decimals$}");
    if t.contains('.') {
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        t
    }
}

/// The task key of a published figure (its table's `task_key` column).
fn figure_key(figures_dir: &Path, name: &str) -> Option<String> {
    let df = pipeline::table::read_parquet(&figures_dir.join(format!("{name}.parquet"))).ok()?;
    strings(&df, "task_key").ok()?.into_iter().next()
}

/// The chapter a figure title belongs to: "Fig. 3.2: ..." -> "3"; Appendix A is the thesis'
/// Chapter 7 of figures (Figs. 7.3-7.4).
fn chapter_of(title: &str) -> String {
    let Some(rest) = title.strip_prefix("Fig. ") else { return "other".into() };
    let ch: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
    if ch.is_empty() {
        "other".into()
    } else {
        ch
    }
}

/// A figure's place in its chapter from its title: "Fig. 3.5 (b)" and "Fig. 3.5b" -> (5, "b");
/// no number: last.
fn figure_number(title: &str) -> (u32, String) {
    let Some(rest) = title.strip_prefix("Fig. ") else { return (u32::MAX, String::new()) };
    let rest = rest.trim_start_matches(|c: char| c.is_ascii_digit()).strip_prefix('.').unwrap_or("");
    let number: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
    let letter: String =
        rest[number.len()..].trim_start_matches([' ', '(']).chars().take_while(|c| c.is_ascii_lowercase()).collect();
    (number.parse().unwrap_or(u32::MAX), letter)
}

fn chapter_heading(ch: &str) -> &'static str {
    match ch {
        "2" => "Chapter 2: adhesion theories (JKR, DMT, Maugis)",
        "3" => "Chapter 3: a hemispherical shell pressed by a plate, adhesion and friction",
        "4" => "Chapter 4: friction of an adhesive cylinder sliding on a viscoelastic half-plane",
        "5" => "Chapter 5: rolling on and under a viscoelastic substrate, Persson-Brener",
        "7" => "Appendix A: Persson's adhesionless friction",
        _ => "Further figures (not in the thesis: checks, limits, extensions)",
    }
}

/// The stages a stage reads, directly or through others.
fn ancestors(p: &Pipeline, name: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut todo = vec![name.to_string()];
    while let Some(n) = todo.pop() {
        if let Some(s) = p.stage(&n) {
            for d in &s.needs {
                if seen.insert(d.clone()) {
                    todo.push(d.clone());
                }
            }
        }
    }
    seen
}

const STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}\
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}\
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}td,th{border:1px solid #ddd;padding:.2em .5em;vertical-align:top}\
th{background:#f4f4f4}.reproduced{color:#176b2c;font-weight:600}.differs{color:#9a5b00;font-weight:600}.calibrated{color:#555;font-weight:600}\
.regressed{color:#b00020;font-weight:700}figure{margin:1.5em 0;border:1px solid #eee;padding:.5em}\
figure svg{max-width:100%;height:auto}figcaption{font-size:.9em;color:#444}.summary{font-size:1.2em;padding:.6em;background:#f6f8fa}\
.small{font-size:.8em;color:#555}nav a{margin-right:1em}.notrun{color:#777;font-style:italic}";

fn verdict_cell(c: &ClaimRow) -> String {
    if c.verdict == NOT_RUN {
        return format!("<td class=\"notrun\">{NOT_RUN}</td>");
    }
    let class = if c.verdict == "reproduced" || c.verdict == "calibrated" {
        if c.verdict == "calibrated" {
            "calibrated"
        } else {
            "reproduced"
        }
    } else if c.expected == "differs" {
        "differs"
    } else {
        "regressed"
    };
    let label = if class == "regressed" { "differs (regression)" } else { c.verdict.as_str() };
    format!("<td class=\"{class}\">{label}</td>")
}

/// A monotonicity claim's 1 or 0 as yes or no, on both sides of the comparison.
fn yes_no(c: &ClaimRow, x: f64) -> Option<String> {
    matches!(c.aggregate.as_str(), "increasing" | "decreasing")
        .then(|| format!("{} ({})", if x == 1.0 { "yes" } else { "no" }, c.aggregate))
}

/// The measured value: a number, or for a monotonicity claim whether it holds; nothing
/// for a claim not run.
fn shown_value(c: &ClaimRow) -> String {
    if c.verdict == NOT_RUN {
        return String::new();
    }
    yes_no(c, c.value).unwrap_or_else(|| number(c.value))
}

/// The thesis' side, read as the measured side is.
fn shown_thesis(c: &ClaimRow) -> String {
    c.thesis.parse::<f64>().ok().and_then(|x| yes_no(c, x)).unwrap_or_else(|| esc(&c.thesis))
}

/// The claims as a table; `ids`: the rows carry the claims' ids (the page's one table of
/// every claim; the tables under the figures repeat rows without them, so ids stay unique).
fn claims_table(claims: &[&ClaimRow], ids: bool) -> String {
    let mut s = String::from(
        "<table class=\"claims\"><tr><th>claim</th><th>where</th><th>statement</th><th>quantity compared</th><th>thesis</th><th>repro</th>\
         <th>independent</th><th>verdict</th><th>why it differs</th></tr>\n",
    );
    for c in claims {
        let independent = c
            .independent
            .as_ref()
            .map_or(String::new(), |(v, src)| format!("{} <span class=\"small\">({})</span>", number(*v), esc(src)));
        let why = if c.docs.is_empty() {
            esc(&c.reason)
        } else {
            format!("{} <span class=\"small\">({})</span>", esc(&c.reason), esc(&c.docs))
        };
        let row_id = if ids { format!(" id=\"claim-{}\"", esc(&c.id)) } else { String::new() };
        let _ = writeln!(
            s,
            "<tr{row_id}><td><code>{id}</code></td><td>{}</td><td>{}</td><td class=\"small\">{}</td><td>{}</td><td>{}</td><td>{independent}</td>{}<td>{why}</td></tr>",
            esc(&c.source),
            esc(&c.statement),
            esc(&c.quantity),
            shown_thesis(c),
            shown_value(c),
            verdict_cell(c),
            id = esc(&c.id),
        );
    }
    s.push_str("</table>\n");
    s
}

/// The pipeline's claims with the verdicts of the last run that evaluated them: the claims
/// table where it exists; after a run of some targets only, the claims it did not reach are
/// `not run`. An error when the run left nothing to show (no claims table, no figure).
fn load_claims(p: &Pipeline, src: &Sources) -> Result<Vec<ClaimRow>> {
    let claims_stage = p.stages.iter().find(|s| s.kind == "claims").map(|s| s.name.clone());
    let table: Vec<ClaimRow> = match &claims_stage {
        Some(name) => {
            let path = src.tables_dir.join(format!("{name}.parquet"));
            if path.exists() {
                read_claims(&path).with_context(|| format!("reading the claims table {}", path.display()))?
            } else {
                Vec::new()
            }
        }
        None => Vec::new(),
    };
    let any_figure =
        p.stages.iter().any(|s| s.kind == "figure" && src.figures_dir.join(format!("{}.svg", s.name)).exists());
    if table.is_empty() && !any_figure {
        anyhow::bail!(
            "no figure of {} in {} and no claims table in {} (run the pipeline first)",
            src.pipeline_file.display(),
            src.figures_dir.display(),
            src.tables_dir.display()
        );
    }
    Ok(pipeline_claims(p, table))
}

/// Writes the report; returns the number of figures and claims it shows.
pub fn write(p: &Pipeline, code_versions: &BTreeMap<String, u32>, src: &Sources, out: &Path) -> Result<(usize, usize)> {
    let claims = load_claims(p, src)?;
    let run: Option<RunReport> = match &src.run_report {
        Some(path) if path.exists() => {
            Some(serde_json::from_slice(&read_regular(path)?).with_context(|| format!("reading {}", path.display()))?)
        }
        _ => None,
    };
    let pipeline_bytes = read_regular(&src.pipeline_file)?;
    let dir = src.pipeline_file.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let (commit, dirty) = match pipeline::report::git_commit(dir) {
        Some((c, modified)) => (Some(c), modified),
        None => (None, false),
    };

    let mut h = String::new();
    h.push_str("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n");
    h.push_str("<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'; img-src data:\">\n");
    h.push_str("<title>repro: reproduction report</title>\n");
    let _ = writeln!(h, "<style>{STYLE}</style></head><body>");
    h.push_str("<h1>Reproduction report</h1>\n<p>Roohollah Nazari, <i>Adhesion and Friction Effects in Soft Contact Mechanics: From Shell Buckling to Viscoelastic Rolling</i>, PhD thesis, Politecnico di Bari, 2025, reproduced by <code>repro</code> from its own code.</p>\n");

    // Claims.
    let n = claims.len();
    let reproduced = claims.iter().filter(|c| c.verdict == "reproduced").count();
    let calibrated = claims.iter().filter(|c| c.verdict == "calibrated").count();
    let explained = claims.iter().filter(|c| c.verdict == "differs" && c.expected == "differs").count();
    let not_run = claims.iter().filter(|c| c.verdict == NOT_RUN).count();
    let regressed = n - reproduced - calibrated - explained - not_run;
    let figures: Vec<_> = p.stages.iter().filter(|s| s.kind == "figure").collect();
    let mut chapters: BTreeMap<String, Vec<_>> = BTreeMap::new();
    for f in &figures {
        let title = f.points.first().and_then(|pt| pt.params["title"].as_str()).unwrap_or(&f.name).to_string();
        chapters.entry(chapter_of(&title)).or_default().push((f, title));
    }
    // In the thesis' order within each chapter (3.2 before 3.3a), figures without a number
    // after those with one, as the file lists them.
    for list in chapters.values_mut() {
        list.sort_by_key(|(_, title)| figure_number(title));
    }
    let order = ["2", "3", "4", "5", "7", "other"];
    h.push_str("<nav>");
    h.push_str("<a href=\"#claims\">Claims</a>");
    for ch in order.iter().filter(|c| chapters.contains_key(**c)) {
        let _ = write!(
            h,
            "<a href=\"#chapter-{ch}\">{}</a>",
            if *ch == "7" {
                "App. A".to_string()
            } else if *ch == "other" {
                "Further".into()
            } else {
                format!("Ch. {ch}")
            }
        );
    }
    h.push_str("<a href=\"#cost\">Cost</a><a href=\"#graph\">Stages</a><a href=\"#provenance\">Provenance</a></nav>\n");
    let _ = writeln!(
        h,
        "<p class=\"summary\" id=\"verdict\">{reproduced} of {n} thesis claims reproduced, {}{explained} differ (explained){}{}.</p>",
        if calibrated > 0 { format!("{calibrated} calibrated (the model tuned to them), ") } else { String::new() },
        if regressed > 0 { format!(", <span class=\"regressed\">{regressed} regressed</span>") } else { String::new() },
        if not_run > 0 { format!(", {not_run} not run (the last run did not reach them)") } else { String::new() }
    );
    h.push_str("<h2 id=\"claims\">The thesis' claims</h2>\n<p>Each claim is a stage of the pipeline that reads a published table; the verdict compares the quantity with the thesis' value and the tolerance its text implies. A claim that differs carries its reason.</p>\n");
    h.push_str(&claims_table(&claims.iter().collect::<Vec<_>>(), true));

    // Chapters.
    let mut shown = 0;
    for ch in order.iter().filter(|c| chapters.contains_key(**c)) {
        let _ = writeln!(h, "<h2 id=\"chapter-{ch}\">{}</h2>", chapter_heading(ch));
        for (f, title) in &chapters[*ch] {
            let svg_path = src.figures_dir.join(format!("{}.svg", f.name));
            if !svg_path.exists() {
                let _ = writeln!(
                    h,
                    "<figure id=\"figure-{name}\"><figcaption><b>{}</b><br><span class=\"small notrun\">not produced: the last run did not reach it (<code>repro run --target {name}</code>)</span></figcaption></figure>",
                    esc(title),
                    name = esc(&f.name),
                );
                continue;
            }
            let svg = read_regular(&svg_path)
                .map(|b| String::from_utf8_lossy(&b).into_owned())
                .with_context(|| format!("reading {}", svg_path.display()))?;
            let svg = svg.trim_start_matches(|c| c != '<');
            let svg = match svg.find("<svg") {
                Some(i) => &svg[i..],
                None => svg,
            };
            // The title as drawn (its `{column}`s filled in), else as written.
            let drawn = svg_title(svg);
            let title = drawn.as_deref().unwrap_or(title);
            let up = ancestors(p, &f.name);
            let bearing: Vec<&ClaimRow> = claims.iter().filter(|c| up.contains(&c.stage)).collect();
            let key = figure_key(&src.figures_dir, &f.name).unwrap_or_else(|| "(not published)".into());
            // The code behind it: every stage it reads, directly or not, with its kind's version.
            let lineage: Vec<String> = up
                .iter()
                .filter_map(|n| p.stage(n))
                .map(|st| format!("{} ({}@v{})", st.name, st.kind, code_versions.get(&st.kind).copied().unwrap_or(0)))
                .collect();
            let _ = writeln!(
                h,
                "<figure id=\"figure-{name}\">{svg}<figcaption><b>{}</b><br><span class=\"small\">figures/{name}.svg, data figures/{name}.parquet; figure@v{}; task key <code>{}</code>; computed from {}</span></figcaption>",
                esc(title),
                code_versions.get("figure").copied().unwrap_or(0),
                esc(&key),
                esc(&lineage.join(", ")),
                name = esc(&f.name),
            );
            if !bearing.is_empty() {
                h.push_str(&claims_table(&bearing, false));
            }
            h.push_str("</figure>\n");
            shown += 1;
        }
    }

    h.push_str(&cost_section(run.as_ref()));
    h.push_str(&stages_section(p, code_versions));
    h.push_str(&provenance_section(src, &pipeline_bytes, commit, dirty));
    h.push_str("</body></html>\n");

    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    let tmp = out.with_extension("html.tmp");
    std::fs::write(&tmp, h).with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, out).with_context(|| format!("writing {}", out.display()))?;
    Ok((shown, n))
}

/// The report's cost section: the run's tasks computed, cached and failed, the task time
/// per stage and the timeline.
fn cost_section(run: Option<&RunReport>) -> String {
    let mut h = String::new();
    h.push_str("<h2 id=\"cost\">Cost of the run</h2>\n");
    match run {
        None => h.push_str("<p>No recorded run of this pipeline file.</p>\n"),
        Some(r) => {
            let computed = r.count(Status::Computed);
            let _ = writeln!(
                h,
                "<p>The latest run of <code>{}</code> without settings, started {}: {} tasks: {computed} computed, {} from the cache, {} failed; {:.1} s of wall time.</p>",
                esc(&r.pipeline),
                pipeline::report::utc_time(r.started_unix_ms),
                r.tasks.len(),
                r.count(Status::Cached),
                r.count(Status::Failed),
                r.wall_time_s
            );
            let mut per_stage: BTreeMap<&str, (usize, usize, f64)> = BTreeMap::new();
            for t in &r.tasks {
                let e = per_stage.entry(&t.stage).or_default();
                match t.status {
                    Status::Computed => {
                        e.0 += 1;
                        e.2 += t.wall_time_s;
                    }
                    _ => e.1 += 1,
                }
            }
            let mut rows: Vec<_> = per_stage.into_iter().filter(|(_, v)| v.0 > 0).collect();
            rows.sort_by(|a, b| b.1 .2.total_cmp(&a.1 .2));
            if rows.is_empty() {
                h.push_str("<p>Every task came from the cache.</p>\n");
            } else {
                h.push_str("<table><tr><th>stage</th><th>computed</th><th>cached</th><th>task time (s)</th></tr>\n");
                for (stage, (c, k, t)) in &rows {
                    let _ = writeln!(h, "<tr><td>{}</td><td>{c}</td><td>{k}</td><td>{t:.2}</td></tr>", esc(stage));
                }
                h.push_str("</table>\n");
                h.push_str(&timeline(r));
            }
        }
    }

    h
}

/// The report's stage graph and the table of every stage (kind, code version, what it reads).
fn stages_section(p: &Pipeline, code_versions: &BTreeMap<String, u32>) -> String {
    let mut h = String::new();
    h.push_str("<h2 id=\"graph\">Stages</h2>\n");
    let title = |f: &pipeline::spec::Stage| {
        chapter_of(f.points.first().and_then(|pt| pt.params["title"].as_str()).unwrap_or(&f.name))
    };
    h.push_str(&crate::stage_graph::panels(p, &["2", "3", "4", "5", "7"], title, chapter_heading));
    h.push_str("<details><summary>");
    let _ = write!(h, "{} stages of {} (kind, code version, what each reads)", p.stages.len(), esc(&p.file));
    h.push_str("</summary><table><tr><th>stage</th><th>kind</th><th>points</th><th>reads</th></tr>\n");
    for s in &p.stages {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}@v{}</td><td>{}</td><td>{}</td></tr>",
            esc(&s.name),
            esc(&s.kind),
            code_versions.get(&s.kind).copied().unwrap_or(0),
            s.points.len(),
            esc(&s.needs.join(", "))
        );
    }
    h.push_str("</table></details>\n");

    h
}

/// The report's provenance: repro's version, the pipeline file and its hash, the git commit.
fn provenance_section(src: &Sources, pipeline_bytes: &[u8], commit: Option<String>, dirty: bool) -> String {
    let mut h = String::new();
    h.push_str("<h2 id=\"provenance\">Provenance</h2>\n<table>");
    let _ = writeln!(h, "<tr><th>repro</th><td>{}</td></tr>", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(
        h,
        "<tr><th>pipeline</th><td>{} (blake3 {})</td></tr>",
        esc(&src.pipeline_file.display().to_string()),
        blake3::hash(pipeline_bytes).to_hex()
    );
    let _ = writeln!(
        h,
        "<tr><th>git commit</th><td>{}</td></tr>",
        commit.map_or("not a git checkout".to_string(), |c| format!(
            "{c}{}",
            if dirty { " (with uncommitted changes)" } else { "" }
        ))
    );
    h.push_str("</table>\n");
    h
}

/// The run's timeline: one bar per computed task (start to end), a row per stage, as SVG.
fn timeline(r: &RunReport) -> String {
    let tasks: Vec<_> = r.tasks.iter().filter(|t| t.status == Status::Computed && t.started_s.is_some()).collect();
    if tasks.is_empty() {
        return "<p>No timeline: the computed tasks ran elsewhere (SLURM) or before timing was recorded.</p>\n".into();
    }
    let mut stages: Vec<&str> = Vec::new();
    for t in &tasks {
        if !stages.contains(&t.stage.as_str()) {
            stages.push(&t.stage);
        }
    }
    let end = tasks.iter().map(|t| t.started_s.unwrap() + t.wall_time_s).fold(0.0f64, f64::max).max(1e-9);
    let (left, width, row) = (170.0, 880.0, 14.0);
    let height = row * stages.len() as f64 + 30.0;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"timeline\" width=\"{}\" height=\"{height}\" viewBox=\"0 0 {} {height}\" font-size=\"10\">\n",
        left + width + 10.0,
        left + width + 10.0
    );
    for (i, st) in stages.iter().enumerate() {
        let y = i as f64 * row;
        let _ = writeln!(s, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>", left - 4.0, y + 10.0, esc(st));
        for t in tasks.iter().filter(|t| t.stage == *st) {
            let x = left + width * t.started_s.unwrap() / end;
            let w = (width * t.wall_time_s / end).max(0.5);
            let _ = writeln!(
                s,
                "<rect x=\"{x:.1}\" y=\"{:.1}\" width=\"{w:.1}\" height=\"{:.1}\" fill=\"#4a78b5\"><title>{} {}: {:.2} s</title></rect>",
                y + 2.0,
                row - 4.0,
                esc(st),
                esc(&t.point),
                t.wall_time_s
            );
        }
    }
    let y = row * stages.len() as f64 + 14.0;
    let _ = writeln!(
        s,
        "<text x=\"{left}\" y=\"{y}\">0 s</text><text x=\"{}\" y=\"{y}\" text-anchor=\"end\">{end:.1} s from the start of the run</text></svg>",
        left + width
    );
    s
}

#[cfg(test)]
mod tests {
    use super::number;

    #[test]
    fn numbers_show_six_significant_digits() {
        assert_eq!(number(2.9059472802519528e-5), "2.90595e-5");
        assert_eq!(number(-1.5016247), "-1.50162");
        assert_eq!(number(230.952765), "230.953");
        assert_eq!(number(1.0), "1");
        assert_eq!(number(0.125781), "0.125781");
        assert_eq!(number(0.0), "0");
        assert_eq!(number(2.5e7), "2.50000e7");
    }
}

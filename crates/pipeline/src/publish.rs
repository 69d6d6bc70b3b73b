//! Publishing a completed stage: its table as `tables/<stage>.parquet` (with each row's
//! task key and code version, and in the file's metadata the stage's parameters and every
//! column's unit), or a figure's files and data in `figures/`. Files are replaced
//! atomically and only when their bytes change; temporaries a killed run left are removed
//! when provably stale.

use crate::key::Hash;
use crate::kind::{Output, Registry};
use crate::spec::{Pipeline, Stage};
use crate::table::{ColumnData, Table};
use anyhow::{bail, Result};
use std::path::{Path, PathBuf};

/// Where published files go.
#[derive(Clone, Debug)]
pub struct OutputDirs {
    pub figures: PathBuf,
    pub tables: PathBuf,
}

/// Adds the per-row task key and the code version to a stage's table, for publishing, and
/// the task's wall time as `wall_time_s` where the kind does not report its own, and as
/// `task_time_s` on the task's first row only (0 on the others: the column sums to the
/// stage's cost); not to a figure's data: its numbers are those of the stages it draws.
fn provenance_table(points: &[(Hash, Output)], times: &[f64], code_version: &str, figure: bool) -> Result<Table> {
    let mut table = Table::new();
    for ((key, out), &dt) in points.iter().zip(times) {
        let n = out.table.n_rows();
        let mut t = out.table.clone();
        if !figure && t.column("wall_time_s").is_none() {
            t = t.with_f64("wall_time_s", vec![dt; n]);
        }
        if !figure {
            t = t.with_f64("task_time_s", (0..n).map(|i| if i == 0 { dt } else { 0.0 }).collect());
        }
        let t = t
            .with("task_key", ColumnData::Str(vec![key.clone(); n]))
            .with("code_version", ColumnData::Str(vec![code_version.to_string(); n]));
        table.append(&t)?;
    }
    Ok(table)
}

/// Writes `bytes` to `path` unless it already holds them; returns whether it wrote.
fn publish_file(path: &Path, bytes: &[u8]) -> Result<bool> {
    if crate::cache::read_regular(path).map(|b| b == bytes).unwrap_or(false) {
        return Ok(false);
    }
    let dir = path.parent().unwrap_or(Path::new("."));
    if let Err(e) = std::fs::create_dir_all(dir) {
        // A user's file where the folder should be is reported, never moved: outputs are
        // theirs.
        let blocker = dir.ancestors().find(|a| std::fs::metadata(a).is_ok_and(|m| !m.is_dir()));
        return Err(match blocker {
            Some(b) => anyhow::anyhow!(
                "cannot write {}: {} is a file, not a folder (move it, or publish elsewhere with --figures or --tables)",
                path.display(),
                b.display()
            ),
            None => anyhow::Error::new(e).context(format!("creating {} for {}", dir.display(), path.display())),
        });
    }
    crate::cache::write_atomic(path, bytes, dir)?;
    Ok(true)
}

/// Removes temporary files a killed run left while publishing (`.repro-<pid>-<n>.tmp`), and
/// only those: a temporary of a process that is still running (another run publishing into
/// the same folder) is left alone. Where the system does not say which processes run (no
/// `/proc`), only temporaries older than a day are removed.
pub fn remove_stale_temporaries(dirs: &[&Path]) {
    let procs = Path::new("/proc/self").exists();
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(dir) else { continue };
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().to_string();
            let Some(pid) = name.strip_prefix(".repro-").and_then(|r| r.strip_suffix(".tmp")) else { continue };
            let pid = pid.split('-').next().and_then(|p| p.parse::<u32>().ok());
            let stale = match pid {
                Some(pid) if procs => pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists(),
                _ => e
                    .metadata()
                    .and_then(|m| m.modified())
                    .is_ok_and(|t| t.elapsed().is_ok_and(|age| age > std::time::Duration::from_secs(86400))),
            };
            if stale {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
}

/// The parameters every point of `stage` shares, canonical (defaults filled in): all of
/// them for an unswept stage, all but the swept ones for a sweep.
fn fixed_params(stage: &Stage) -> serde_json::Map<String, serde_json::Value> {
    let mut points = stage.points.iter().filter_map(|p| p.params.as_object());
    let Some(first) = points.next() else { return Default::default() };
    let mut fixed = first.clone();
    for other in points {
        fixed.retain(|k, v| other.get(k) == Some(v));
    }
    fixed
}

/// A completed stage's table as published: its rows with their provenance (task key, code
/// version, wall time) and, in the Parquet metadata, the stage's parameters and every
/// column's unit and meaning. Also whether the stage is a figure.
pub fn stage_parquet(
    p: &Pipeline,
    stage: &Stage,
    registry: &Registry,
    points: &[(Hash, Output)],
    times: &[f64],
) -> Result<(Vec<u8>, bool)> {
    let kind = registry.get(&stage.kind).unwrap();
    let code_version = format!("{}@v{}", stage.kind, kind.version());
    let is_figure = points.iter().any(|(_, o)| !o.artifacts.is_empty());
    let table = provenance_table(points, times, &code_version, is_figure)?;
    let keys: Vec<&str> = points.iter().map(|(k, _)| k.as_str()).collect();
    // What a reader needs beside the numbers: the stage's parameters as the pipeline gives
    // them (a figure's axis labels among them) and every column's unit and meaning.
    let columns: serde_json::Map<String, serde_json::Value> = table
        .column_names()
        .into_iter()
        .filter_map(|c| Some((c.to_string(), serde_json::to_value(registry.column(&c)?).ok()?)))
        .collect();
    let metadata = vec![
        ("repro.pipeline".to_string(), p.file.clone()),
        ("repro.stage".to_string(), stage.name.clone()),
        ("repro.code_version".to_string(), code_version),
        ("repro.version".to_string(), env!("CARGO_PKG_VERSION").to_string()),
        ("repro.task_keys".to_string(), keys.join(",")),
        ("repro.params".to_string(), serde_json::to_string(&fixed_params(stage))?),
        ("repro.columns".to_string(), serde_json::to_string(&columns)?),
    ];
    Ok((table.to_parquet_bytes(&metadata)?, is_figure))
}

/// Publishes a completed stage: `tables/<stage>.parquet`, or for a figure
/// `figures/<stage>.<ext>` for each artifact and `figures/<stage>.parquet` for its data.
pub fn publish_stage(
    p: &Pipeline,
    stage: &Stage,
    registry: &Registry,
    points: &[(Hash, Output)],
    times: &[f64],
    dirs: &OutputDirs,
) -> Result<Vec<String>> {
    let (bytes, is_figure) = stage_parquet(p, stage, registry, points, times)?;
    if is_figure && points.len() != 1 {
        bail!("figure stage `{}` has {} points; a figure stage takes no sweep", stage.name, points.len());
    }
    let dir = if is_figure { &dirs.figures } else { &dirs.tables };
    let mut written = Vec::new();
    let pq = dir.join(format!("{}.parquet", stage.name));
    if publish_file(&pq, &bytes)? {
        written.push(pq.display().to_string());
    }
    for (_, o) in points {
        for (ext, text) in &o.artifacts {
            let path = dir.join(format!("{}.{ext}", stage.name));
            if publish_file(&path, text.as_bytes())? {
                written.push(path.display().to_string());
            }
        }
    }
    Ok(written)
}

/// The folder a run with parameters set on the command line (`-S`) publishes into unless
/// told otherwise: `overrides/<pipeline>/<the settings>` (characters other than letters,
/// digits and `._=+-` as `_`, each setting a path component's part joined by `,`; a long
/// name ends with a hash of the whole). The figures and tables that the pipeline file
/// itself produces are then never overwritten by a run that computed something else, and
/// the same settings always publish to the same place.
pub fn overrides_folder(pipeline: &Path, overrides: &[String]) -> std::path::PathBuf {
    let stem = pipeline.file_stem().map_or_else(|| "pipeline".to_string(), |s| s.to_string_lossy().to_string());
    let safe = |s: &str| -> String {
        s.chars().map(|c| if c.is_ascii_alphanumeric() || "._=+-".contains(c) { c } else { '_' }).collect()
    };
    let joined = overrides.iter().map(|o| safe(o)).collect::<Vec<_>>().join(",");
    let name = if joined.len() > 100 {
        let hash = blake3::hash(overrides.join("\n").as_bytes()).to_hex();
        format!("{}-{}", &joined[..80], &hash[..16])
    } else {
        joined
    };
    Path::new("overrides").join(safe(&stem)).join(name)
}

/// Where a run publishes: `figures` and `tables` as given, else `figures/` and `tables/`,
/// except that a run with settings (`-S`) and without `publish` defaults to its own folder
/// (`overrides_folder`, returned too).
pub fn publish_dirs(
    pipeline: &Path,
    settings: &[String],
    figures: Option<std::path::PathBuf>,
    tables: Option<std::path::PathBuf>,
    publish: bool,
) -> (std::path::PathBuf, std::path::PathBuf, Option<std::path::PathBuf>) {
    let apart = (!settings.is_empty() && !publish).then(|| overrides_folder(pipeline, settings));
    let base = |sub: &str| apart.as_ref().map_or_else(|| sub.into(), |dir| dir.join(sub));
    (figures.unwrap_or_else(|| base("figures")), tables.unwrap_or_else(|| base("tables")), apart)
}

#[cfg(test)]
mod overrides_folder_tests {
    use super::overrides_folder;
    use std::path::Path;

    #[test]
    fn settings_name_their_folder() {
        let p = Path::new("pipelines/thesis.yaml");
        assert_eq!(
            overrides_folder(p, &["max_vs_lambda.W=1".into(), "rolling.k=[0.1, 1]".into()]),
            Path::new("overrides/thesis/max_vs_lambda.W=1,rolling.k=_0.1__1_")
        );
        // A long list: its first 80 characters and a hash, so that two lists differ.
        let long: Vec<String> = (0..20).map(|i| format!("stage{i}.param=1")).collect();
        let mut other = long.clone();
        other[19] = "stage19.param=2".into();
        let (a, b) = (overrides_folder(p, &long), overrides_folder(p, &other));
        assert_ne!(a, b);
        assert!(a.file_name().unwrap().len() == 97, "{a:?}");
    }
}

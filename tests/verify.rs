//! `repro verify`: a copy of committed figures passes; one changed value in a table, or one
//! changed number in an SVG, fails with the file, the column and row (or line) named.

use crate::common;
use common::{column, Scratch};
use polars::prelude::{DataType, NamedFrom, ParquetWriter, Series};
use std::path::Path;

const FIGURE: &str = "fig2_4";

fn copy_figure(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for ext in ["svg", "parquet"] {
        let name = format!("{FIGURE}.{ext}");
        std::fs::copy(from.join(&name), to.join(&name)).unwrap();
    }
}

fn committed() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("figures")
}

#[test]
fn an_untouched_copy_passes_and_a_changed_value_fails_by_name() {
    let s = Scratch::new("verify");
    copy_figure(&committed(), &s.path("reference"));
    copy_figure(&committed(), &s.path("produced"));
    let out = s.repro(&["verify", "produced", "reference"]);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert_eq!(out.status.code(), Some(0), "{text}");
    assert!(text.contains("2 equal, 0 differ"), "{text}");

    // One value of the first float column, moved by one part in a million.
    let table = s.path(&format!("produced/{FIGURE}.parquet"));
    let mut df = repro::pipeline::table::read_parquet(&table).unwrap();
    let name = df
        .get_column_names()
        .iter()
        .map(|c| c.to_string())
        .find(|c| df.column(c).unwrap().dtype() == &DataType::Float64 && !c.ends_with("_time_s"))
        .unwrap();
    let mut values = column(&df, &name);
    let row = (values.len() / 2..values.len()).find(|&i| values[i] != 0.0).unwrap();
    values[row] *= 1.0 + 1e-6;
    df.with_column(Series::new(name.as_str().into(), values).into()).unwrap();
    ParquetWriter::new(std::fs::File::create(&table).unwrap()).finish(&mut df).unwrap();
    let out = s.repro(&["verify", "produced", "reference"]);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(text.contains(&format!("DIFFERS {FIGURE}.parquet: column `{name}`, row {row}")), "{text}");
    assert!(text.contains("1 equal, 1 differ"), "{text}");
    // Within a tolerance it passes.
    let out = s.repro(&["verify", "produced", "reference", "--rel-tol", "1e-5"]);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stdout));
}

#[test]
fn a_changed_svg_and_an_uncommitted_figure_fail() {
    let s = Scratch::new("verify-svg");
    copy_figure(&committed(), &s.path("reference"));
    copy_figure(&committed(), &s.path("produced"));
    let svg = s.path(&format!("produced/{FIGURE}.svg"));
    let text = std::fs::read_to_string(&svg).unwrap();
    // The first coordinate of the first curve, nudged.
    let at = text.find("<polyline").unwrap();
    let digit = at + text[at..].find(|c: char| c.is_ascii_digit()).unwrap();
    let mut changed = text.clone();
    let d = changed.as_bytes()[digit];
    changed.replace_range(digit..digit + 1, if d == b'9' { "8" } else { "9" });
    std::fs::write(&svg, changed).unwrap();
    std::fs::write(s.path("produced/new.svg"), "<svg/>").unwrap();
    let out = s.repro(&["verify", "produced", "reference"]);
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    let line = text[..digit].matches('\n').count() + 1;
    assert!(stdout.contains(&format!("DIFFERS {FIGURE}.svg: line {line} differs")), "{stdout}");
    assert!(stdout.contains("DIFFERS new.svg: not in the reference"), "{stdout}");
    // A reference file the run did not produce is reported, not failed.
    std::fs::remove_file(s.path("produced/new.svg")).unwrap();
    std::fs::copy(s.path(&format!("reference/{FIGURE}.svg")), &svg).unwrap();
    std::fs::remove_file(s.path(&format!("produced/{FIGURE}.parquet"))).unwrap();
    let out = s.repro(&["verify", "produced", "reference"]);
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(stdout.contains("1 equal, 0 differ, 1 in reference not produced"), "{stdout}");
}

#[test]
fn comparing_nothing_fails() {
    // An empty produced folder, or one holding only a subfolder, compares nothing: exit 1,
    // saying so, not "0 equal, 0 differ" and success.
    let s = Scratch::new("verify-nothing");
    copy_figure(&committed(), &s.path("reference"));
    std::fs::create_dir_all(s.path("produced/sub")).unwrap();
    let out = s.repro(&["verify", "produced", "reference"]);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(text.contains("0 equal, 0 differ") && text.contains("nothing was compared"), "{text}");
    // With one figure produced it passes again.
    copy_figure(&committed(), &s.path("produced"));
    assert_eq!(s.repro(&["verify", "produced", "reference"]).status.code(), Some(0));
}

//! Stage kinds: where the orchestrator (parameters, tables) meets the physics.
//! Each kind binds one physics function to typed, validated parameters and a table.

pub mod bem;
pub mod bench;
pub mod claim;
pub mod fem;
pub mod figure;
pub mod fit;
pub mod jkr_limit;
pub mod material;
pub mod pb;
pub mod theory;
pub mod util;
pub mod values;

use pipeline::kind::{ColumnDoc, Registry};

/// The output columns' units and meanings: the tables of `docs/outputs.md` (rows
/// "| `name` | unit | meaning |"), the one description of every column the kinds write
/// (`tests/kind_versions.rs` checks that each is there).
const OUTPUT_COLUMNS: &str = include_str!("../../docs/outputs.md");

/// The documented output columns, in the order of `docs/outputs.md`.
pub fn documented_columns() -> Vec<(String, ColumnDoc)> {
    OUTPUT_COLUMNS
        .lines()
        .filter_map(|line| {
            let cells = table_cells(line);
            let name = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            let (unit, meaning) = (cells.get(2)?, cells.get(3)?);
            (cells.len() >= 5 && !unit.is_empty() && !meaning.is_empty())
                .then(|| (name.to_string(), ColumnDoc { unit: unit.to_string(), meaning: meaning.to_string() }))
        })
        .collect()
}

/// The cells of a Markdown table row, trimmed, split at the pipes that are not escaped
/// (`\|` stands for a `|` inside a cell, as in |W|).
fn table_cells(line: &str) -> Vec<String> {
    let mut cells = vec![String::new()];
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'|') => {
                cells.last_mut().expect("a cell").push('|');
                chars.next();
            }
            '|' => cells.push(String::new()),
            _ => cells.last_mut().expect("a cell").push(c),
        }
    }
    cells.iter().map(|c| c.trim().to_string()).collect()
}

/// Every stage kind a pipeline may use.
pub fn registry() -> Registry {
    let mut r = Registry::new();
    r.document_columns(documented_columns());
    // Tasks stop at the solvers' checkpoints once their time limit has passed, or the
    // process cancelled them.
    r.set_limiter(|limit, f| {
        use physics::numerics::budget::{within, Exhausted};
        within(limit, f).map_err(|why| match why {
            Exhausted::Deadline => pipeline::kind::Stopped::TimeLimit,
            Exhausted::Cancelled => pipeline::kind::Stopped::Interrupted,
        })
    });
    theory::register(&mut r);
    bem::register(&mut r);
    fem::register(&mut r);
    bench::register(&mut r);
    claim::register(&mut r);
    figure::register(&mut r);
    fit::register(&mut r);
    jkr_limit::register(&mut r);
    pb::register(&mut r);
    util::register(&mut r);
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_escaped_pipe_stays_in_its_cell() {
        let cells = table_cells(r"| `F_T` | 1 | force F_T* = μ* \|W\| (Eq. 5.6) |");
        assert_eq!(cells, ["", "`F_T`", "1", "force F_T* = μ* |W| (Eq. 5.6)", ""]);
        // Every documented meaning is read whole: the ones with |W| end where their row does.
        let docs: std::collections::BTreeMap<String, ColumnDoc> = documented_columns().into_iter().collect();
        assert_eq!(docs["V0"].meaning, "speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)");
        assert_eq!(docs["F_T"].meaning, "rolling friction force F_T* = μ* |W| (Eq. 5.6)");
        // No row of docs/outputs.md has more cells than a name, a unit and a meaning.
        for line in OUTPUT_COLUMNS.lines().filter(|l| l.starts_with("| `")) {
            assert_eq!(table_cells(line).len(), 5, "{line}");
        }
    }
}

//! A small column-oriented table: the unit of data that tasks exchange.
//!
//! Tasks return tables; the cache stores them as canonical JSON (so that byte equality
//! means equal results, which is what early cutoff relies on); publishing converts them to
//! Parquet with polars. Non-finite floats are refused: no NaN or infinity reaches a table.

use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", content = "values", rename_all = "lowercase")]
pub enum ColumnData {
    F64(Vec<f64>),
    I64(Vec<i64>),
    Bool(Vec<bool>),
    Str(Vec<String>),
}

impl ColumnData {
    pub fn len(&self) -> usize {
        match self {
            ColumnData::F64(v) => v.len(),
            ColumnData::I64(v) => v.len(),
            ColumnData::Bool(v) => v.len(),
            ColumnData::Str(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn type_name(&self) -> &'static str {
        match self {
            ColumnData::F64(_) => "f64",
            ColumnData::I64(_) => "i64",
            ColumnData::Bool(_) => "bool",
            ColumnData::Str(_) => "str",
        }
    }

    /// Appends `other` (of the same type) to `self`.
    fn extend(&mut self, other: &ColumnData) -> Result<()> {
        match (self, other) {
            (ColumnData::F64(a), ColumnData::F64(b)) => a.extend_from_slice(b),
            (ColumnData::I64(a), ColumnData::I64(b)) => a.extend_from_slice(b),
            (ColumnData::Bool(a), ColumnData::Bool(b)) => a.extend_from_slice(b),
            (ColumnData::Str(a), ColumnData::Str(b)) => a.extend_from_slice(b),
            (a, b) => bail!("cannot append a {} column to a {} column", b.type_name(), a.type_name()),
        }
        Ok(())
    }

    /// The value at `row` as f64 (numbers and booleans), if it is numeric.
    pub fn f64_at(&self, row: usize) -> Option<f64> {
        match self {
            ColumnData::F64(v) => v.get(row).copied(),
            ColumnData::I64(v) => v.get(row).map(|&x| x as f64),
            ColumnData::Bool(v) => v.get(row).map(|&x| f64::from(u8::from(x))),
            ColumnData::Str(_) => None,
        }
    }

    /// The value at `row` formatted for labels.
    pub fn display_at(&self, row: usize) -> String {
        match self {
            ColumnData::F64(v) => format_number(v[row]),
            ColumnData::I64(v) => v[row].to_string(),
            ColumnData::Bool(v) => v[row].to_string(),
            ColumnData::Str(v) => v[row].clone(),
        }
    }
}

/// Formats a number compactly for labels: `0.1`, `1000`, `1e-6`.
pub fn format_number(x: f64) -> String {
    if x != 0.0 && (x.abs() >= 1e5 || x.abs() < 1e-3) {
        let s = format!("{x:e}");
        return s;
    }
    let s = format!("{:.6}", x);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Table {
    pub columns: Vec<(String, ColumnData)>,
}

impl Table {
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a column (builder style).
    pub fn with(mut self, name: &str, data: ColumnData) -> Self {
        self.push(name, data);
        self
    }

    pub fn with_f64(self, name: &str, v: Vec<f64>) -> Self {
        self.with(name, ColumnData::F64(v))
    }

    pub fn push(&mut self, name: &str, data: ColumnData) {
        if let Some(slot) = self.columns.iter_mut().find(|(n, _)| n == name) {
            slot.1 = data;
        } else {
            self.columns.push((name.to_string(), data));
        }
    }

    pub fn n_rows(&self) -> usize {
        self.columns.first().map_or(0, |(_, c)| c.len())
    }

    pub fn column(&self, name: &str) -> Option<&ColumnData> {
        self.columns.iter().find(|(n, _)| n == name).map(|(_, c)| c)
    }

    /// A column as f64 values, or an error naming the column and the columns that exist.
    pub fn f64_column(&self, name: &str) -> Result<Vec<f64>> {
        let col = self
            .column(name)
            .with_context(|| format!("no column `{name}` (columns: {})", self.column_names().join(", ")))?;
        (0..col.len()).map(|i| col.f64_at(i).with_context(|| format!("column `{name}` is not numeric"))).collect()
    }

    /// A text column's values, or an error naming the column (and the columns that exist).
    pub fn str_column(&self, name: &str) -> Result<Vec<String>> {
        match self.column(name) {
            Some(ColumnData::Str(v)) => Ok(v.clone()),
            Some(_) => bail!("column `{name}` is not text"),
            None => bail!("no column `{name}` (columns: {})", self.column_names().join(", ")),
        }
    }

    pub fn column_names(&self) -> Vec<String> {
        self.columns.iter().map(|(n, _)| n.clone()).collect()
    }

    /// Checks that all columns have the same length and every float is finite.
    pub fn check(&self) -> Result<()> {
        let n = self.n_rows();
        for (name, col) in &self.columns {
            if col.len() != n {
                bail!("column `{name}` has {} rows, expected {n}", col.len());
            }
            if let ColumnData::F64(v) = col {
                if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                    bail!("column `{name}` holds a non-finite value ({}) at row {i}", v[i]);
                }
            }
        }
        Ok(())
    }

    /// Appends the rows of `other`, which must have the same columns in the same order.
    pub fn append(&mut self, other: &Table) -> Result<()> {
        if self.columns.is_empty() {
            *self = other.clone();
            return Ok(());
        }
        if self.column_names() != other.column_names() {
            bail!(
                "cannot append tables with different columns: [{}] vs [{}]",
                self.column_names().join(", "),
                other.column_names().join(", ")
            );
        }
        for ((_, a), (_, b)) in self.columns.iter_mut().zip(&other.columns) {
            a.extend(b)?;
        }
        Ok(())
    }

    /// Canonical bytes: the same table always gives the same bytes.
    pub fn canonical_bytes(&self) -> Vec<u8> {
        serde_json::to_vec(self).expect("a table always serialises")
    }

    /// Converts to a polars DataFrame.
    pub fn to_polars(&self) -> Result<polars::prelude::DataFrame> {
        use polars::prelude::*;
        let cols: Vec<Column> = self
            .columns
            .iter()
            .map(|(name, c)| match c {
                ColumnData::F64(v) => Column::new(name.as_str().into(), v.as_slice()),
                ColumnData::I64(v) => Column::new(name.as_str().into(), v.as_slice()),
                ColumnData::Bool(v) => Column::new(name.as_str().into(), v.as_slice()),
                ColumnData::Str(v) => Column::new(name.as_str().into(), v.as_slice()),
            })
            .collect();
        Ok(DataFrame::new(self.n_rows(), cols)?)
    }

    /// Parquet bytes of this table, with `metadata` as file-level key/value pairs.
    pub fn to_parquet_bytes(&self, metadata: &[(String, String)]) -> Result<Vec<u8>> {
        use polars::prelude::*;
        let mut df = self.to_polars()?;
        let mut buf = std::io::Cursor::new(Vec::new());
        ParquetWriter::new(&mut buf)
            .with_key_value_metadata(Some(KeyValueMetadata::from_static(metadata.to_vec())))
            .finish(&mut df)?;
        Ok(buf.into_inner())
    }
}

/// Reads a Parquet file into a polars DataFrame (used by tests and tools).
/// Opens a table's file, which must be a regular file (`cache::read_regular`: a FIFO would
/// block the open).
fn open_regular(path: &std::path::Path) -> Result<std::fs::File> {
    let meta = std::fs::metadata(path).with_context(|| format!("opening {}", path.display()))?;
    if !meta.is_file() {
        anyhow::bail!("opening {}: not a regular file", path.display());
    }
    std::fs::File::open(path).with_context(|| format!("opening {}", path.display()))
}

pub fn read_parquet(path: &std::path::Path) -> Result<polars::prelude::DataFrame> {
    use polars::prelude::*;
    let f = open_regular(path)?;
    Ok(ParquetReader::new(f).finish()?)
}

/// The file-level key/value metadata of a Parquet file (`to_parquet_bytes`' `metadata`).
pub fn read_parquet_metadata(path: &std::path::Path) -> Result<Vec<(String, String)>> {
    use polars::prelude::*;
    let f = open_regular(path)?;
    let mut reader = ParquetReader::new(f);
    let meta = reader.get_metadata()?;
    Ok(meta
        .key_value_metadata()
        .iter()
        .flatten()
        .map(|kv| (kv.key.clone(), kv.value.clone().unwrap_or_default()))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn append_checks_columns_and_types() {
        let mut a = Table::new().with_f64("x", vec![1.0]);
        a.append(&Table::new().with_f64("x", vec![2.0])).unwrap();
        assert_eq!(a.f64_column("x").unwrap(), vec![1.0, 2.0]);
        assert!(a.append(&Table::new().with_f64("y", vec![2.0])).is_err());
    }

    #[test]
    fn non_finite_values_are_refused() {
        let t = Table::new().with_f64("x", vec![1.0, f64::NAN]);
        let err = t.check().unwrap_err().to_string();
        assert!(err.contains("non-finite") && err.contains("`x`"), "{err}");
    }

    #[test]
    fn parquet_round_trip() {
        let t = Table::new().with_f64("x", vec![1.0, 2.5]).with("s", ColumnData::Str(vec!["a".into(), "b".into()]));
        let bytes = t.to_parquet_bytes(&[("k".into(), "v".into())]).unwrap();
        let dir = std::env::temp_dir().join(format!("repro-pq-{}", std::process::id()));
        std::fs::write(&dir, &bytes).unwrap();
        let df = read_parquet(&dir).unwrap();
        std::fs::remove_file(&dir).ok();
        assert_eq!(df.height(), 2);
        assert_eq!(df.width(), 2);
    }
}

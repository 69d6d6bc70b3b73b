//! Text the commands print: a kind's parameters, range and columns (`repro kinds KIND`), and
//! CSV fields (`repro show --csv`).

/// A CSV field: quoted (with doubled quotes) when it holds a comma, a quote or a newline.
pub(crate) fn csv_field(t: &str) -> String {
    if t.contains([',', '"', '\n']) {
        format!("\"{}\"", t.replace('"', "\"\""))
    } else {
        t.to_string()
    }
}

/// `repro kinds KIND`: a kind's parameters and output columns, as a table of text.
pub(crate) fn describe_kind(k: &dyn pipeline::kind::DynKind, registry: &pipeline::kind::Registry) -> String {
    let d = repro::description::describe(k, registry);
    let mut out = format!(
        "{} (code version {}): {}\ntime limit per task: {} s (a stage's `time_limit`, `repro run --time-limit`)\n\n",
        d.name, d.version, d.doc, d.time_limit_s
    );
    if d.params.is_empty() {
        out.push_str("no parameters\n");
    } else {
        out.push_str(&format!(
            "{:<18} {:<22} {:<14} {:<14} {:<9} meaning\n",
            "parameter", "type", "default", "valid range", "sweep"
        ));
    }
    for p in &d.params {
        // One spelling of "no default": an optional parameter whose default is null has none.
        let default = match &p.default {
            Some(v) if !v.is_null() => v.to_string(),
            _ if p.required => "(required)".into(),
            _ => "(none)".into(),
        };
        let default = if default.chars().count() > 14 {
            format!("{}…", default.chars().take(13).collect::<String>())
        } else {
            default
        };
        let sweep = if p.sweepable { "sweepable" } else { "" };
        out.push_str(&format!(
            "{:<18} {:<22} {default:<14} {:<14} {sweep:<9} {}\n",
            p.name, p.r#type, p.range, p.meaning
        ));
    }
    if !d.columns.is_empty() {
        out.push_str(&format!("\n{:<24} {:<26} meaning\n", "output column", "unit"));
        for c in &d.columns {
            out.push_str(&format!("{:<24} {:<26} {}\n", c.name, c.unit, c.meaning));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn csv_fields_are_quoted_only_when_they_must_be() {
        assert_eq!(super::csv_field("λ = 1"), "λ = 1");
        assert_eq!(super::csv_field("λ = 1, W = 0.1"), "\"λ = 1, W = 0.1\"");
        assert_eq!(super::csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(super::csv_field("two\nlines"), "\"two\nlines\"");
    }
}

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

pub(crate) fn describe_kind(
    k: &dyn repro::pipeline::kind::DynKind,
    registry: &repro::pipeline::kind::Registry,
) -> String {
    use serde_json::Value;
    let schema = k.params_schema();
    let defs = schema.get("$defs").cloned().unwrap_or(Value::Null);
    let resolve = |v: &Value| -> Value {
        match v.get("$ref").and_then(Value::as_str).and_then(|r| r.rsplit('/').next()) {
            Some(name) => defs.get(name).cloned().unwrap_or(Value::Null),
            None => v.clone(),
        }
    };
    let type_of = |v: &Value| -> String {
        if let Some(r) = v.get("$ref").and_then(Value::as_str) {
            return r.rsplit('/').next().unwrap_or(r).to_string();
        }
        match v.get("type") {
            Some(Value::String(t)) => t.clone(),
            Some(Value::Array(ts)) => ts.iter().filter_map(Value::as_str).collect::<Vec<_>>().join(" or "),
            _ => match v.get("anyOf").or_else(|| v.get("oneOf")).and_then(Value::as_array) {
                Some(alts) => alts
                    .iter()
                    .map(|a| {
                        a.get("$ref")
                            .and_then(Value::as_str)
                            .map(|r| r.rsplit('/').next().unwrap_or(r).to_string())
                            .or_else(|| a.get("type").and_then(Value::as_str).map(str::to_string))
                            .or_else(|| a.get("const").map(|c| c.to_string()))
                            .unwrap_or_else(|| "value".into())
                    })
                    .collect::<Vec<_>>()
                    .join(" or "),
                None => v.get("enum").map_or("value".into(), |e| format!("one of {e}")),
            },
        }
    };
    let mut out = format!(
        "{} (code version {}): {}\ntime limit per task: {} s (a stage's `time_limit`, `repro run --time-limit`)\n\n",
        k.name(),
        k.version(),
        k.doc(),
        k.time_limit_s()
    );
    let required: Vec<&str> = schema
        .get("required")
        .and_then(Value::as_array)
        .map_or(Vec::new(), |r| r.iter().filter_map(Value::as_str).collect());
    let Some(props) = schema.get("properties").and_then(Value::as_object) else {
        out.push_str("no parameters\n");
        return out;
    };
    out.push_str(&format!(
        "{:<18} {:<22} {:<14} {:<14} {:<9} meaning\n",
        "parameter", "type", "default", "valid range", "sweep"
    ));
    for (name, v) in props {
        let doc = v
            .get("description")
            .and_then(Value::as_str)
            .map(str::to_string)
            .or_else(|| resolve(v).get("description").and_then(Value::as_str).map(str::to_string))
            .unwrap_or_default();
        let default = match v.get("default") {
            Some(d) => d.to_string(),
            None if required.contains(&name.as_str()) => "(required)".into(),
            None => "(none)".into(),
        };
        let default = if default.chars().count() > 14 {
            format!("{}…", default.chars().take(13).collect::<String>())
        } else {
            default
        };
        let sweep = if k.sweepable().contains(&name.as_str()) { "sweepable" } else { "" };
        let doc = doc.split_whitespace().collect::<Vec<_>>().join(" ");
        let range = repro::pipeline::kind::range_text(&schema, v);
        out.push_str(&format!("{name:<18} {:<22} {default:<14} {range:<14} {sweep:<9} {doc}\n", type_of(v)));
    }
    if !k.columns().is_empty() {
        out.push_str(&format!("\n{:<24} {:<26} meaning\n", "output column", "unit"));
        for c in k.columns() {
            let (unit, meaning) =
                registry.column(c).map_or(("", "(see docs/outputs.md)"), |d| (d.unit.as_str(), d.meaning.as_str()));
            out.push_str(&format!("{c:<24} {unit:<26} {meaning}\n"));
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

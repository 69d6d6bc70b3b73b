//! The architecture holds: the orchestrator crate knows no physics, the physics crate no
//! serialisation, YAML, files or caches, and no crate's modules import each other in a
//! cycle. Read from the manifests and the sources, so a change that breaks a layer fails
//! here with the file that breaks it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The names in the `[dependencies]` table of a crate's manifest.
fn dependencies(manifest: &str) -> BTreeSet<String> {
    let text = std::fs::read_to_string(manifest).unwrap();
    let mut in_deps = false;
    let mut names = BTreeSet::new();
    for line in text.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            in_deps = line == "[dependencies]";
            continue;
        }
        if in_deps && !line.is_empty() && !line.starts_with('#') {
            let name = line.split(['=', '.', ' ']).next().unwrap().trim();
            names.insert(name.to_string());
        }
    }
    names
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// A file's code without comments and without its test module.
fn code(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let text = text.split("#[cfg(test)]").next().unwrap();
    text.lines().map(|l| l.split("//").next().unwrap()).collect::<Vec<_>>().join("\n")
}

#[test]
fn the_orchestrator_knows_no_physics_and_the_physics_no_files_or_serialisation() {
    let pipeline = dependencies("crates/pipeline/Cargo.toml");
    let physics = dependencies("crates/physics/Cargo.toml");
    assert!(pipeline.contains("polars") && physics.contains("faer"), "{pipeline:?} {physics:?}");
    for name in ["repro-physics", "faer", "realfft", "rustfft", "libm"] {
        assert!(!pipeline.contains(name), "the orchestrator depends on `{name}`");
    }
    for name in ["repro-pipeline", "serde", "serde_json", "marked-yaml", "schemars", "polars", "blake3", "anyhow"] {
        assert!(!physics.contains(name), "the physics depends on `{name}`");
    }
    let mut files = Vec::new();
    rust_files(Path::new("crates/physics/src"), &mut files);
    assert!(files.len() > 20);
    for f in &files {
        let c = code(f);
        for io in ["std::fs", "std::io", "File::", "std::env", "std::process", "serde"] {
            assert!(!c.contains(io), "{} uses `{io}`: the physics reads and writes no files", f.display());
        }
    }
}

/// The module of a source file under `root`: `a::b` for `a/b.rs` or `a/b/mod.rs`.
fn module_of(root: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(root).unwrap().with_extension("");
    let mut parts: Vec<String> = rel.iter().map(|s| s.to_string_lossy().to_string()).collect();
    match parts.last().map(String::as_str) {
        // The crate roots, and test modules in files of their own.
        Some("lib" | "main" | "tests") => return None,
        Some("mod") => {
            parts.pop();
        }
        _ => {}
    }
    Some(parts.join("::"))
}

/// The module paths a piece of code names: `crate::a::b` as (None, [a, b]), and
/// `super::super::a` as (Some(2), [a]).
fn named_paths(code: &str) -> Vec<(Option<usize>, Vec<String>)> {
    let mut out = Vec::new();
    for prefix in ["crate::", "super::"] {
        for (i, _) in code.match_indices(prefix) {
            let before = code[..i].chars().last();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue; // a later segment of a path (`super::super::`), or another word
            }
            let mut rest = &code[i + prefix.len()..];
            let mut ups = usize::from(prefix == "super::");
            while prefix == "super::" && rest.starts_with("super::") {
                ups += 1;
                rest = &rest["super::".len()..];
            }
            let path: String = rest
                .chars()
                .take_while(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '_' || *c == ':')
                .collect();
            let segments = path.split("::").filter(|s| !s.is_empty()).map(str::to_string).collect();
            out.push(((prefix == "super::").then_some(ups), segments));
        }
    }
    out
}

/// The dependencies between the modules of a crate (`crate::` and `super::` paths), lifted
/// to siblings: a module that names a module of another subtree depends on it, and each of
/// its ancestors below their common parent on the other's (so that `a::x` naming `b` and
/// `b` naming `a` is the cycle a <-> b).
fn module_graph(root: &str) -> BTreeMap<String, BTreeSet<String>> {
    let root = Path::new(root);
    let mut files = Vec::new();
    rust_files(root, &mut files);
    let modules: BTreeMap<String, PathBuf> =
        files.iter().filter_map(|f| Some((module_of(root, f)?, f.clone()))).collect();
    let resolve = |base: &[String], path: &[String]| -> Option<String> {
        (1..=path.len()).rev().map(|k| [base, &path[..k]].concat().join("::")).find(|m| modules.contains_key(m))
    };
    let mut graph: BTreeMap<String, BTreeSet<String>> = modules.keys().map(|m| (m.clone(), BTreeSet::new())).collect();
    for (m, f) in &modules {
        let segments: Vec<String> = m.split("::").map(str::to_string).collect();
        for (ups, path) in named_paths(&code(f)) {
            let base = match ups {
                None => &segments[..0],
                Some(n) if n <= segments.len() => &segments[..segments.len() - n],
                Some(_) => continue,
            };
            let Some(d) = resolve(base, &path) else { continue };
            let d: Vec<String> = d.split("::").map(str::to_string).collect();
            // The first level where the two paths part: those two siblings.
            let common = segments.iter().zip(&d).take_while(|(a, b)| a == b).count();
            if common < segments.len() && common < d.len() {
                graph.entry(segments[..=common].join("::")).or_default().insert(d[..=common].join("::"));
            }
        }
    }
    graph
}

/// A cycle of `graph`, if it has one.
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        g: &BTreeMap<String, BTreeSet<String>>,
        v: &str,
        state: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(v.to_string(), 1);
        stack.push(v.to_string());
        for w in g.get(v).into_iter().flatten() {
            match state.get(w.as_str()) {
                Some(1) => {
                    let at = stack.iter().position(|s| s == w).unwrap();
                    return Some(stack[at..].to_vec());
                }
                Some(_) => {}
                None => {
                    if let Some(c) = visit(g, w, state, stack) {
                        return Some(c);
                    }
                }
            }
        }
        stack.pop();
        state.insert(v.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for v in graph.keys() {
        if !state.contains_key(v.as_str()) {
            if let Some(c) = visit(graph, v, &mut state, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

#[test]
fn no_crate_s_modules_import_each_other_in_a_cycle() {
    for root in ["crates/pipeline/src", "crates/physics/src", "src"] {
        let g = module_graph(root);
        assert!(g.len() > 5, "{root}: {g:?}");
        assert_eq!(find_cycle(&g), None, "{root}: modules import each other in a cycle");
    }
    // The check sees a cycle where there is one.
    let mut g = module_graph("crates/pipeline/src");
    assert!(g["executor"].contains("plan") && g["plan"].contains("cache"), "{g:?}");
    g.get_mut("cache").unwrap().insert("executor".into());
    assert!(find_cycle(&g).is_some());
    // Through a submodule and `super::super`: the BEM solver's files and the rest of `bem`.
    let g = module_graph("crates/physics/src");
    assert!(g["bem::solver::continuation"].contains("bem::solver::branch"), "{g:?}");
    assert!(g["bem::maxima"].contains("bem::solver"), "{g:?}");
}

#[test]
fn every_integration_test_file_is_built() {
    // `Cargo.toml` turns off cargo's discovery of tests (`autotests = false`): a file in tests/
    // runs only as a `[[test]]` of its own or as a module of tests/integration.rs. One that is
    // neither would be silently skipped.
    let manifest = std::fs::read_to_string("Cargo.toml").unwrap();
    let declared: BTreeSet<String> = manifest
        .lines()
        .filter_map(|l| l.trim().strip_prefix("path = \"tests/")?.strip_suffix(".rs\"").map(str::to_string))
        .collect();
    let merged: BTreeSet<String> = code(Path::new("tests/integration.rs"))
        .lines()
        .filter_map(|l| l.trim().strip_prefix("mod ")?.strip_suffix(';').map(str::to_string))
        .collect();
    assert!(declared.contains("integration") && merged.contains("common"), "{declared:?} {merged:?}");
    let mut missing = Vec::new();
    for e in std::fs::read_dir("tests").unwrap().flatten() {
        let p = e.path();
        if let Some(stem) = p.extension().filter(|x| *x == "rs").and(p.file_stem()).and_then(|s| s.to_str()) {
            if !declared.contains(stem) && !merged.contains(stem) {
                missing.push(stem.to_string());
            }
        }
    }
    assert!(
        missing.is_empty(),
        "tests/{{{}}}.rs: neither a [[test]] in Cargo.toml nor a module of tests/integration.rs",
        missing.join(", ")
    );
    // No file is built twice (its tests would run twice).
    let twice: Vec<&String> = declared.intersection(&merged).collect();
    assert!(twice.is_empty(), "built both on its own and in tests/integration.rs: {twice:?}");
}

#[test]
fn the_chapter3_bench_runs_every_shell_stage_of_the_thesis_pipeline() {
    // `make bench-chapter3` names its stages (CHAPTER3 in the Makefile): a shell stage added
    // to the pipeline and not to the list would go unmeasured.
    let makefile = std::fs::read_to_string("Makefile").unwrap();
    let start = makefile.find("\nCHAPTER3 =").expect("CHAPTER3 in the Makefile") + "\nCHAPTER3 =".len();
    let mut listed = BTreeSet::new();
    for line in makefile[start..].lines() {
        listed.extend(line.trim_end_matches('\\').split_whitespace().map(str::to_string));
        if !line.ends_with('\\') {
            break;
        }
    }
    let text = std::fs::read_to_string("pipelines/thesis.yaml").unwrap();
    let pipeline = repro::pipeline::parse::parse("pipelines/thesis.yaml", &text, &repro::stages::registry()).unwrap();
    let shell: BTreeSet<String> =
        pipeline.stages.iter().filter(|s| s.kind.starts_with("fem.")).map(|s| s.name.clone()).collect();
    assert!(shell.len() >= 20, "{shell:?}");
    assert_eq!(listed, shell);
}

/// A line's code with its string and character literals and its `//` comment removed, so
/// that the braces left are the code's.
fn braces_of(line: &str) -> (usize, usize) {
    let (mut open, mut close) = (0, 0);
    let mut chars = line.chars().peekable();
    let mut in_str = false;
    while let Some(c) = chars.next() {
        match (in_str, c) {
            (true, '\\') => {
                chars.next();
            }
            (true, '"') => in_str = false,
            (true, _) => {}
            (false, '"') => in_str = true,
            (false, '/') if chars.peek() == Some(&'/') => break,
            // A character literal ('{', '\'', '\n'); a lifetime (`'a`) has no closing quote.
            (false, '\'') => {
                let rest: String = chars.clone().take(3).collect();
                if rest.starts_with('\\') {
                    chars.nth(2);
                } else if rest.chars().nth(1) == Some('\'') {
                    chars.nth(1);
                }
            }
            (false, '{') => open += 1,
            (false, '}') => close += 1,
            _ => {}
        }
    }
    (open, close)
}

/// A source file's text before its test module.
fn outside_tests(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    text.split("#[cfg(test)]\nmod tests").next().unwrap().to_string()
}

/// The functions of a source file outside its test module: (line, name, length in lines).
fn function_lengths(path: &Path) -> Vec<(usize, String, usize)> {
    let text = outside_tests(path);
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let t = line.trim_start();
        // `pub`, `pub(crate)`, `pub(super)`, `pub(in path)`.
        let t = match t.strip_prefix("pub(") {
            Some(r) => r.split_once(") ").map_or(t, |(_, rest)| rest),
            None => t.strip_prefix("pub ").unwrap_or(t),
        };
        let t = t.strip_prefix("const ").or_else(|| t.strip_prefix("unsafe ")).unwrap_or(t);
        let Some(rest) = t.strip_prefix("fn ") else { continue };
        let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        let mut depth = 0i64;
        let mut started = false;
        for (j, l) in lines.iter().enumerate().skip(i) {
            let (open, close) = braces_of(l);
            if !started && open == 0 && l.contains(';') {
                break; // a declaration without a body
            }
            started |= open > 0;
            depth += open as i64 - close as i64;
            if started && depth <= 0 {
                out.push((i + 1, name.clone(), j - i + 1));
                break;
            }
        }
    }
    out
}

#[test]
fn no_function_outside_tests_is_longer_than_a_reader_can_hold_in_mind() {
    const LIMIT: usize = 150;
    let mut files = Vec::new();
    for dir in ["src", "crates/pipeline/src", "crates/physics/src", "crates/python/src"] {
        rust_files(Path::new(dir), &mut files);
    }
    let mut long = Vec::new();
    let mut longest = 0;
    for f in &files {
        for (line, name, len) in function_lengths(f) {
            longest = longest.max(len);
            if len > LIMIT {
                long.push(format!("{}:{line} {name}: {len} lines", f.display()));
            }
        }
    }
    assert!(long.is_empty(), "functions over {LIMIT} lines (split them along their phases):\n{}", long.join("\n"));
    // The scan finds functions: the longest today is 144 lines (`figure::draw`).
    assert!(longest > 100, "the function scan found nothing long ({longest} lines): is it reading the sources?");
}

#[test]
fn the_brace_counter_ignores_strings_characters_and_comments() {
    assert_eq!(braces_of(r#"let s = format!("{x} {{ }}"); // { not this"#), (0, 0));
    assert_eq!(braces_of(r"if c == '{' || c == '\'' { f('}') }"), (1, 1));
    assert_eq!(braces_of("fn f<'a>(x: &'a str) -> &'a str {"), (1, 0));
}

#[test]
fn the_root_crate_names_the_crates_it_uses() {
    // `src/` writes `physics::fem::...` and `pipeline::...` where it crosses into the other
    // crates, not the re-exports `crate::fem`, `crate::pipeline` (`src/lib.rs` keeps them
    // for the library's users: the tests, the Python package).
    let mut files = Vec::new();
    rust_files(Path::new("src"), &mut files);
    let re_exported = ["fem", "bem", "numerics", "theory", "rheology", "lennard_jones", "pipeline"];
    let mut found = Vec::new();
    for f in files.iter().filter(|f| !f.ends_with("lib.rs")) {
        let text = code(f);
        for m in re_exported {
            for prefix in ["crate::", "repro::"] {
                if text.contains(&format!("{prefix}{m}::")) {
                    found.push(format!("{}: {prefix}{m}::", f.display()));
                }
            }
        }
    }
    assert!(files.len() > 20 && found.is_empty(), "{found:?}");
}

/// The source files outside tests: the crates' `src` trees, test modules' files aside.
fn sources() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in ["src", "crates/pipeline/src", "crates/physics/src", "crates/python/src"] {
        rust_files(Path::new(dir), &mut files);
    }
    files
        .retain(|f| f.file_name().is_none_or(|n| n != "tests.rs") && !f.components().any(|c| c.as_os_str() == "tests"));
    files
}

/// The number of parameters in a parameter list (the text between its parentheses),
/// `self` not counted: the commas at depth 0, where generics, tuples, closures' types and
/// slices open a level.
fn parameter_count(list: &str) -> usize {
    let list = list.trim().trim_end_matches(',');
    if list.trim().is_empty() {
        return 0;
    }
    let mut depth = 0i32;
    let mut count = 1;
    let mut prev = ' ';
    for c in list.chars() {
        match c {
            '(' | '[' | '{' => depth += 1,
            '<' => depth += 1,
            // `->` in an `impl Fn(..) -> T` is no closing bracket.
            '>' if prev != '-' => depth -= 1,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => count += 1,
            _ => {}
        }
        prev = c;
    }
    let first = list.split(',').next().unwrap_or("");
    count - usize::from(first.contains("self"))
}

/// The functions of a file outside its test module with more than `limit` parameters:
/// (line, name, count, whether the doc comment above says why, naming its arguments).
fn long_parameter_lists(path: &Path, limit: usize) -> Vec<(usize, String, usize, bool)> {
    let text = outside_tests(path);
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let t = line.trim_start();
        if t.starts_with("//") {
            continue;
        }
        let Some(at) = t.find("fn ") else { continue };
        if at > 0
            && !t[..at].split_whitespace().all(|w| w.starts_with("pub") || ["const", "unsafe", "async"].contains(&w))
        {
            continue;
        }
        let rest = &t[at + 3..];
        let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        // The parameter list: from the first `(` after the name to its match, across lines.
        let joined = lines[i..(i + 40).min(lines.len())].join("\n");
        let from = joined.find(&format!("fn {name}")).unwrap() + 3 + name.len();
        let Some(open) = joined[from..].find('(').map(|k| from + k) else { continue };
        let mut depth = 0;
        let mut close = None;
        for (k, c) in joined[open..].char_indices() {
            match c {
                '(' => depth += 1,
                ')' => {
                    depth -= 1;
                    if depth == 0 {
                        close = Some(open + k);
                        break;
                    }
                }
                _ => {}
            }
        }
        let Some(close) = close else { continue };
        let count = parameter_count(&joined[open + 1..close]);
        if count > limit {
            let doc: Vec<&str> = lines[..i]
                .iter()
                .rev()
                .map(|l| l.trim())
                .take_while(|l| l.starts_with("///") || l.starts_with("#["))
                .filter(|l| l.starts_with("///"))
                .collect();
            let reasoned = doc.iter().any(|l| l.to_lowercase().contains("arguments"));
            out.push((i + 1, name, count, reasoned));
        }
    }
    out
}

#[test]
fn the_parameter_counter_counts_top_level_parameters() {
    assert_eq!(parameter_count(""), 0);
    assert_eq!(parameter_count("&self"), 0);
    assert_eq!(parameter_count("&mut self, a: usize,"), 1);
    assert_eq!(
        parameter_count("a: BTreeMap<String, Vec<(f64, f64)>>, f: impl Fn(f64, f64) -> f64, t: (&[f64], f64)"),
        3
    );
}

#[test]
fn a_function_of_more_than_six_parameters_says_why_in_its_doc_comment() {
    const LIMIT: usize = 6;
    let mut unexplained = Vec::new();
    let mut found = 0;
    for f in sources() {
        for (line, name, count, reasoned) in long_parameter_lists(&f, LIMIT) {
            found += 1;
            if !reasoned {
                unexplained.push(format!("{}:{line} {name}: {count} parameters", f.display()));
            }
        }
    }
    assert!(
        unexplained.is_empty(),
        "functions over {LIMIT} parameters whose doc comment does not say why (a sentence on its arguments), \
         or group them in a type:\n{}",
        unexplained.join("\n")
    );
    // The scan finds them: the Python binding's `run` mirrors the command line's options.
    assert!(found >= 1, "the parameter scan found no long list: is it reading the sources?");
}

/// The lines of code of a file outside its test module: neither blank nor a comment.
fn lines_of_code(text: &str) -> usize {
    let text = text.split("#[cfg(test)]\nmod tests").next().unwrap();
    text.lines().filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with("//")).count()
}

#[test]
fn a_file_of_more_than_500_lines_of_code_says_why_it_stays_one_file() {
    const LIMIT: usize = 500;
    let mut unexplained = Vec::new();
    let mut largest = 0;
    for f in sources() {
        let text = std::fs::read_to_string(&f).unwrap();
        let loc = lines_of_code(&text);
        largest = largest.max(loc);
        let header: String =
            text.lines().take_while(|l| l.starts_with("//!") || l.trim().is_empty()).collect::<Vec<_>>().join(" ");
        if loc > LIMIT && !header.contains("One file") {
            unexplained.push(format!("{}: {loc} lines of code", f.display()));
        }
    }
    assert!(
        unexplained.is_empty(),
        "files over {LIMIT} lines of code whose header (`//!`) does not say why they stay one file \
         (\"One file: ...\"), or split them along their concepts:\n{}",
        unexplained.join("\n")
    );
    assert!(largest > 300, "the largest file has {largest} lines of code: is the scan reading the sources?");
}

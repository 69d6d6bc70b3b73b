//! How the orchestrator scales with the number of tasks: a synthetic pipeline of N tiny
//! tasks (`util.sleep`, 0 ms: the work is all orchestration) plus a stage that reads them
//! all. Per N: parsing and planning (`repro dag`'s work), a dry run on an empty cache, the
//! cold run (every entry written atomically with fsync), a no-op rerun, and a dry run on the
//! full cache. Run: `cargo bench --bench scale [-- N...]` (default 1000 10000 100000).

use repro::pipeline::cache::LockMode;
use repro::pipeline::executor::{run, RunOptions};
use repro::pipeline::parse;
use std::time::Instant;

fn main() {
    let args: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if args.is_empty() { vec![1_000, 10_000, 100_000] } else { args };
    let registry = repro::stages::registry();
    println!(
        "{:>7} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "tasks", "parse_s", "dry_s", "cold_s", "noop_s", "dry2_s", "MB"
    );
    for n in sizes {
        let dir = std::env::temp_dir().join(format!("repro-scale-{n}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let yaml = format!(
            "stages:\n  - name: many\n    kind: util.sleep\n    params: {{x: {{linspace: [1, {n}, {n}]}}, ms: 0}}\n  - name: all\n    kind: util.sleep\n    needs: [many]\n    params: {{x: 0}}\n"
        );
        let file = dir.join("p.yaml");
        std::fs::write(&file, &yaml).unwrap();
        let t = Instant::now();
        let p = parse::parse(&file.display().to_string(), &yaml, &registry).unwrap();
        let parse = t.elapsed().as_secs_f64();
        let opts = |dry_run| RunOptions {
            cache_dir: dir.join("cache"),
            figures_dir: dir.join("figures"),
            tables_dir: dir.join("tables"),
            dry_run,
            progress: false,
            lock: LockMode::Refuse,
            ..Default::default()
        };
        let timed = |dry: bool, expect_computed: usize| {
            let t = Instant::now();
            let r = run(&p, &registry, &opts(dry)).unwrap();
            let dt = t.elapsed().as_secs_f64();
            let computed = r.count(if dry {
                repro::pipeline::report::Status::WouldRun
            } else {
                repro::pipeline::report::Status::Computed
            });
            assert_eq!(computed, expect_computed, "n = {n}, dry = {dry}");
            dt
        };
        let dry = timed(true, n);
        let cold = timed(false, n + 1);
        let noop = timed(false, 0);
        let dry2 = timed(true, 0);
        let mb = dir_size(&dir.join("cache")) as f64 / 1e6;
        println!("{n:>7} {parse:>9.3} {dry:>9.3} {cold:>9.2} {noop:>9.3} {dry2:>9.3} {mb:>9.1}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

fn dir_size(p: &std::path::Path) -> u64 {
    let Ok(rd) = std::fs::read_dir(p) else { return 0 };
    rd.flatten()
        .map(|e| {
            let m = e.metadata().unwrap();
            if m.is_dir() {
                dir_size(&e.path())
            } else {
                m.len()
            }
        })
        .sum()
}

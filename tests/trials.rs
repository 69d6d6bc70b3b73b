//! Randomized trials at scale, each printing its counts (`cargo test --test trials --
//! --nocapture`): 50 SIGKILLs at random moments of a run, publishing included, each
//! resumed to the outputs of an undisturbed run; 34 kinds of damage to a finished run's
//! cache and outputs, each healed by the next run; 300 mutated pipeline files given to the
//! command line, each accepted or refused with a located error, never a crash. The random
//! choices come from a fixed seed, so a failure reproduces.

mod common;
use common::{sleep_pipeline, snapshot, snapshot_untimed, Scratch};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// xorshift64*: a small, seeded generator (the trials must reproduce, not be cryptographic).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Per published file, its name and a hash of its bytes (figures) or of its contents but
/// the timing columns (tables).
type Outputs = Vec<(String, String)>;

fn outputs(s: &Scratch) -> Outputs {
    let hashed = |files: Vec<(String, Vec<u8>)>| -> Vec<(String, String)> {
        files.into_iter().map(|(name, bytes)| (name, blake3::hash(&bytes).to_hex().to_string())).collect()
    };
    let mut all = hashed(snapshot(&s.path("figures")));
    all.extend(hashed(snapshot_untimed(&s.path("tables"))));
    all
}

fn entries(dir: &Path) -> usize {
    let Ok(shards) = std::fs::read_dir(dir.join("cache/objects")) else { return 0 };
    shards.flatten().filter_map(|d| std::fs::read_dir(d.path()).ok()).map(|f| f.count()).sum()
}

#[test]
fn fifty_kills_at_random_moments_resume_to_the_same_outputs() {
    // 12 tasks of 40 ms on 2 workers, a reader, and a figure: about 0.3 s of work.
    let yaml = sleep_pipeline("{linspace: [1, 12, 12]}", 40, "t");
    let reference = Scratch::new("kills-ref");
    reference.write("p.yaml", &yaml);
    let t0 = Instant::now();
    assert_eq!(reference.run("p.yaml", &["--jobs", "2"]).0, 0);
    let mut total = t0.elapsed().as_secs_f64();
    let expected = outputs(&reference);
    // The run's length is the least of three cold runs: the first start of the binary can
    // take several times a later one, and kills timed on it would land after most runs end.
    for i in 0..2 {
        let again = Scratch::new(&format!("kills-ref-{i}"));
        again.write("p.yaml", &yaml);
        let t0 = Instant::now();
        assert_eq!(again.run("p.yaml", &["--jobs", "2"]).0, 0);
        total = total.min(t0.elapsed().as_secs_f64());
    }
    let mut rng = Rng(0x5eed_0001);
    let (mut computing, mut publishing, mut finished) = (0, 0, 0);
    // Where the kills near the end land: narrowed towards the short window in which every
    // task is stored and the run assembles and publishes (a kill after the run's end moves
    // its upper bound down, one while it still computes its lower bound up), so that the
    // window is reached whatever this machine's timing. The other kills land anywhere while
    // the run still computes, before that lower bound: a run under the load of the other
    // tests can be much shorter or longer than the reference runs were.
    let (mut lo, mut hi) = (0.75 * total, 1.1 * total);
    for i in 0..50 {
        let s = Scratch::new(&format!("kills-{i}"));
        s.write("p.yaml", &yaml);
        // Half the kills anywhere in the run, half near its end, where it publishes.
        let near_end = i % 2 == 1;
        let at = if near_end { lo + (hi - lo) * rng.unit() } else { rng.unit() * lo };
        let mut child = s.spawn_run("p.yaml", &["--jobs", "2"]);
        std::thread::sleep(Duration::from_secs_f64(at));
        let alive = child.try_wait().unwrap().is_none();
        let done = entries(&s.dir);
        child.kill().unwrap();
        child.wait().unwrap();
        match (alive, done) {
            (false, _) => {
                finished += 1;
                hi = hi.min(at);
            }
            (true, n) if n >= 14 => publishing += 1,
            _ => {
                computing += 1;
                lo = lo.max(at);
            }
        }
        if hi - lo < 1e-3 {
            (lo, hi) = (0.75 * hi.min(total), 1.1 * total);
        }
        let (code, err, r) = s.run("p.yaml", &["--jobs", "2"]);
        assert_eq!(code, 0, "kill {i} at {at:.3} s: {err}");
        assert!(!err.contains("corrupted"), "kill {i}: no torn entry was visible: {err}");
        assert_eq!(outputs(&s), expected, "kill {i} at {at:.3} s: the outputs of an undisturbed run");
        assert_eq!(std::fs::read_dir(s.path("cache/tmp")).unwrap().count(), 0, "kill {i}: no temporaries left");
        assert_eq!(r.count(None, "failed"), 0);
        let (_, _, r) = s.run("p.yaml", &[]);
        assert_eq!(r.count(None, "computed"), 0, "kill {i}: every entry sound after the resume");
    }
    println!(
        "50 kills (run of {total:.2} s): {computing} while computing, {publishing} after every task was stored (assembling, publishing), {finished} after the run had ended"
    );
    assert!(computing >= 15 && publishing >= 5, "the kills reach every phase: {computing} {publishing}");
}

/// A finished run's directory, copied (cache, outputs, pipeline) for one trial.
fn copy_tree(from: &Path, to: &Path) {
    let st = std::process::Command::new("cp").arg("-a").arg(from).arg(to).status().unwrap();
    assert!(st.success());
}

/// The cache entries of a run's directory, sorted.
fn entry_paths(dir: &Path) -> Vec<PathBuf> {
    let mut all: Vec<PathBuf> = std::fs::read_dir(dir.join("cache/objects"))
        .unwrap()
        .flatten()
        .flat_map(|d| std::fs::read_dir(d.path()).unwrap().flatten().map(|f| f.path()))
        .collect();
    all.sort();
    all
}

fn first_entry(dir: &Path) -> PathBuf {
    entry_paths(dir).remove(0)
}

fn other_entry(dir: &Path) -> PathBuf {
    entry_paths(dir).pop().unwrap()
}

fn manifest(dir: &Path) -> PathBuf {
    let pid = std::fs::read_dir(dir.join("cache/manifests")).unwrap().flatten().next().unwrap().path();
    pid.join("sweep.json")
}

fn replace_with_dir(p: &Path, with_file: bool) {
    let _ = std::fs::remove_file(p);
    let _ = std::fs::remove_dir_all(p);
    std::fs::create_dir_all(p).unwrap();
    if with_file {
        std::fs::write(p.join("junk"), b"junk").unwrap();
    }
}

fn replace_with_file(p: &Path) {
    let _ = std::fs::remove_dir_all(p);
    let _ = std::fs::remove_file(p);
    std::fs::write(p, b"not a directory").unwrap();
}

fn flip_byte(p: &Path, from_end: usize) {
    let mut b = std::fs::read(p).unwrap();
    let n = b.len();
    b[n - 1 - from_end.min(n - 1)] ^= 0x20;
    std::fs::write(p, b).unwrap();
}

fn truncate(p: &Path, keep: f64) {
    let b = std::fs::read(p).unwrap();
    std::fs::write(p, &b[..(b.len() as f64 * keep) as usize]).unwrap();
}

fn link(p: &Path, target: &Path) {
    let _ = std::fs::remove_file(p);
    let _ = std::fs::remove_dir_all(p);
    std::os::unix::fs::symlink(target, p).unwrap();
}

type Damage = (&'static str, fn(&Path));

/// Damage to a finished run's directory (`d`: its root).
const DAMAGE: &[Damage] = &[
    ("entry emptied", |d| truncate(&first_entry(d), 0.0)),
    ("entry cut in half", |d| truncate(&first_entry(d), 0.5)),
    ("entry: a byte of its body altered", |d| flip_byte(&first_entry(d), 5)),
    ("entry: its header altered", |d| {
        let p = first_entry(d);
        let mut b = std::fs::read(&p).unwrap();
        b[0] ^= 0x20;
        std::fs::write(&p, b).unwrap();
    }),
    ("entry deleted", |d| std::fs::remove_file(first_entry(d)).unwrap()),
    ("entry replaced by an empty directory", |d| replace_with_dir(&first_entry(d), false)),
    ("entry replaced by a directory with files", |d| replace_with_dir(&first_entry(d), true)),
    ("entry replaced by a link to another entry", |d| link(&first_entry(d), &other_entry(d))),
    ("entry replaced by a dangling link", |d| link(&first_entry(d), Path::new("/nonexistent/entry"))),
    ("entry holding another entry's bytes", |d| std::fs::copy(other_entry(d), first_entry(d)).map(|_| ()).unwrap()),
    ("an objects shard replaced by a file", |d| replace_with_file(first_entry(d).parent().unwrap())),
    ("objects/ removed", |d| std::fs::remove_dir_all(d.join("cache/objects")).unwrap()),
    ("objects/ replaced by a file", |d| replace_with_file(&d.join("cache/objects"))),
    ("a manifest deleted", |d| std::fs::remove_file(manifest(d)).unwrap()),
    ("a manifest overwritten with garbage", |d| std::fs::write(manifest(d), b"{not json").unwrap()),
    ("a manifest replaced by a directory", |d| replace_with_dir(&manifest(d), true)),
    ("manifests/ removed", |d| std::fs::remove_dir_all(d.join("cache/manifests")).unwrap()),
    ("a pipeline's manifests folder replaced by a file", |d| replace_with_file(manifest(d).parent().unwrap())),
    ("runs/last.json overwritten with garbage", |d| {
        std::fs::write(d.join("cache/runs/last.json"), b"\x00\x01").unwrap()
    }),
    ("runs/ replaced by a file", |d| replace_with_file(&d.join("cache/runs"))),
    ("tmp/ replaced by a file", |d| replace_with_file(&d.join("cache/tmp"))),
    ("tmp/ holding a torn temporary", |d| std::fs::write(d.join("cache/tmp/entry.tmp"), b"half an entr").unwrap()),
    ("the lock file deleted", |d| std::fs::remove_file(d.join("cache/lock")).unwrap()),
    ("lock.info a dangling link", |d| link(&d.join("cache/lock.info"), Path::new("/nonexistent/lock.info"))),
    ("lock.info a directory", |d| replace_with_dir(&d.join("cache/lock.info"), true)),
    ("a figure deleted", |d| std::fs::remove_file(d.join("figures/fig.svg")).unwrap()),
    ("a figure cut in half", |d| truncate(&d.join("figures/fig.svg"), 0.5)),
    ("a figure replaced by a directory", |d| replace_with_dir(&d.join("figures/fig.svg"), true)),
    ("a figure's data overwritten with garbage", |d| std::fs::write(d.join("figures/fig.parquet"), b"PAR1").unwrap()),
    ("a table replaced by a link to a file outside", |d| link(&d.join("tables/sweep.parquet"), &d.join("outside.txt"))),
    ("a table replaced by a dangling link", |d| link(&d.join("tables/sweep.parquet"), Path::new("/nonexistent/t"))),
    ("a stale temporary of a dead run among the tables", |d| {
        std::fs::write(d.join("tables/.repro-4194303-1.tmp"), b"stale").unwrap()
    }),
    ("tables/ removed", |d| std::fs::remove_dir_all(d.join("tables")).unwrap()),
    ("a run of the history cut in half", |d| {
        let run = std::fs::read_dir(d.join("cache/runs"))
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .find(|p| p.file_name().unwrap().to_string_lossy().starts_with("run-"))
            .unwrap();
        truncate(&run, 0.5);
    }),
];

#[test]
fn thirty_four_kinds_of_damage_to_the_cache_and_outputs_heal_on_the_next_run() {
    let yaml = sleep_pipeline("[1, 2, 3]", 0, "t");
    let pristine = Scratch::new("damage-pristine");
    pristine.write("p.yaml", &yaml);
    pristine.write("outside.txt", "a file outside the outputs");
    assert_eq!(pristine.run("p.yaml", &[]).0, 0);
    let expected = outputs(&pristine);
    assert!(DAMAGE.len() >= 30);
    let mut healed = 0;
    for (i, (what, damage)) in DAMAGE.iter().enumerate() {
        let s = Scratch::new(&format!("damage-{i}"));
        std::fs::remove_dir_all(&s.dir).unwrap();
        copy_tree(&pristine.dir, &s.dir);
        damage(&s.dir);
        let (code, err, _) = s.run("p.yaml", &[]);
        assert_eq!(code, 0, "{what}: the run carries on: {err}");
        assert_eq!(outputs(&s), expected, "{what}: the outputs of an undamaged run");
        assert_eq!(std::fs::read(s.path("outside.txt")).unwrap(), b"a file outside the outputs", "{what}");
        // Healed: the next run finds everything in place and computes nothing.
        let (code, err, r) = s.run("p.yaml", &[]);
        assert_eq!(code, 0, "{what}: {err}");
        assert_eq!(r.count(None, "computed"), 0, "{what}: healed by the first rerun: {err}");
        assert!(!err.contains("corrupted"), "{what}: {err}");
        healed += 1;
    }
    println!("{healed} of {} kinds of damage healed by one run, outputs identical", DAMAGE.len());
}

/// Edits a pipeline file as a careless hand might: a byte replaced, deleted, duplicated,
/// a line dropped or repeated, a number changed, a key misspelt.
fn mutate(text: &str, rng: &mut Rng) -> String {
    let mut b = text.as_bytes().to_vec();
    for _ in 0..1 + rng.below(3) {
        if b.is_empty() {
            b.push(b'x');
        }
        let n = b.len();
        let at = rng.below(n).min(b.len().saturating_sub(1));
        match rng.below(8) {
            0 => {
                let bytes = b" :-[]{},\n0123456789.aeZ#&*\"'\t";
                b[at] = bytes[rng.below(bytes.len())];
            }
            1 => {
                b.remove(at);
            }
            2 => b.insert(at, b[at]),
            3 => {
                // Drop a line.
                let s = String::from_utf8_lossy(&b).to_string();
                let mut lines: Vec<&str> = s.lines().collect();
                if !lines.is_empty() {
                    lines.remove(rng.below(lines.len()));
                }
                b = lines.join("\n").into_bytes();
            }
            4 => {
                // Repeat a line.
                let s = String::from_utf8_lossy(&b).to_string();
                let mut lines: Vec<&str> = s.lines().collect();
                if !lines.is_empty() {
                    let k = rng.below(lines.len());
                    lines.insert(k, lines[k]);
                }
                b = lines.join("\n").into_bytes();
            }
            5 => {
                // A number made extreme, negative or not a number.
                let s = String::from_utf8_lossy(&b).to_string();
                let digits: Vec<usize> = s.char_indices().filter(|(_, c)| c.is_ascii_digit()).map(|(i, _)| i).collect();
                if !digits.is_empty() {
                    let i = digits[rng.below(digits.len())];
                    let with = ["1e300", "-7", "0", "nan", ".inf", "1e-320", "99999999999"][rng.below(7)];
                    b = format!("{}{}{}", &s[..i], with, &s[i + 1..]).into_bytes();
                }
            }
            6 => b.insert(at, 0xff),
            _ => {
                let s = String::from_utf8_lossy(&b).to_string();
                b = s.replacen("kind", ["kidn", "knd", "Kind"][rng.below(3)], 1).into_bytes();
            }
        }
    }
    String::from_utf8_lossy(&b).to_string()
}

#[test]
fn three_hundred_mutated_pipeline_files_are_accepted_or_refused_with_a_location() {
    let base = "stages:\n  - name: sweep\n    kind: util.sleep\n    params: {x: [1, 2.5, 4], ms: 0}\n  - name: after\n    kind: util.sleep\n    needs: [sweep]\n    params: {x: 7}\n  - name: fig\n    kind: figure\n    needs: [sweep]\n    params:\n      title: \"t\"\n      x_label: \"x\"\n      y_label: \"rows\"\n      layers:\n        - data: {from: sweep, x: x, y: upstream_rows, label: \"sweep\"}\n";
    let s = Scratch::new("mutants");
    let mut rng = Rng(0x5eed_0003);
    let (mut accepted, mut refused) = (0, 0);
    for i in 0..300 {
        let text = mutate(base, &mut rng);
        std::fs::write(s.path("m.yaml"), &text).unwrap();
        let out = s.repro(&["run", "m.yaml", "--dry-run", "-q", "--cache", "c"]);
        let err = String::from_utf8_lossy(&out.stderr);
        match out.status.code() {
            Some(0) => accepted += 1,
            Some(2) => {
                // Located: file, line and column (or the byte offset of invalid UTF-8).
                assert!(err.contains("m.yaml:"), "mutant {i}: the error names the file:\n{text}\n{err}");
                refused += 1;
            }
            other => panic!("mutant {i} exits with {other:?} (0 or 2 expected):\n{text}\n{err}"),
        }
    }
    println!("300 mutated pipeline files: {accepted} accepted, {refused} refused with a located error");
    assert!(accepted >= 10 && refused >= 100, "{accepted} {refused}");
}

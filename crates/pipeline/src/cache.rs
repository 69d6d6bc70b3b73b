//! The content-addressed task cache.
//!
//! Layout under the cache directory:
//! - `objects/<k0k1>/<key>.entry`: one task's result. The first line is
//!   `repro-entry-1 <blake3 of the rest>`; the rest is JSON (key, kind, version, parameters,
//!   output hash, output). Entries are verified on every read: a corrupted or truncated
//!   entry is reported and recomputed.
//! - `manifests/<pipeline id>/<stage>.json`: what a stage's points were at its last run
//!   (used to explain why a task is stale).
//! - `runs/last.json`: the report of the last run.
//! - `tmp/`: files being written; renamed into place when complete (atomic writes).
//! - `worker-tmp/`: the same for SLURM workers (cleaned only of day-old files).
//! - `slurm/`: task specifications, task lists, logs and failure records of the SLURM
//!   executor (see [`super::slurm`]).
//! - `lock`: held (an OS file lock) by the one `repro` coordinator that uses this cache.

use super::key::{content_hash, Hash};
use super::kind::Output;
use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::collections::BTreeMap;
use std::fs::{self, File};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

const ENTRY_MAGIC: &str = "repro-entry-1";
/// Where SLURM workers stage their atomic writes.
const WORKER_TMP: &str = "worker-tmp";

/// Writes `bytes` to `path` atomically: a temporary file in `tmp_dir` (same file system),
/// flushed to disk, then renamed over `path`.
pub fn write_atomic(path: &Path, bytes: &[u8], tmp_dir: &Path) -> Result<()> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    create_dirs(tmp_dir, n)?;
    if let Some(parent) = path.parent() {
        create_dirs(parent, n).with_context(|| format!("writing {}", path.display()))?;
    }
    let tmp = tmp_dir.join(format!(".repro-{}-{n}.tmp", std::process::id()));
    let result = (|| -> Result<()> {
        let mut f = File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        super::fault::point("atomic.before_rename");
        move_aside_non_file(path, n)?;
        fs::rename(&tmp, path)?;
        super::fault::point("atomic.after_rename");
        Ok(())
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result.with_context(|| format!("writing {}", path.display()))
}

/// Reads a file that must be a regular one (following links): anything else (a FIFO, a
/// socket, a device, a directory) is an error of kind `InvalidData` instead of a read that
/// blocks forever (a FIFO's `open` waits for a writer). Every file the tool reads back from
/// the cache or its outputs is read through this.
pub fn read_regular(path: &Path) -> std::io::Result<Vec<u8>> {
    let meta = fs::metadata(path)?;
    if !meta.is_file() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("{} is not a regular file", path.display()),
        ));
    }
    fs::read(path)
}

/// Creates `dir` and its missing parents. Where that fails because a file, or a link that
/// leads nowhere, stands where one of them should be, that is moved aside (as by
/// `move_aside_non_file`) and the directories are created: damage heals instead of failing
/// every run. A link to a directory is followed, as a user may have made it.
fn create_dirs(dir: &Path, n: u64) -> Result<()> {
    if fs::create_dir_all(dir).is_ok() {
        return Ok(());
    }
    let mut ancestors: Vec<&Path> = dir.ancestors().filter(|a| !a.as_os_str().is_empty()).collect();
    ancestors.reverse();
    for a in ancestors {
        match fs::metadata(a) {
            Ok(m) if m.is_dir() => continue,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound && fs::symlink_metadata(a).is_err() => break,
            _ => {
                let mut aside = a.as_os_str().to_owned();
                aside.push(format!(".damaged-{}-{n}", std::process::id()));
                match fs::rename(a, &aside) {
                    Ok(()) => eprintln!(
                        "repro: warning: {} was not a directory; moved aside to {}",
                        a.display(),
                        aside.to_string_lossy()
                    ),
                    // Another task of this run moved it first.
                    Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
                    Err(e) => return Err(e).with_context(|| format!("moving {} aside", a.display())),
                }
                break;
            }
        }
    }
    fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    Ok(())
}

/// Whatever stands at `path` and is neither a file nor a link (a directory, a fifo, a
/// socket) is renamed to `<path>.damaged-<pid>-<n>` beside it, with a warning, so that the
/// write lands: damage heals on the next write instead of failing every run, and nothing is
/// deleted. (A link is replaced by the rename itself, never followed.)
fn move_aside_non_file(path: &Path, n: u64) -> Result<()> {
    let Ok(meta) = fs::symlink_metadata(path) else { return Ok(()) };
    let kind = meta.file_type();
    if kind.is_file() || kind.is_symlink() {
        return Ok(());
    }
    let mut aside = path.as_os_str().to_owned();
    aside.push(format!(".damaged-{}-{n}", std::process::id()));
    let aside = std::path::PathBuf::from(aside);
    fs::rename(path, &aside)?;
    let what = if kind.is_dir() { "a directory" } else { "not a file" };
    eprintln!("repro: warning: {} was {what}; moved aside to {}", path.display(), aside.display());
    Ok(())
}

/// A cached task result.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Entry {
    pub key: Hash,
    pub kind: String,
    pub version: u32,
    pub params: Value,
    pub output_hash: Hash,
    pub output: Output,
    pub wall_time_s: f64,
}

impl Entry {
    pub fn new(key: Hash, kind: &str, version: u32, params: Value, output: Output, wall_time_s: f64) -> Self {
        let output_hash = output_hash(&output);
        Entry { key, kind: kind.to_string(), version, params, output_hash, output, wall_time_s }
    }
}

/// Columns that record how a result was obtained rather than what it is (timings): they
/// are stored and published but left out of the output hash, so that recomputing a task
/// with the same result still cuts off everything downstream.
pub const VOLATILE_COLUMNS: &[&str] = &["wall_time_s"];

/// The hash of an output's canonical bytes without its volatile columns (what early
/// cutoff compares).
pub fn output_hash(output: &Output) -> Hash {
    if output.table.columns.iter().any(|(n, _)| VOLATILE_COLUMNS.contains(&n.as_str())) {
        let mut stable = output.clone();
        stable.table.columns.retain(|(n, _)| !VOLATILE_COLUMNS.contains(&n.as_str()));
        return content_hash(&serde_json::to_vec(&stable).expect("outputs serialise"));
    }
    content_hash(&serde_json::to_vec(output).expect("outputs serialise"))
}

/// Why a cache lookup found nothing usable.
#[derive(Debug, Clone, PartialEq)]
pub enum Miss {
    Absent,
    Corrupted(String),
}

pub struct Cache {
    pub root: PathBuf,
    tmp: PathBuf,
    _lock: Option<File>,
    _dir_lock: Option<File>,
}

/// How to behave when another `repro` holds the cache.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LockMode {
    Wait,
    Refuse,
}

#[derive(Debug, thiserror::Error)]
#[error("the cache {dir} is in use by another repro ({holder}); rerun when it has finished, or omit --no-wait to wait for it")]
pub struct CacheBusy {
    pub dir: String,
    pub holder: String,
}

/// The cache never writes through a link it did not create: a symbolic link standing where
/// one of its own directories (or an object shard) belongs is removed (the link only, never
/// its target), with a warning, and the directory is made afresh when next written.
fn unlink_foreign_links(root: &Path) {
    let mut paths: Vec<PathBuf> = ["objects", "manifests", "runs", "tmp", WORKER_TMP, "slurm", "lock.info"]
        .iter()
        .map(|d| root.join(d))
        .collect();
    if let Ok(shards) = fs::read_dir(root.join("objects")) {
        paths.extend(shards.filter_map(|e| e.ok().map(|e| e.path())));
    }
    if let Ok(pipelines) = fs::read_dir(root.join("manifests")) {
        paths.extend(pipelines.filter_map(|e| e.ok().map(|e| e.path())));
    }
    for p in paths {
        if fs::symlink_metadata(&p).is_ok_and(|m| m.file_type().is_symlink()) {
            eprintln!("repro: warning: {} is a symbolic link the cache did not create; removing the link", p.display());
            let _ = fs::remove_file(&p);
        }
    }
}

/// Why the cache could not be opened for a run.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    /// Another run holds it (and the caller asked not to wait).
    #[error(transparent)]
    Busy(CacheBusy),
    /// It cannot be created, locked or written.
    #[error(transparent)]
    Io(#[from] anyhow::Error),
}

/// Takes an exclusive lock on `file` (the cache's lock file or directory): at once, or, held
/// by another run, refused (`LockMode::Refuse`) or waited for, saying who holds it.
fn lock_exclusive(file: &File, root: &Path, mode: LockMode) -> Result<(), OpenError> {
    match file.try_lock() {
        Ok(()) => Ok(()),
        Err(fs::TryLockError::WouldBlock) => {
            let holder = read_regular(&root.join("lock.info"))
                .map(|b| String::from_utf8_lossy(&b).into_owned())
                .unwrap_or_else(|_| "unknown process".into());
            let holder = holder.trim().to_string();
            if mode == LockMode::Refuse {
                return Err(OpenError::Busy(CacheBusy { dir: root.display().to_string(), holder }));
            }
            eprintln!(
                "repro: the cache {} is in use by another repro ({holder}); waiting for it to finish",
                root.display()
            );
            file.lock().context("locking the cache")?;
            Ok(())
        }
        Err(fs::TryLockError::Error(e)) => Err(anyhow::Error::new(e).context("locking the cache").into()),
    }
}

impl Cache {
    /// Opens the cache for reading and writing, holding its lock for as long as it lives.
    pub fn open(root: &Path, mode: LockMode) -> Result<Cache, OpenError> {
        fs::create_dir_all(root).with_context(|| format!("creating the cache directory {}", root.display()))?;
        let lock_path = root.join("lock");
        // A directory or a fifo standing for the lock file would fail every run: moved aside.
        move_aside_non_file(&lock_path, 0).with_context(|| format!("moving {} aside", lock_path.display()))?;
        let file =
            fs::OpenOptions::new().create(true).truncate(false).write(true).read(true).open(&lock_path).with_context(
                || {
                    format!(
                        "the cache {} is not writable (opening {}); a run stores its results there: \
                     give a writable --cache, or read this one with `repro status`",
                        root.display(),
                        lock_path.display()
                    )
                },
            )?;
        lock_exclusive(&file, root, mode)?;
        // The directory itself is locked too: deleting `lock` from under a run (a second run
        // then creates and locks a new file) does not let a second run in.
        let dir = fs::File::open(root).with_context(|| format!("opening the cache directory {}", root.display()))?;
        lock_exclusive(&dir, root, mode)?;
        unlink_foreign_links(root);
        let cache = Cache { root: root.to_path_buf(), tmp: root.join("tmp"), _lock: Some(file), _dir_lock: Some(dir) };
        // Written like every other file: a rename replaces whatever stands there, a link
        // included, without writing through it. It only tells a waiting run who holds the
        // lock: a full disk fails the entries the run stores, each recorded, not the run.
        if let Err(e) =
            write_atomic(&root.join("lock.info"), format!("pid {}", std::process::id()).as_bytes(), &cache.tmp_dir())
        {
            eprintln!("repro: warning: {e:#}");
        }
        // Files left in tmp/ by a killed run are incomplete: nobody else can be writing them.
        let _ = fs::remove_dir_all(cache.tmp_dir());
        fs::create_dir_all(cache.tmp_dir()).with_context(|| format!("creating {}", cache.tmp_dir().display()))?;
        // SLURM workers write through worker-tmp/; a worker of a killed coordinator may
        // still be writing there, so only files older than a day are removed.
        if let Ok(files) = fs::read_dir(root.join(WORKER_TMP)) {
            let day = std::time::Duration::from_secs(86_400);
            for f in files.flatten() {
                let old = f.metadata().and_then(|m| m.modified()).is_ok_and(|t| t.elapsed().is_ok_and(|a| a > day));
                if old {
                    let _ = fs::remove_file(f.path());
                }
            }
        }
        Ok(cache)
    }

    /// Opens the cache for reading only, without the lock (status, dry runs).
    pub fn open_read_only(root: &Path) -> Cache {
        Cache { root: root.to_path_buf(), tmp: root.join("tmp"), _lock: None, _dir_lock: None }
    }

    /// Opens the cache for a SLURM worker: no lock (the coordinator holds it), writes
    /// through its own temporary directory with the same atomic protocol.
    pub fn open_worker(root: &Path) -> Result<Cache> {
        if !root.join("objects").is_dir() && !root.join("lock").exists() {
            bail!("{} is not a repro cache (no lock file, no objects/)", root.display());
        }
        let tmp = root.join(WORKER_TMP);
        fs::create_dir_all(&tmp).with_context(|| format!("creating {}", tmp.display()))?;
        Ok(Cache { root: root.to_path_buf(), tmp, _lock: None, _dir_lock: None })
    }

    pub fn tmp_dir(&self) -> PathBuf {
        self.tmp.clone()
    }

    fn objects_dir(&self) -> PathBuf {
        self.root.join("objects")
    }

    pub fn entry_path(&self, key: &str) -> PathBuf {
        self.objects_dir().join(&key[..2]).join(format!("{key}.entry"))
    }

    pub fn get(&self, key: &str) -> Result<Entry, Miss> {
        if !is_key(key) {
            return Err(Miss::Corrupted(format!("`{key}` is not a task key")));
        }
        let path = self.entry_path(key);
        let bytes = match read_regular(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(Miss::Absent),
            Err(e) => return Err(Miss::Corrupted(format!("unreadable: {e}"))),
        };
        decode_entry(key, &bytes).map_err(|e| Miss::Corrupted(e.to_string()))
    }

    pub fn put(&self, entry: &Entry) -> Result<()> {
        let body = serde_json::to_vec(entry)?;
        let mut bytes = format!("{ENTRY_MAGIC} {}\n", content_hash(&body)).into_bytes();
        bytes.extend_from_slice(&body);
        write_atomic(&self.entry_path(&entry.key), &bytes, &self.tmp_dir())
    }

    pub fn manifest_path(&self, pipeline_id: &str, stage: &str) -> PathBuf {
        self.root.join("manifests").join(pipeline_id).join(format!("{stage}.json"))
    }

    pub fn read_manifest(&self, pipeline_id: &str, stage: &str) -> Option<StageManifest> {
        let bytes = read_regular(&self.manifest_path(pipeline_id, stage)).ok()?;
        serde_json::from_slice(&bytes).ok()
    }

    /// Writes a stage's manifest unless it already holds the same (a no-op rerun of a
    /// large sweep then writes nothing).
    pub fn write_manifest(&self, pipeline_id: &str, stage: &str, m: &StageManifest) -> Result<()> {
        let path = self.manifest_path(pipeline_id, stage);
        let bytes = serde_json::to_vec_pretty(m)?;
        if read_regular(&path).is_ok_and(|old| old == bytes) {
            return Ok(());
        }
        write_atomic(&path, &bytes, &self.tmp_dir())
    }

    /// Every key that has an entry.
    pub fn all_keys(&self) -> Result<Vec<Hash>> {
        let mut keys = Vec::new();
        let Ok(dirs) = fs::read_dir(self.objects_dir()) else { return Ok(keys) };
        for d in dirs {
            for f in fs::read_dir(d?.path())? {
                let name = f?.file_name().to_string_lossy().to_string();
                if let Some(k) = name.strip_suffix(".entry") {
                    keys.push(k.to_string());
                }
            }
        }
        keys.sort();
        Ok(keys)
    }

    pub fn remove(&self, key: &str) -> Result<u64> {
        let path = self.entry_path(key);
        let size = fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        fs::remove_file(&path)?;
        Ok(size)
    }
}

/// Whether `s` has the form of a task key (64 lowercase hex digits).
pub fn is_key(s: &str) -> bool {
    s.len() == 64 && s.bytes().all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
}

/// Decodes and verifies an entry's bytes: header, content hash (checked before anything
/// is deserialised), key and output hash.
pub fn decode_entry(key: &str, bytes: &[u8]) -> Result<Entry> {
    let nl = bytes.iter().position(|&b| b == b'\n').context("truncated entry (no header line)")?;
    let header = std::str::from_utf8(&bytes[..nl]).context("header is not text")?;
    let Some(hash) = header.strip_prefix(&format!("{ENTRY_MAGIC} ")) else {
        bail!("not a repro cache entry (header `{}`)", header.chars().take(40).collect::<String>());
    };
    let body = &bytes[nl + 1..];
    let actual = content_hash(body);
    if actual != hash {
        bail!(
            "content hash mismatch (stored {}…, actual {}…): truncated or modified",
            hash.chars().take(12).collect::<String>(),
            &actual[..12]
        );
    }
    let entry: Entry = serde_json::from_slice(body).context("entry does not parse")?;
    if entry.key != key {
        bail!("entry holds key {} but is stored under {key}", entry.key);
    }
    if output_hash(&entry.output) != entry.output_hash {
        bail!("output hash mismatch");
    }
    Ok(entry)
}

/// What a stage's points were when it last ran.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct StageManifest {
    pub kind: String,
    pub version: u32,
    pub inputs: BTreeMap<String, Hash>,
    pub points: Vec<ManifestPoint>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ManifestPoint {
    pub label: String,
    pub params: Value,
    pub key: Hash,
    /// The hashes of the rows it read of the stages it needs row by row, by stage.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub inputs: BTreeMap<String, Hash>,
}

#[cfg(test)]
mod tests {

    #[test]
    fn a_header_with_a_multibyte_character_in_its_hash_is_rejected_not_a_panic() {
        // Found by tests/fuzz.rs: a byte flipped into the stored hash made it `…83\u{fffd}ac…`,
        // and the message sliced it at byte 12, inside the character.
        let mut bytes =
            format!("{ENTRY_MAGIC} 47f67883a83\u{fffd}aca3fd900525be58b5f26690ea91c7244d089e18860eeec54389\n")
                .into_bytes();
        bytes.extend_from_slice(b"{}");
        let err = decode_entry(&"0".repeat(64), &bytes).unwrap_err().to_string();
        assert!(err.contains("content hash mismatch"), "{err}");
    }

    use super::*;
    use crate::table::Table;

    #[test]
    fn timings_do_not_count_in_the_output_hash() {
        let a = Output::from(Table::new().with_f64("mu_star", vec![0.5]).with_f64("wall_time_s", vec![1.0]));
        let b = Output::from(Table::new().with_f64("mu_star", vec![0.5]).with_f64("wall_time_s", vec![2.0]));
        let c = Output::from(Table::new().with_f64("mu_star", vec![0.6]).with_f64("wall_time_s", vec![1.0]));
        assert_eq!(output_hash(&a), output_hash(&b));
        assert_ne!(output_hash(&a), output_hash(&c));
    }
}

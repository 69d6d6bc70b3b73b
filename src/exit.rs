//! How `repro` ends: every outcome and every kind of error of the command line, and the
//! exit code of each, in one place.
//!
//! | code | meaning |
//! |---|---|
//! | 0 | success |
//! | 1 | some tasks failed (the others ran; the report names the failures) |
//! | 2 | invalid input: a pipeline file, a parameter or an option (nothing was run) |
//! | 3 | the cache is in use by another run (`--no-wait`) |
//! | 4 | any other error: the file system, the cache, SLURM (outputs written where possible) |
//! | 5 | every task ran, and a thesis claim that held before no longer holds |

use pipeline::cache::CacheBusy;
use pipeline::executor::{RunError, UsageError};
use pipeline::spec::InvalidPipeline;
use std::process::ExitCode;

/// How a command ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    Success,
    FailedTasks,
    InvalidInput,
    CacheBusy,
    Error,
    Regression,
}

impl Exit {
    pub fn code(self) -> u8 {
        match self {
            Exit::Success => 0,
            Exit::FailedTasks => 1,
            Exit::InvalidInput => 2,
            Exit::CacheBusy => 3,
            Exit::Error => 4,
            Exit::Regression => 5,
        }
    }
}

impl From<Exit> for ExitCode {
    fn from(e: Exit) -> ExitCode {
        ExitCode::from(e.code())
    }
}

/// Why a command could not do what it was asked.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// A pipeline file (or a parameter set over it) is invalid: every error, located.
    #[error("{0}")]
    InvalidPipeline(#[from] InvalidPipeline),
    /// An option or argument names something that does not exist, or is malformed.
    #[error("{0}")]
    Usage(String),
    /// Another run holds the cache.
    #[error(transparent)]
    CacheBusy(#[from] CacheBusy),
    /// The one task of `repro point` failed, panicked, ran out of time or was refused its
    /// memory (as a task of a run fails: exit code 1).
    #[error("the point was not computed: {0}")]
    TaskFailed(#[from] pipeline::task::TaskError),
    /// Anything else (the file system, the cache, SLURM), with its chain of causes.
    #[error("{0:#}")]
    Other(#[from] anyhow::Error),
}

impl From<UsageError> for CliError {
    fn from(e: UsageError) -> Self {
        CliError::Usage(e.to_string())
    }
}

impl From<RunError> for CliError {
    fn from(e: RunError) -> Self {
        match e {
            RunError::Usage(u) => u.into(),
            RunError::CacheBusy(b) => CliError::CacheBusy(b),
            RunError::Io(e) => CliError::Other(e),
        }
    }
}

impl From<std::io::Error> for CliError {
    fn from(e: std::io::Error) -> Self {
        CliError::Other(e.into())
    }
}

impl From<serde_json::Error> for CliError {
    fn from(e: serde_json::Error) -> Self {
        CliError::Other(e.into())
    }
}

impl CliError {
    /// A usage error with this message.
    pub fn usage(message: impl Into<String>) -> Self {
        CliError::Usage(message.into())
    }

    pub fn exit(&self) -> Exit {
        match self {
            CliError::InvalidPipeline(_) | CliError::Usage(_) => Exit::InvalidInput,
            CliError::CacheBusy(_) => Exit::CacheBusy,
            CliError::TaskFailed(_) => Exit::FailedTasks,
            CliError::Other(_) => Exit::Error,
        }
    }

    /// Prints the error to stderr and returns its exit code.
    pub fn report(&self) -> ExitCode {
        match self {
            CliError::InvalidPipeline(inv) => {
                eprintln!("{inv}");
                eprintln!("repro: the pipeline is invalid; nothing was run");
            }
            other => eprintln!("repro: error: {other}"),
        }
        self.exit().into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_of_error_has_its_exit_code() {
        let invalid = CliError::from(InvalidPipeline(Vec::new()));
        let busy = CliError::from(RunError::CacheBusy(CacheBusy { dir: "c".into(), holder: "pid 1".into() }));
        let usage = CliError::from(RunError::Usage(UsageError::UnknownStage("--target x".into())));
        let io = CliError::from(std::io::Error::other("disk full"));
        let failed = CliError::from(pipeline::task::TaskError::TimedOut { limit_s: 1.0 });
        let codes: Vec<u8> = [invalid, usage, busy, io, failed].iter().map(|e| e.exit().code()).collect();
        assert_eq!(codes, vec![2, 2, 3, 4, 1]);
    }
}

//! The orchestrator: pipeline files, the stage graph, cache keys, the cache, the executor
//! and the run report. It knows nothing of physics: stage kinds plug in through
//! [`kind::Kind`].
pub mod adaptive;
pub mod backend;
pub mod cache;
pub mod diff;
pub mod executor;
pub mod fault;
pub mod gc;
pub mod graph;
pub mod key;
pub mod kind;
pub mod parse;
pub mod plan;
pub mod publish;
pub mod reason;
pub mod report;
pub mod schema;
pub mod slurm;
pub mod spec;
pub mod table;
pub mod task;
pub mod verify;

//! Running a sweep: the pending tasks in a thread pool with progress and ETA, each stored as
//! it finishes, then the tables and the picture (`execute`); the tables of a sharded sweep once
//! every shard is done (`merge`); the progress of a directory (`status`); Slurm job scripts
//! (`slurm`); progress bars (`progress`); a refined level's midpoints certified without runs
//! (`certify`, opt-in).
//!
//! May use: `spec`, `store`, `map`, `tables`, `pictures`. Used by: the CLI.
mod certify;
pub mod execute;
pub mod merge;
pub mod progress;
pub mod slurm;
pub mod status;

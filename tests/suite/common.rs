//! Helpers shared by the end-to-end test binaries.
use polars::prelude::*;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::OnceLock;

/// The `droplet` binary under test.
pub fn droplet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_droplet"))
}

/// A Parquet table.
#[allow(dead_code)]
pub fn read(path: &Path) -> DataFrame {
    ParquetReader::new(std::fs::File::open(path).unwrap())
        .finish()
        .unwrap()
}

/// Rewrites one string column of a Parquet table: `f(row, old) -> new` (a false label for
/// `droplet audit` to catch), keeping its metadata (the spec a map's tables carry).
#[allow(dead_code)]
pub fn edit(path: &Path, column: &str, f: impl Fn(usize, Option<&str>) -> Option<String>) {
    use droplet_sweep::tables::sweep_tables::{read_metadata, write_parquet};
    let meta: Vec<(String, String)> = read_metadata(path).unwrap().into_iter().collect();
    let mut df = read(path);
    let old = df.column(column).unwrap().str().unwrap().clone();
    let new: Vec<Option<String>> = (0..df.height()).map(|i| f(i, old.get(i))).collect();
    df.with_column(Column::new(column.into(), new)).unwrap();
    write_parquet(&mut df, path, meta).unwrap();
}

/// A table without its wall-clock column (the one value that differs between two runs).
#[allow(dead_code)]
pub fn table_without_wall(path: &Path) -> DataFrame {
    let df = read(path);
    if df.schema().contains("wall_s") {
        df.drop("wall_s").unwrap()
    } else {
        df
    }
}

// Not every test binary uses every helper below.

/// Runs the binary to the end.
#[allow(dead_code)]
pub fn run(args: &[&str]) -> Output {
    droplet().args(args).output().expect("binary runs")
}

/// Writes a spec (or any text) file `name` into `dir`.
#[allow(dead_code)]
pub fn write_spec(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// The one JSON object a successful `--json` command printed.
#[allow(dead_code)]
pub fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

/// Starts `droplet sweep SPEC --out OUT --jobs 2 --json` without waiting (to be killed).
#[allow(dead_code)]
pub fn sweep_in_background(spec: &Path, out: &Path) -> Child {
    droplet()
        .args([
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--jobs",
            "2",
            "--json",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// Starts `droplet sweep SPEC --out OUT` again and again, each time killing it with SIGKILL
/// after a fixed-seed random wait below `full_ms` (an uninterrupted sweep's length), until
/// `kills` sweeps were interrupted or `max_tries` were started; a sweep that finished first is
/// started over from an empty directory. Returns `(kills, tries)`.
#[allow(dead_code)]
pub fn kill_at_random_moments(
    spec: &Path,
    out: &Path,
    full_ms: u64,
    kills: usize,
    max_tries: usize,
) -> (usize, usize) {
    let mut x: u64 = 20261127;
    let (mut killed, mut tries) = (0, 0);
    while killed < kills && tries < max_tries {
        tries += 1;
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let wait = 20 + (x >> 33) % full_ms.max(50);
        let mut child = sweep_in_background(spec, out);
        std::thread::sleep(std::time::Duration::from_millis(wait));
        if child.try_wait().unwrap().is_none() {
            child.kill().unwrap(); // SIGKILL
            killed += 1;
        }
        child.wait().unwrap();
        if out.join("runs.parquet").exists() {
            std::fs::remove_dir_all(out).unwrap();
        }
    }
    (killed, tries)
}

/// `droplet sweep SPEC --out OUT --json --no-plot EXTRA...`, run to the end.
#[allow(dead_code)]
pub fn sweep(spec: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
        "--no-plot",
    ];
    args.extend_from_slice(extra);
    run(&args)
}

/// The smoke sweep (`sweeps/smoke.yaml`: 16 points x 4 initial conditions at N = 96), run
/// once per test process by `droplet sweep ... --json`: its directory and the summary it
/// printed. Shared read-only; a test that writes into a sweep directory copies it first
/// ([`copy_sweep`]).
#[allow(dead_code)]
pub fn smoke_sweep() -> &'static (PathBuf, serde_json::Value) {
    static SMOKE: OnceLock<(PathBuf, serde_json::Value)> = OnceLock::new();
    SMOKE.get_or_init(|| {
        // Kept for the whole process (a static is never dropped), under cargo's own
        // directory for the tests' temporary files.
        let dir = tempfile::Builder::new()
            .prefix("smoke-")
            .tempdir_in(env!("CARGO_TARGET_TMPDIR"))
            .unwrap()
            .keep();
        let out = dir.join("smoke");
        let summary = json(&run(&[
            "sweep",
            "sweeps/smoke.yaml",
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]));
        (out, summary)
    })
}

/// Copies a sweep directory (its tables, pictures and stored runs) to `to`.
#[allow(dead_code)]
pub fn copy_sweep(from: &Path, to: &Path) {
    std::fs::create_dir_all(to.join("runs")).unwrap();
    for dir in [from.to_path_buf(), from.join("runs")] {
        for e in std::fs::read_dir(&dir).unwrap().flatten() {
            if e.file_type().unwrap().is_file() {
                let rel = e.path().strip_prefix(from).unwrap().to_path_buf();
                std::fs::copy(e.path(), to.join(rel)).unwrap();
            }
        }
    }
}

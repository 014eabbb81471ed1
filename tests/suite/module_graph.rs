//! The folders of each library crate depend one way, in the order their `lib.rs` lists them
//! (numerics -> model -> stepping -> contract -> reduced -> roots -> runs -> continuation in
//! the solver crate; spec -> store -> map -> tables -> audit -> pictures -> execution -> studies -> bench
//! in the sweep crate), the module graph has no cycle, and neither have the files inside
//! each folder.
//!
//! A module is a top-level file or folder of `src/` (`stepping/comoving_etd.rs` belongs to
//! `stepping`); it depends on another when its code (not its comments, not its `#[cfg(test)]`
//! part) names `crate::other`. Inside a folder, a file depends on another of the folder when
//! it names `crate::folder::other` or `super::other`. A cycle fails the test with the
//! modules on it.
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Module -> the modules it names.
type Graph = BTreeMap<String, BTreeSet<String>>;

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The names following `crate::` in `code`, and in `use crate::{a, b::c}` groups.
fn named_modules(code: &str) -> BTreeSet<String> {
    named_after(code, "crate::")
}

/// The names following `prefix` in `code`, and in `use prefix{a, b::c}` groups.
fn named_after(code: &str, prefix: &str) -> BTreeSet<String> {
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut out = BTreeSet::new();
    for (i, _) in code.match_indices(prefix) {
        // `prefix` as a path's start, not inside a longer one (`super::` in `a::super::`).
        let before = code[..i].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
            continue;
        }
        let rest = &code[i + prefix.len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let name = ident(item.trim());
                if !name.is_empty() {
                    out.insert(name);
                }
            }
        } else {
            let name = ident(rest);
            if !name.is_empty() {
                out.insert(name);
            }
        }
    }
    out
}

fn graph(src: &Path) -> Graph {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut g = Graph::new();
    for f in &files {
        let top = module_of(f.strip_prefix(src).unwrap());
        if top == "lib" || top == "main" {
            continue;
        }
        let code = code_of(f);
        let mut deps = named_modules(&code);
        deps.remove(&top);
        g.entry(top).or_default().extend(deps);
    }
    // Only edges between the crate's own modules.
    let names: BTreeSet<String> = g.keys().cloned().collect();
    for deps in g.values_mut() {
        deps.retain(|d| names.contains(d));
    }
    g
}

/// The module a file below a folder belongs to: its first path component, without `.rs`.
fn module_of(rel: &Path) -> String {
    rel.components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy()
        .trim_end_matches(".rs")
        .to_string()
}

/// The code of a file: not its comments, not its `#[cfg(test)]` part.
fn code_of(file: &Path) -> String {
    let text = std::fs::read_to_string(file).unwrap();
    let code_part = text.split("#[cfg(test)]").next().unwrap();
    code_part
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The files of the folder `dir` (a top-level module `folder`) and the files of the folder
/// each names (`crate::folder::file`, `super::file`).
fn folder_graph(dir: &Path, folder: &str) -> Graph {
    let mut files = Vec::new();
    rust_files(dir, &mut files);
    let mut g = Graph::new();
    for f in &files {
        let rel = f.strip_prefix(dir).unwrap();
        let name = module_of(rel);
        let code = code_of(f);
        let mut deps = named_after(&code, &format!("crate::{folder}::"));
        if rel.components().count() == 1 {
            deps.extend(named_after(&code, "super::"));
        }
        deps.remove(&name);
        g.entry(name).or_default().extend(deps);
    }
    let names: BTreeSet<String> = g.keys().cloned().collect();
    for deps in g.values_mut() {
        deps.retain(|d| names.contains(d));
    }
    g
}

/// A cycle, if any (depth-first search with an explicit path).
fn find_cycle(g: &Graph) -> Option<Vec<String>> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    fn visit(
        g: &Graph,
        v: &str,
        marks: &mut BTreeMap<String, Mark>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        marks.insert(v.to_string(), Mark::Open);
        path.push(v.to_string());
        for w in &g[v] {
            match marks[w] {
                Mark::Open => {
                    let start = path.iter().position(|p| p == w).unwrap();
                    let mut cycle = path[start..].to_vec();
                    cycle.push(w.clone());
                    return Some(cycle);
                }
                Mark::New => {
                    if let Some(c) = visit(g, w, marks, path) {
                        return Some(c);
                    }
                }
                Mark::Done => {}
            }
        }
        path.pop();
        marks.insert(v.to_string(), Mark::Done);
        None
    }
    let mut marks: BTreeMap<String, Mark> = g.keys().map(|k| (k.clone(), Mark::New)).collect();
    for v in g.keys() {
        if marks[v] == Mark::New {
            if let Some(c) = visit(g, v, &mut marks, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

#[test]
fn the_checker_finds_a_planted_cycle() {
    let mut g = Graph::new();
    for (a, b) in [("spec", "error"), ("error", "merge"), ("merge", "error")] {
        g.entry(a.into()).or_default().insert(b.into());
        g.entry(b.into()).or_default();
    }
    assert_eq!(
        find_cycle(&g),
        Some(vec!["error".into(), "merge".into(), "error".into()])
    );
    assert_eq!(
        named_modules("use crate::{a, b::c};\nlet x = crate::d::e();"),
        ["a", "b", "d"].iter().map(|s| s.to_string()).collect()
    );
}

#[test]
fn library_crates_have_no_module_import_cycle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for krate in ["crates/solver", "crates/sweep"] {
        let g = graph(&root.join(krate).join("src"));
        assert!(g.len() >= 9, "{krate}: only {} modules found", g.len());
        if let Some(cycle) = find_cycle(&g) {
            panic!("{krate}: module import cycle {}", cycle.join(" -> "));
        }
    }
}

#[test]
fn the_files_of_a_folder_have_no_import_cycle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut folders = 0;
    for krate in ["crates/solver", "crates/sweep", "."] {
        let src = root.join(krate).join("src");
        for e in std::fs::read_dir(&src).unwrap().flatten() {
            if !e.path().is_dir() {
                continue;
            }
            let folder = e.file_name().to_string_lossy().to_string();
            let g = folder_graph(&e.path(), &folder);
            folders += 1;
            if let Some(cycle) = find_cycle(&g) {
                panic!(
                    "{krate}/src/{folder}: file import cycle {}",
                    cycle.join(" -> ")
                );
            }
        }
    }
    assert!(folders >= 10, "only {folders} folders found");
    // The folder check sees `super::` and the folder's own paths, not a longer path.
    assert_eq!(
        named_after(
            "use super::{a, b::c}; x::super::d(); crate::runs::e",
            "super::"
        ),
        ["a", "b"].iter().map(|s| s.to_string()).collect()
    );
}

/// The top-level modules of each crate, lowest first: each may use only those before it.
const LAYERS: [(&str, &[&str]); 2] = [
    (
        "crates/solver",
        &[
            "error",
            "numerics",
            "model",
            "stepping",
            "contract",
            "reduced",
            "roots",
            "runs",
            "continuation",
        ],
    ),
    (
        "crates/sweep",
        &[
            "merge_report",
            "error",
            "spec",
            "store",
            "map",
            "tables",
            "audit",
            "pictures",
            "execution",
            "studies",
            "bench",
        ],
    ),
];

#[test]
fn folders_depend_one_way_in_the_documented_order() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for (krate, order) in LAYERS {
        let g = graph(&root.join(krate).join("src"));
        let found: BTreeSet<&str> = g.keys().map(String::as_str).collect();
        let listed: BTreeSet<&str> = order.iter().copied().collect();
        assert_eq!(
            found, listed,
            "{krate}: the top-level modules changed; update LAYERS and lib.rs's map"
        );
        let rank = |m: &str| order.iter().position(|o| *o == m).unwrap();
        for (m, deps) in &g {
            for d in deps {
                assert!(
                    rank(d) < rank(m),
                    "{krate}: {m} uses {d}, which comes after it in lib.rs's map"
                );
            }
        }
    }
}

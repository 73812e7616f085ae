//! The workbench's files import one way: no file of `src/` imports, through
//! any chain of imports, from a file that imports it; and its parts (the
//! folders `lib.rs` lists, bottom to top) import only from the parts below
//! them, stand at most 8 floors tall, and leave at most 12 files directly
//! in `src/` (issue 67). (The solver crate has its own check:
//! `crates/cdca/tests/layout.rs`.)
//!
//! A file's imports are the `crate::…` and `super::…` paths in its code
//! (`use` lines, brace groups of one level and inline paths), and paths
//! `a::…` whose first segment is a top-level module of `src/` that the file
//! does not declare itself; comments and the `#[cfg(test)] mod tests` part
//! are left out. A path is traced to the deepest file it names
//! (`crate::canvas::ViewSettings` → `src/canvas/mod.rs`).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

#[path = "../crates/cdca/tests/support/rust_files.rs"]
mod support;
use support::rust_files;

/// The workbench's parts, bottom to top, as `lib.rs` lists them.
const PARTS: [&str; 10] = [
    "style", "files", "results", "run", "plots", "study", "state", "canvas", "panels", "app",
];

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The file a module path names, as deep as the files go.
fn resolve(segments: &[&str]) -> Option<PathBuf> {
    let (mut base, mut found) = (src_dir(), None);
    for seg in segments {
        let file = base.join(format!("{seg}.rs"));
        let dir_mod = base.join(seg).join("mod.rs");
        if file.exists() {
            found = Some(file);
        } else if dir_mod.exists() {
            found = Some(dir_mod);
        } else {
            break;
        }
        base = base.join(seg);
    }
    found
}

/// The code of a file without comment lines and its test module.
fn code_of(text: &str) -> String {
    let code: Vec<&str> = text
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect();
    let code = code.join("\n");
    match code.find("#[cfg(test)]\nmod tests") {
        Some(i) => code[..i].to_owned(),
        None => code,
    }
}

/// Every lowercase path in `code` (`a::b::c`, segments of `[a-z0-9_]`)
/// not preceded by a path character, with `crate::{x, y::z}` groups
/// expanded into `crate::x` and `crate::y::z`.
fn paths(code: &str) -> Vec<Vec<String>> {
    let bytes = code.as_bytes();
    let word = |b: u8| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_';
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = word(bytes[i])
            && !bytes[i].is_ascii_digit()
            && (i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || b"_:".contains(&bytes[i - 1])));
        if !starts {
            i += 1;
            continue;
        }
        let mut segments = Vec::new();
        loop {
            let s = i;
            while i < bytes.len() && word(bytes[i]) {
                i += 1;
            }
            segments.push(code[s..i].to_owned());
            if code[i..].starts_with("::{") {
                let close = code[i..].find('}').map_or(bytes.len(), |c| i + c);
                for item in code[i + 3..close].split(',') {
                    let item: String = item
                        .trim()
                        .chars()
                        .take_while(|c| c.is_ascii_alphanumeric() || "_:".contains(*c))
                        .collect();
                    let mut p = segments.clone();
                    p.extend(
                        item.split("::")
                            .filter(|s| !s.is_empty())
                            .map(str::to_owned),
                    );
                    out.push(p);
                }
                i = close;
                break;
            }
            if code[i..].starts_with("::") && code.as_bytes().get(i + 2).is_some_and(|&b| word(b)) {
                i += 2;
                continue;
            }
            out.push(segments);
            break;
        }
    }
    out
}

/// The files of `src/` each file imports.
fn import_graph() -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
    let src = src_dir();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let top: BTreeSet<String> = fs::read_dir(&src)
        .expect("src")
        .map(|e| e.expect("entry").path())
        .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .filter(|s| s != "lib" && s != "main")
        .collect();
    let mut graph = BTreeMap::new();
    for f in &files {
        let code = code_of(&fs::read_to_string(f).expect("readable file"));
        let local: BTreeSet<String> = code
            .split("mod ")
            .skip(1)
            .map(|s| {
                s.chars()
                    .take_while(|c| c.is_ascii_lowercase() || *c == '_')
                    .collect()
            })
            .collect();
        // the module path of the file's parent, for `super::`
        let rel = f.strip_prefix(&src).expect("under src");
        let mut parent: Vec<String> = rel
            .parent()
            .map(|p| p.iter().map(|s| s.to_string_lossy().into_owned()).collect())
            .unwrap_or_default();
        if f.file_name().is_some_and(|n| n == "mod.rs") {
            parent.pop();
        }
        let mut deps = BTreeSet::new();
        for p in paths(&code) {
            let target: Option<Vec<String>> = match p[0].as_str() {
                "crate" => Some(p[1..].to_vec()),
                "super" => Some(
                    parent
                        .iter()
                        .cloned()
                        .chain(p[1..].iter().cloned())
                        .collect(),
                ),
                first if p.len() > 1 && top.contains(first) && !local.contains(first) => {
                    Some(p.clone())
                }
                _ => None,
            };
            let target = target.and_then(|t| {
                let segs: Vec<&str> = t.iter().map(String::as_str).collect();
                resolve(&segs)
            });
            if let Some(t) = target.filter(|t| t != f) {
                deps.insert(t);
            }
        }
        graph.insert(f.clone(), deps);
    }
    graph
}

/// A cycle through `start`, if any (depth-first search).
fn cycle_from(
    graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>,
    start: &PathBuf,
) -> Option<Vec<PathBuf>> {
    let mut stack = vec![(start.clone(), vec![start.clone()])];
    let mut seen = BTreeSet::new();
    while let Some((node, path)) = stack.pop() {
        for next in graph.get(&node).into_iter().flatten() {
            if next == start {
                return Some(path);
            }
            if seen.insert(next.clone()) {
                let mut p = path.clone();
                p.push(next.clone());
                stack.push((next.clone(), p));
            }
        }
    }
    None
}

#[test]
fn no_file_imports_from_a_file_that_imports_it() {
    let graph = import_graph();
    let edges: usize = graph.values().map(BTreeSet::len).sum();
    // the check sees the imports: every panel file imports the view
    assert!(edges > 100, "only {edges} imports found");
    let view = src_dir().join("state").join("view.rs");
    let plots = src_dir().join("panels").join("plots.rs");
    assert!(graph[&plots].contains(&view), "{:?}", graph[&plots]);
    let src = src_dir();
    let cycles: Vec<String> = graph
        .keys()
        .filter_map(|f| cycle_from(&graph, f))
        .map(|c| {
            c.iter()
                .map(|p| p.strip_prefix(&src).unwrap_or(p).display().to_string())
                .collect::<Vec<_>>()
                .join(" → ")
        })
        .collect();
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
}

/// The part a file of `src/` is in (its folder), `None` for `lib.rs` and
/// `main.rs`.
fn part_of(file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src_dir()).expect("under src");
    (rel.components().count() > 1).then(|| {
        rel.iter()
            .next()
            .expect("a folder")
            .to_string_lossy()
            .into_owned()
    })
}

/// Every file but `lib.rs` and `main.rs` is in one of the parts, and each
/// part imports only from the parts below it in [`PARTS`].
#[test]
fn parts_import_only_from_the_parts_below_them() {
    let graph = import_graph();
    let rank = |part: &str| PARTS.iter().position(|p| *p == part);
    let src = src_dir();
    let name = |f: &Path| f.strip_prefix(&src).unwrap_or(f).display().to_string();
    let mut loose = Vec::new();
    let mut upward = Vec::new();
    for (from, targets) in &graph {
        let Some(part) = part_of(from) else {
            let top = name(from);
            if top != "lib.rs" && top != "main.rs" {
                loose.push(top);
            }
            continue;
        };
        let Some(rf) = rank(&part) else {
            loose.push(name(from));
            continue;
        };
        for t in targets {
            let rt = part_of(t).and_then(|p| rank(&p));
            if rt.is_none_or(|rt| rt > rf) {
                upward.push(format!("{} → {}", name(from), name(t)));
            }
        }
    }
    assert!(loose.is_empty(), "files in no part of lib.rs: {loose:?}");
    assert!(upward.is_empty(), "imports going up the parts: {upward:#?}");
}

/// Counting each part as one room, the parts stand at most 8 floors tall
/// (a part on each floor imports from a part on the floor below), and at
/// most 12 files stay directly in `src/`.
#[test]
fn the_parts_stand_at_most_8_floors_tall() {
    let graph = import_graph();
    let mut below: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (from, targets) in &graph {
        let Some(part) = part_of(from) else { continue };
        let entry = below.entry(part.clone()).or_default();
        entry.extend(
            targets
                .iter()
                .filter_map(|t| part_of(t))
                .filter(|p| *p != part),
        );
    }
    // the parts are in the order of PARTS (the test above): one pass up
    let mut floor: BTreeMap<String, usize> = BTreeMap::new();
    for part in PARTS {
        let f = 1 + below
            .get(part)
            .into_iter()
            .flatten()
            .map(|p| floor.get(p).copied().unwrap_or(0))
            .max()
            .unwrap_or(0);
        floor.insert(part.to_owned(), f);
    }
    let tallest = floor.values().max().copied().unwrap_or(0);
    assert!(
        tallest <= 8,
        "the parts stand {tallest} floors tall: {floor:?}"
    );
    let loose = fs::read_dir(src_dir())
        .expect("src")
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "rs"))
        })
        .count();
    assert!(loose <= 12, "{loose} files directly in src/");
}

//! The solver crate's layout (issue 13): imports go one way, down the
//! stack of the method's parts, and no file imports from a file that
//! imports it; ARCHITECTURE.md's module tree lists exactly the source files.
//!
//! Reference: the table in `src/lib.rs`. A file's imports are its
//! `use crate::…`/`use super::…` lines and inline `crate::…` paths outside
//! `#[cfg(test)]` code; an import of a re-exported item is traced to the
//! file that defines it (an index's own `pub use` lines are not imports).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

#[path = "support/rust_files.rs"]
mod support;
use support::rust_files;

/// The parts, bottom to top, as `lib.rs` lists them.
const PARTS: [&str; 12] = [
    "error",
    "scene",
    "report",
    "geometry",
    "discretisation",
    "solvers",
    "contact",
    "fracture",
    "simulation",
    "race",
    "csv",
    "study",
];

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Module path of a file: `lib.rs` → `[]`, `a/mod.rs` → `[a]`, `a/b.rs` → `[a, b]`.
fn module_of(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|l| l == "mod" || l == "lib") {
        parts.pop();
    }
    parts
}

/// The code of a file without its `#[cfg(test)]` part and comments.
fn code_of(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or_default();
    text.lines()
        .map(|l| l.split("//").next().unwrap_or_default())
        .collect::<Vec<_>>()
        .join("\n")
}

/// Expands `a::{b, c::{d, e}}` into `a::b`, `a::c::d`, `a::c::e`.
fn expand(path: &str) -> Vec<String> {
    // drop `as alias` renames, then white space
    let mut words: Vec<&str> = Vec::new();
    let mut tokens = path.split_whitespace();
    while let Some(w) = tokens.next() {
        if w == "as" {
            let alias = tokens.next().unwrap_or_default();
            words.push(alias.trim_start_matches(|c: char| c.is_alphanumeric() || c == '_'));
        } else {
            words.push(w);
        }
    }
    let path: String = words.concat();
    let Some(open) = path.find('{') else {
        return vec![path];
    };
    let prefix = &path[..open];
    let inner = &path[open + 1..path.rfind('}').unwrap_or(path.len())];
    let (mut depth, mut start, mut out) = (0, 0, Vec::new());
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                out.extend(expand(&format!("{prefix}{}", &inner[start..i])));
                start = i + 1;
            }
            _ => {}
        }
    }
    if start < inner.len() {
        out.extend(expand(&format!("{prefix}{}", &inner[start..])));
    }
    out
}

/// Every path a file imports, as absolute module paths (`crate` dropped).
fn imports(code: &str, module: &[String], is_index: bool) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    // `use` statements (possibly spanning lines)
    for stmt in code.split(';') {
        let s = stmt.trim();
        let body = if let Some(b) = s.strip_prefix("use ") {
            b
        } else if let Some(b) = s
            .strip_prefix("pub(crate) use ")
            .or(s.strip_prefix("pub(super) use "))
        {
            b
        } else if let Some(b) = s.strip_prefix("pub use ") {
            if is_index {
                continue;
            }
            b
        } else {
            continue;
        };
        for p in expand(body) {
            let segs: Vec<&str> = p.split("::").collect();
            let abs: Option<Vec<String>> = match segs.first() {
                Some(&"crate") => Some(segs[1..].iter().map(|s| (*s).to_string()).collect()),
                Some(&"super") => {
                    let mut base = module.to_vec();
                    let mut rest = &segs[..];
                    while rest.first() == Some(&"super") {
                        base.pop();
                        rest = &rest[1..];
                    }
                    base.extend(rest.iter().map(|s| (*s).to_string()));
                    Some(base)
                }
                _ => None,
            };
            paths.extend(abs);
        }
    }
    // inline `crate::a::b` paths in code
    for (i, _) in code.match_indices("crate::") {
        if code[..i].ends_with("use ") {
            continue;
        }
        let tail: String = code[i + 7..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
            .collect();
        paths.push(
            tail.split("::")
                .filter(|s| !s.is_empty())
                .map(str::to_string)
                .collect(),
        );
    }
    paths
}

struct Crate {
    /// Module path → file (relative to src).
    files: BTreeMap<Vec<String>, PathBuf>,
    /// Index file → re-exported name → module path it comes from.
    reexports: BTreeMap<Vec<String>, BTreeMap<String, Vec<String>>>,
    code: BTreeMap<Vec<String>, String>,
}

impl Crate {
    fn load() -> Self {
        let src = src_dir();
        let mut list = Vec::new();
        rust_files(&src, &mut list);
        let (mut files, mut reexports, mut code) =
            (BTreeMap::new(), BTreeMap::new(), BTreeMap::new());
        for p in list {
            let rel = p.strip_prefix(&src).expect("inside src").to_path_buf();
            let module = module_of(&rel);
            let text = code_of(&fs::read_to_string(&p).expect("readable source"));
            let mut names = BTreeMap::new();
            for stmt in text.split(';') {
                if let Some(body) = stmt.trim().strip_prefix("pub use ") {
                    for path in expand(body) {
                        let segs: Vec<String> = path.split("::").map(str::to_string).collect();
                        if let Some((name, from)) = segs.split_last() {
                            let mut abs = module.clone();
                            abs.extend(from.iter().cloned());
                            names.insert(name.clone(), abs);
                        }
                    }
                }
            }
            reexports.insert(module.clone(), names);
            code.insert(module.clone(), text);
            files.insert(module, rel);
        }
        Self {
            files,
            reexports,
            code,
        }
    }

    /// The file that defines what `path` names.
    fn resolve(&self, path: &[String]) -> Option<Vec<String>> {
        let mut n = path.len();
        while !self.files.contains_key(&path[..n]) {
            n = n.checked_sub(1)?;
        }
        let module = path[..n].to_vec();
        if let Some(name) = path.get(n)
            && let Some(from) = self.reexports.get(&module).and_then(|r| r.get(name))
        {
            let mut next = from.clone();
            next.push(name.clone());
            if next != path {
                return self.resolve(&next);
            }
        }
        Some(module)
    }

    /// Edges file → file it imports from.
    fn edges(&self) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
        let mut edges = BTreeMap::new();
        for (module, code) in &self.code {
            let rel = &self.files[module];
            let is_index = rel.ends_with("mod.rs") || rel.ends_with("lib.rs");
            let set: BTreeSet<Vec<String>> = imports(code, module, is_index)
                .iter()
                .filter_map(|p| self.resolve(p))
                .filter(|t| t != module && !t.is_empty())
                .collect();
            edges.insert(module.clone(), set);
        }
        edges
    }
}

fn name(m: &[String]) -> String {
    if m.is_empty() {
        "lib".into()
    } else {
        m.join("::")
    }
}

/// Depth-first search with colours (1 on the stack, 2 done); the first
/// cycle found, as the list of files around it.
fn visit(
    m: &[String],
    edges: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
    colour: &mut BTreeMap<Vec<String>, u8>,
    stack: &mut Vec<Vec<String>>,
) -> Option<Vec<Vec<String>>> {
    colour.insert(m.to_vec(), 1);
    stack.push(m.to_vec());
    for t in edges.get(m).into_iter().flatten() {
        match colour.get(t).copied().unwrap_or(0) {
            1 => {
                let start = stack.iter().position(|s| s == t).unwrap_or(0);
                let mut cycle = stack[start..].to_vec();
                cycle.push(t.clone());
                return Some(cycle);
            }
            0 => {
                if let Some(c) = visit(t, edges, colour, stack) {
                    return Some(c);
                }
            }
            _ => {}
        }
    }
    stack.pop();
    colour.insert(m.to_vec(), 2);
    None
}

/// No file imports from a file that (directly or through others) imports it.
#[test]
fn no_import_cycles_between_files() {
    let krate = Crate::load();
    let edges = krate.edges();
    assert!(edges.len() > 40, "found only {} files", edges.len());
    let mut colour = BTreeMap::new();
    for m in edges.keys() {
        if colour.get(m).copied().unwrap_or(0) == 0
            && let Some(cycle) = visit(m, &edges, &mut colour, &mut Vec::new())
        {
            let names: Vec<String> = cycle.iter().map(|m| name(m)).collect();
            panic!("import cycle: {}", names.join(" → "));
        }
    }
}

/// Every import goes down (or stays inside) the stack of parts in `lib.rs`.
#[test]
fn imports_go_down_the_stack_of_parts() {
    let krate = Crate::load();
    let rank = |m: &[String]| m.first().and_then(|p| PARTS.iter().position(|q| q == p));
    let mut upward = Vec::new();
    for (from, targets) in krate.edges() {
        let Some(rf) = rank(&from) else {
            assert!(
                from.is_empty(),
                "file {} is in no part of lib.rs",
                name(&from)
            );
            continue;
        };
        for t in targets {
            let rt = rank(&t).expect("an import resolves to a part");
            if rt > rf {
                upward.push(format!("{} → {}", name(&from), name(&t)));
            }
        }
    }
    assert!(upward.is_empty(), "imports going up the stack: {upward:#?}");
}

/// ARCHITECTURE.md's Layout section lists every source file of the solver
/// crate, and nothing else.
#[test]
fn architecture_module_tree_matches_the_folders() {
    let architecture =
        fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../ARCHITECTURE.md"))
            .expect("ARCHITECTURE.md at the repository root");
    let layout = architecture
        .split("## Layout")
        .nth(1)
        .and_then(|s| s.split("\n## ").next())
        .expect("a Layout section");
    let mut files = Vec::new();
    rust_files(&src_dir(), &mut files);
    let src = src_dir();
    let mut missing = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&src).expect("inside src");
        let leaf = rel
            .file_name()
            .expect("file name")
            .to_string_lossy()
            .to_string();
        let label = if leaf == "mod.rs" {
            format!(
                "{}/",
                rel.parent()
                    .expect("folder")
                    .file_name()
                    .expect("name")
                    .to_string_lossy()
            )
        } else {
            leaf
        };
        if !layout.contains(&label) {
            missing.push(rel.display().to_string());
        }
    }
    assert!(
        missing.is_empty(),
        "files missing from ARCHITECTURE.md's Layout tree: {missing:?}"
    );
    // and no file named there that does not exist
    let names: BTreeSet<String> = files
        .iter()
        .map(|f| f.file_name().expect("name").to_string_lossy().to_string())
        .collect();
    let stale: Vec<&str> = layout
        .split_whitespace()
        .filter(|w| Path::new(w).extension().is_some_and(|e| e == "rs") && !w.contains('/'))
        .filter(|w| !names.contains(*w))
        .collect();
    assert!(
        stale.is_empty(),
        "ARCHITECTURE.md names files that do not exist: {stale:?}"
    );
}

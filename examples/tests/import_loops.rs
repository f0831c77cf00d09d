//! No import loops in any library crate of the workspace: each module imports only modules
//! below it.
//!
//! A module is a file (`foo.rs`, or `foo/mod.rs` for `foo`; `lib.rs` is the crate root). A
//! module `A` imports `B` when `A` has a `use` (`pub use` re-exports included) of a
//! `crate::`, `super::` or `self::` path, or of a path that starts with one of `A`'s child
//! modules, that resolves to something in `B`: the longest prefix of the path that names a
//! module. Paths grouped in braces (`use super::{a::X, b::Y}`) are taken one by one. Edges
//! to the crate root are left out (it re-exports the public items of every module), and so
//! is everything from `#[cfg(test)] mod tests` to the end of its file, since a test module
//! may import its parent. The test fails naming the modules of every cycle of the graph,
//! with the imports that close it.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// A module's path inside its crate (`["scene", "file"]`; empty for the crate root).
type ModPath = Vec<String>;

/// The `.rs` files under `dir`, recursively.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module a file under `src` defines.
fn module_of(src: &Path, file: &Path) -> ModPath {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: ModPath = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

/// The source without its comment lines and without its test module (everything from
/// `#[cfg(test)]` followed by `mod tests {` to the end of the file).
fn strip(source: &str) -> String {
    let mut out = String::new();
    let mut lines = source.lines().peekable();
    while let Some(line) = lines.next() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("//") {
            continue;
        }
        if let Some(rest) = trimmed.strip_prefix("#[cfg(test)]") {
            let rest = rest.trim_start();
            let next = if rest.is_empty() {
                lines.peek().map_or("", |l| l.trim_start())
            } else {
                rest
            };
            if next.starts_with("mod tests {") {
                break;
            }
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// The paths of the `use` declarations of `source` that start with a lowercase segment
/// followed by `::` (`crate::scene::Scene`, `super::{a, b::C}`, `std::fmt`), as written.
fn use_paths(source: &str) -> Vec<String> {
    let bytes = source.as_bytes();
    let is_ident = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(found) = source[i..].find("use") {
        let start = i + found;
        i = start + 3;
        if start > 0 && is_ident(bytes[start - 1]) {
            continue;
        }
        if !bytes.get(i).is_some_and(u8::is_ascii_whitespace) {
            continue;
        }
        let path_start = i + source[i..].len() - source[i..].trim_start().len();
        let first_len = source[path_start..]
            .bytes()
            .take_while(|&b| b.is_ascii_lowercase() || b == b'_')
            .count();
        if first_len == 0 || !source[path_start + first_len..].starts_with("::") {
            continue;
        }
        let Some(end) = source[path_start..].find(';') else {
            break;
        };
        out.push(source[path_start..path_start + end].to_string());
        i = path_start + end + 1;
    }
    out
}

/// The top-level comma-separated items of a brace group's contents.
fn split_group(group: &str) -> Vec<&str> {
    let mut items = Vec::new();
    let (mut depth, mut from) = (0, 0);
    for (k, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&group[from..k]);
                from = k + 1;
            }
            _ => {}
        }
    }
    items.push(&group[from..]);
    items
        .into_iter()
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .collect()
}

/// One use tree expanded into its simple paths, each as its segments (`a::{b, c::D}` gives
/// `[a, b]` and `[a, c, D]`; `self` in a group stands for the prefix; renames dropped).
fn expand(tree: &str) -> Vec<Vec<String>> {
    let tree: String = tree.split_whitespace().collect::<Vec<_>>().join(" ");
    let tree = tree.trim();
    match tree.find('{') {
        None => {
            let simple = tree.split(" as ").next().unwrap();
            vec![
                simple
                    .split("::")
                    .map(|s| s.trim().to_string())
                    .filter(|s| !s.is_empty())
                    .collect(),
            ]
        }
        Some(open) => {
            let close = tree.rfind('}').expect("a closed use group");
            let prefix: Vec<String> = tree[..open]
                .split("::")
                .map(|s| s.trim().to_string())
                .filter(|s| !s.is_empty())
                .collect();
            let mut out = Vec::new();
            for item in split_group(&tree[open + 1..close]) {
                for rest in expand(item) {
                    let mut path = prefix.clone();
                    path.extend(rest.into_iter().filter(|s| s != "self"));
                    out.push(path);
                }
            }
            out
        }
    }
}

/// The module a path used in module `m` resolves to: the longest prefix naming a module;
/// `None` for paths outside the crate.
fn resolve(modules: &BTreeMap<ModPath, PathBuf>, m: &ModPath, path: &[String]) -> Option<ModPath> {
    let (mut cur, rest): (ModPath, &[String]) = match path.first().map(String::as_str) {
        Some("crate") => (Vec::new(), &path[1..]),
        Some("self") => (m.clone(), &path[1..]),
        Some("super") => {
            let mut cur = m.clone();
            let mut k = 0;
            while path.get(k).is_some_and(|s| s == "super") {
                cur.pop();
                k += 1;
            }
            (cur, &path[k..])
        }
        Some(first) => {
            let mut child = m.clone();
            child.push(first.to_string());
            if !modules.contains_key(&child) {
                return None;
            }
            (m.clone(), path)
        }
        None => return None,
    };
    let mut best = cur.clone();
    for seg in rest {
        cur.push(seg.clone());
        if modules.contains_key(&cur) {
            best = cur.clone();
        } else {
            break;
        }
    }
    Some(best)
}

/// The strongly connected components of more than one module (Tarjan).
fn cycles(edges: &BTreeMap<ModPath, BTreeSet<ModPath>>) -> Vec<Vec<ModPath>> {
    struct State<'g> {
        edges: &'g BTreeMap<ModPath, BTreeSet<ModPath>>,
        index: BTreeMap<&'g ModPath, usize>,
        low: BTreeMap<&'g ModPath, usize>,
        stack: Vec<&'g ModPath>,
        on_stack: BTreeSet<&'g ModPath>,
        found: Vec<Vec<ModPath>>,
    }
    fn visit<'g>(s: &mut State<'g>, v: &'g ModPath) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        s.on_stack.insert(v);
        for w in s.edges.get(v).into_iter().flatten() {
            if !s.index.contains_key(w) {
                visit(s, w);
                let lw = s.low[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if s.on_stack.contains(w) {
                let iw = s.index[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if s.low[v] == s.index[v] {
            let mut comp = Vec::new();
            loop {
                let w = s.stack.pop().unwrap();
                s.on_stack.remove(w);
                comp.push(w.clone());
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                s.found.push(comp);
            }
        }
    }
    let mut s = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !s.index.contains_key(v) {
            visit(&mut s, v);
        }
    }
    s.found
}

/// A module path as Rust writes it (`scene::file`; `crate` for the root).
fn name(m: &[String]) -> String {
    if m.is_empty() {
        "crate".into()
    } else {
        m.join("::")
    }
}

/// The import loops of the crate whose sources are under `src`, one message per cycle.
fn crate_loops(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let modules: BTreeMap<ModPath, PathBuf> = files
        .iter()
        .map(|f| (module_of(src, f), f.clone()))
        .collect();
    let mut edges: BTreeMap<ModPath, BTreeSet<ModPath>> = BTreeMap::new();
    // The `use` behind each edge, for the message.
    let mut why: BTreeMap<(ModPath, ModPath), String> = BTreeMap::new();
    for (m, file) in &modules {
        let source = strip(&fs::read_to_string(file).unwrap());
        for tree in use_paths(&source) {
            for path in expand(&tree) {
                if let Some(target) = resolve(&modules, m, &path)
                    && &target != m
                    && !target.is_empty()
                {
                    why.entry((m.clone(), target.clone()))
                        .or_insert_with(|| format!("use {}", path.join("::")));
                    edges.entry(m.clone()).or_default().insert(target);
                }
            }
        }
    }
    cycles(&edges)
        .into_iter()
        .map(|comp| {
            let members: BTreeSet<&ModPath> = comp.iter().collect();
            let names: Vec<String> = comp.iter().map(|m| name(m)).collect();
            let mut msg = format!("[{}]", names.join(", "));
            for a in &comp {
                for b in edges[a].iter().filter(|b| members.contains(b)) {
                    let file = modules[a].strip_prefix(src).unwrap().display();
                    let u = &why[&(a.clone(), b.clone())];
                    msg += &format!("\n      {} -> {} ({file}: {u})", name(a), name(b));
                }
            }
            msg
        })
        .collect()
}

#[test]
fn no_crate_has_an_import_loop() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let crates = root.join("crates");
    let mut dirs: Vec<PathBuf> = fs::read_dir(&crates)
        .unwrap()
        .map(|e| e.unwrap().path().join("src"))
        .filter(|src| src.is_dir())
        .collect();
    dirs.sort();
    // The other packages of the workspace too (their libraries' modules).
    dirs.extend(
        ["examples", "benches", "peer-tests"]
            .iter()
            .map(|p| root.join(p).join("src"))
            .filter(|src| src.is_dir()),
    );
    assert!(
        dirs.len() >= 5,
        "the crates are found under {}",
        crates.display()
    );
    let mut report = Vec::new();
    for src in &dirs {
        let krate = src.parent().unwrap().file_name().unwrap().to_string_lossy();
        for cycle in crate_loops(src) {
            report.push(format!("  {krate}: {cycle}"));
        }
    }
    assert!(
        report.is_empty(),
        "import loops (each module must import only modules below it; move what two \
         modules share into a module of its own):\n{}",
        report.join("\n")
    );
}

#[test]
fn a_child_importing_its_parent_is_a_loop() {
    let dir = std::env::temp_dir().join(format!("import-loops-{}", std::process::id()));
    let src = dir.join("src");
    fs::create_dir_all(src.join("a")).unwrap();
    fs::write(src.join("lib.rs"), "pub mod a;\npub use a::Thing;\n").unwrap();
    fs::write(
        src.join("a/mod.rs"),
        "mod b;\npub use b::{Other, helper};\n/// Doc.\npub struct Thing;\n",
    )
    .unwrap();
    fs::write(
        src.join("a/b.rs"),
        "use super::Thing;\n/// Doc.\npub struct Other;\n/// Doc.\npub fn helper() {}\n\
         #[cfg(test)]\nmod tests {\n    use crate::a::Thing;\n}\n",
    )
    .unwrap();
    let loops = crate_loops(&src);
    assert_eq!(loops.len(), 1, "{loops:?}");
    assert!(loops[0].starts_with("[a, a::b]"), "{loops:?}");

    // The definition moved below both: no loop.
    fs::write(
        src.join("a/mod.rs"),
        "mod b;\nmod thing;\npub use b::Other;\n",
    )
    .unwrap();
    fs::write(src.join("a/thing.rs"), "/// Doc.\npub struct Thing;\n").unwrap();
    fs::write(
        src.join("a/b.rs"),
        "use super::thing::Thing;\n/// Doc.\npub struct Other;\n",
    )
    .unwrap();
    let loops = crate_loops(&src);
    fs::remove_dir_all(&dir).unwrap();
    assert!(loops.is_empty(), "{loops:?}");
}

//! The architecture holds: no import cycle between the source files of `src/` (the arrows of
//! ARCHITECTURE.md point down only), read from the files themselves.
//!
//! A file A imports file B when A names an item of B's module through `use crate::…`,
//! `use super::…`, `use self::…` or an inline `crate::…` path (in code or in a doc link). A
//! re-export from a front door (`pub use` in `lib.rs` or a `mod.rs`) is left out, and so is every
//! path that ends at a front door: a folder's front door is not a room, so `use crate::linkage::Plan`
//! imports no file, while `use crate::linkage::plan::Plan` imports `linkage/plan.rs`. A file's
//! unit tests (`#[cfg(test)] mod tests { … }` at its end) are left out. These are the rules of
//! `shared/tools/import-cycles`, which this test follows (it also reads `use a::b as c;`).
//!
//! The test also lists, without asserting anything about them, the functions longer than
//! [`LONG_FUNCTION`] lines: `cargo test --test tmm architecture -- --nocapture` prints them.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

/// Import cycles tolerated while a change that removes them is under way, each as its files in
/// sorted order (none today). The test fails when one of them no longer exists, so that the
/// list never allows a cycle that is gone.
const KNOWN_CYCLES: &[&[&str]] = &[];

/// A function longer than this many lines (from its `fn` line to its closing brace) is listed.
const LONG_FUNCTION: usize = 150;

/// The source files of a crate: path relative to `src/` (with `/`) → text.
type Sources = BTreeMap<String, String>;

/// The file imports: importing file → imported file → the names that tie them.
type Edges = BTreeMap<String, BTreeMap<String, BTreeSet<String>>>;

fn read_sources(dir: &Path, rel: &str, out: &mut Sources) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{dir:?}: {e}"))
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path
            .file_name()
            .expect("a file name")
            .to_string_lossy()
            .into_owned();
        let sub = if rel.is_empty() {
            name.clone()
        } else {
            format!("{rel}/{name}")
        };
        if path.is_dir() {
            read_sources(&path, &sub, out);
        } else if name.ends_with(".rs") {
            let text = fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
            out.insert(sub, text);
        }
    }
}

/// Whether a file is a front door (`lib.rs`, `main.rs`, `mod.rs`).
fn is_front(rel: &str) -> bool {
    let base = rel.rsplit('/').next().unwrap_or(rel);
    matches!(base, "lib.rs" | "main.rs" | "mod.rs")
}

/// The module path of a file: `linkage/plan.rs` → [linkage, plan]; `linkage/mod.rs` → [linkage].
fn module_of(rel: &str) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .strip_suffix(".rs")
        .unwrap_or(rel)
        .split('/')
        .map(str::to_owned)
        .collect();
    if is_front(rel) {
        parts.pop();
    }
    parts
}

/// The text without the file's unit tests (`#[cfg(test)] mod tests {` to the end).
fn without_unit_tests(text: &str) -> &str {
    let mut from = 0;
    while let Some(i) = text[from..].find("#[cfg(test)]") {
        let at = from + i;
        let rest = text[at + "#[cfg(test)]".len()..].trim_start();
        let is_unit_tests = rest
            .strip_prefix("mod")
            .filter(|r| r.starts_with(char::is_whitespace))
            .and_then(|r| r.trim_start().strip_prefix("tests"))
            .is_some_and(|r| r.trim_start().starts_with('{'));
        if is_unit_tests {
            return &text[..at];
        }
        from = at + 1;
    }
    text
}

/// A `use …;` declaration: whether it is `pub`, its use tree, and where the whole declaration
/// lies in the text (byte range).
struct UseDeclaration {
    public: bool,
    tree: String,
    span: std::ops::Range<usize>,
}

/// The use declarations of a text, one per `use …;` whose line starts with it.
fn use_declarations(text: &str) -> Vec<UseDeclaration> {
    let mut out = Vec::new();
    let mut offset = 0;
    while offset < text.len() {
        let line_end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
        let line = &text[offset..line_end];
        let trimmed = line.trim_start();
        let start = offset + (line.len() - trimmed.len());
        let (public, after) = match trimmed.strip_prefix("pub") {
            Some(rest) if rest.starts_with('(') => match rest.find(')') {
                Some(close) => (true, &rest[close + 1..]),
                None => (false, trimmed),
            },
            Some(rest) if rest.starts_with(char::is_whitespace) => (true, rest),
            _ => (false, trimmed),
        };
        let after_trim = after.trim_start();
        let is_use = (!public || after_trim.len() < after.len())
            && after_trim
                .strip_prefix("use")
                .is_some_and(|r| r.starts_with(char::is_whitespace));
        if is_use {
            let tree_start = start + (trimmed.len() - after_trim.len()) + "use".len();
            if let Some(semi) = text[tree_start..].find(';') {
                let end = tree_start + semi + 1;
                out.push(UseDeclaration {
                    public,
                    tree: text[tree_start..end - 1].to_owned(),
                    span: start..end,
                });
                offset = text[end..].find('\n').map_or(text.len(), |i| end + i + 1);
                continue;
            }
        }
        offset = line_end + 1;
    }
    out
}

/// The paths of a use tree: `a::{b, c::{d, e as f}}` → `a::b`, `a::c::d`, `a::c::e`.
fn expand(tree: &str) -> Vec<String> {
    fn split_top(s: &str) -> Vec<&str> {
        let (mut parts, mut depth, mut start) = (Vec::new(), 0, 0);
        for (i, ch) in s.char_indices() {
            match ch {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    parts.push(&s[start..i]);
                    start = i + 1;
                }
                _ => {}
            }
        }
        parts.push(&s[start..]);
        parts
    }
    fn rec(prefix: &str, tree: &str, out: &mut Vec<String>) {
        for part in split_top(tree) {
            let part = part.trim();
            if part.is_empty() {
                continue;
            }
            match part.find('{') {
                Some(open) => {
                    let close = part.rfind('}').expect("a closing brace in a use tree");
                    let head = format!("{prefix}{}", &part[..open]);
                    rec(&head, &part[open + 1..close], out);
                }
                None => {
                    // `x as y` and `x as _` name x.
                    let words: Vec<&str> = part.split_whitespace().collect();
                    let path = match words.iter().position(|w| *w == "as") {
                        Some(k) => words[..k].concat(),
                        None => words.concat(),
                    };
                    out.push(format!("{prefix}{path}"));
                }
            }
        }
    }
    let compact: String = tree.split_whitespace().collect::<Vec<_>>().join(" ");
    let compact = compact
        .replace(" :: ", "::")
        .replace(":: ", "::")
        .replace(" ::", "::");
    let mut out = Vec::new();
    rec("", &compact, &mut out);
    out
}

/// The inline `crate::a::b…` paths of a text, as their segments after `crate`.
fn inline_crate_paths(text: &str) -> Vec<Vec<String>> {
    let is_word = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(i) = text[from..].find("crate::") {
        let at = from + i;
        from = at + "crate".len();
        if text[..at].chars().next_back().is_some_and(is_word) {
            continue;
        }
        let mut segs = Vec::new();
        let mut rest = &text[at + "crate".len()..];
        while let Some(r) = rest.strip_prefix("::") {
            let len = r
                .char_indices()
                .find(|&(k, c)| !(is_word(c) && (k > 0 || !c.is_ascii_digit())))
                .map_or(r.len(), |(k, _)| k);
            if len == 0 {
                break;
            }
            segs.push(r[..len].to_owned());
            rest = &r[len..];
        }
        if !segs.is_empty() {
            out.push(segs);
        }
    }
    out
}

/// The file a module path names: the longest prefix that is a file, unless that is a front door.
fn resolve(modules: &BTreeMap<Vec<String>, String>, path: &[String]) -> Option<String> {
    (1..=path.len())
        .rev()
        .find_map(|k| modules.get(&path[..k]))
        .filter(|rel| !is_front(rel))
        .cloned()
}

/// The imports between the files.
fn imports(sources: &Sources) -> Edges {
    let modules: BTreeMap<Vec<String>, String> = sources
        .keys()
        .map(|rel| (module_of(rel), rel.clone()))
        .collect();
    let mut edges = Edges::new();
    for (rel, text) in sources {
        let text = without_unit_tests(text);
        let me = module_of(rel);
        let front = is_front(rel);
        let mut add = |target: Option<String>, name: &str| {
            if let Some(target) = target.filter(|t| t != rel) {
                edges
                    .entry(rel.clone())
                    .or_default()
                    .entry(target)
                    .or_default()
                    .insert(name.to_owned());
            }
        };
        let mut code = text.to_owned();
        for decl in use_declarations(text) {
            if decl.public && front {
                // A re-export from a front door: no import, in its use tree or inline.
                code.replace_range(decl.span.clone(), &" ".repeat(decl.span.len()));
                continue;
            }
            for path in expand(&decl.tree) {
                let mut segs: Vec<String> = path
                    .split("::")
                    .filter(|s| !s.is_empty())
                    .map(str::to_owned)
                    .collect();
                let mut base: Vec<String> = match segs.first().map(String::as_str) {
                    Some("crate") => Vec::new(),
                    Some("super") => me[..me.len().saturating_sub(1)].to_vec(),
                    Some("self") => me.clone(),
                    _ => continue,
                };
                segs.remove(0);
                while segs.first().map(String::as_str) == Some("super") {
                    base.pop();
                    segs.remove(0);
                }
                let name = segs.last().cloned().unwrap_or_else(|| "*".to_owned());
                base.extend(segs);
                add(resolve(&modules, &base), &name);
            }
        }
        for segs in inline_crate_paths(&code) {
            let name = segs.last().cloned().unwrap_or_default();
            add(resolve(&modules, &segs), &name);
        }
    }
    edges
}

/// The import cycles: the strongly connected components of more than one file, each sorted.
fn cycles(edges: &Edges) -> Vec<Vec<String>> {
    struct Tarjan<'a> {
        edges: &'a Edges,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        found: Vec<Vec<String>>,
    }
    impl<'a> Tarjan<'a> {
        fn visit(&mut self, v: &'a str) {
            let n = self.index.len();
            self.index.insert(v, n);
            self.low.insert(v, n);
            self.stack.push(v);
            self.on.insert(v);
            for w in self.edges.get(v).into_iter().flat_map(|m| m.keys()) {
                if !self.index.contains_key(w.as_str()) {
                    self.visit(w);
                    let lw = self.low[w.as_str()];
                    let lv = self.low.get_mut(v).expect("visited");
                    *lv = (*lv).min(lw);
                } else if self.on.contains(w.as_str()) {
                    let iw = self.index[w.as_str()];
                    let lv = self.low.get_mut(v).expect("visited");
                    *lv = (*lv).min(iw);
                }
            }
            if self.low[v] == self.index[v] {
                let mut comp = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on.remove(w);
                    comp.push(w.to_owned());
                    if w == v {
                        break;
                    }
                }
                if comp.len() > 1 {
                    comp.sort();
                    self.found.push(comp);
                }
            }
        }
    }
    let mut t = Tarjan {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !t.index.contains_key(v.as_str()) {
            t.visit(v);
        }
    }
    t.found.sort();
    t.found
}

/// One cycle through the first file of a component, with the names that tie each step:
/// `a.rs -> b.rs (X, Y) -> a.rs (Z)`, then every import inside the component.
fn describe(edges: &Edges, comp: &[String]) -> String {
    let inside: BTreeSet<&str> = comp.iter().map(String::as_str).collect();
    let start = comp[0].as_str();
    // Breadth-first from the start back to it, inside the component.
    let mut came: BTreeMap<&str, &str> = BTreeMap::new();
    let mut queue = std::collections::VecDeque::from([start]);
    let mut closing = None;
    while let Some(v) = queue.pop_front() {
        for w in edges.get(v).into_iter().flat_map(|m| m.keys()) {
            let w = w.as_str();
            if w == start {
                closing = Some(v);
                queue.clear();
                break;
            }
            if inside.contains(w) && !came.contains_key(w) {
                came.insert(w, v);
                queue.push_back(w);
            }
        }
    }
    let mut middle = Vec::new();
    let mut v = closing.expect("a component closes on its start");
    while v != start {
        middle.push(v);
        v = came[v];
    }
    middle.reverse();
    let path: Vec<&str> = [vec![start], middle, vec![start]].concat();
    let mut s = start.to_owned();
    for pair in path.windows(2) {
        let names: Vec<&str> = edges[pair[0]][pair[1]].iter().map(String::as_str).collect();
        s += &format!(" -> {} ({})", pair[1], names.join(", "));
    }
    for a in comp {
        for (b, names) in edges.get(a).into_iter().flatten() {
            if inside.contains(b.as_str()) {
                let names: Vec<&str> = names.iter().map(String::as_str).collect();
                s += &format!("\n    {a} -> {b}: {}", names.join(", "));
            }
        }
    }
    s
}

/// The text with comments and the contents of string and character literals blanked
/// (newlines kept), so that braces can be counted.
fn code_only(text: &str) -> Vec<char> {
    let c: Vec<char> = text.chars().collect();
    let mut out = c.clone();
    let blank = |out: &mut Vec<char>, from: usize, to: usize| {
        for ch in &mut out[from..to] {
            if *ch != '\n' {
                *ch = ' ';
            }
        }
    };
    let is_word = |ch: char| ch.is_alphanumeric() || ch == '_';
    let mut i = 0;
    while i < c.len() {
        let next = c.get(i + 1).copied();
        if c[i] == '/' && next == Some('/') {
            let end = (i..c.len()).find(|&k| c[k] == '\n').unwrap_or(c.len());
            blank(&mut out, i, end);
            i = end;
        } else if c[i] == '/' && next == Some('*') {
            let (mut depth, mut k) = (1, i + 2);
            while k < c.len() && depth > 0 {
                if c[k] == '/' && c.get(k + 1) == Some(&'*') {
                    depth += 1;
                    k += 2;
                } else if c[k] == '*' && c.get(k + 1) == Some(&'/') {
                    depth -= 1;
                    k += 2;
                } else {
                    k += 1;
                }
            }
            blank(&mut out, i, k);
            i = k;
        } else if c[i] == 'r'
            && (i == 0 || !is_word(c[i - 1]) || (c[i - 1] == 'b' && (i < 2 || !is_word(c[i - 2]))))
            && matches!(next, Some('"') | Some('#'))
        {
            // A raw string r"…", r#"…"#, br"…" (or a raw identifier r#name, left alone).
            let hashes = c[i + 1..].iter().take_while(|&&ch| ch == '#').count();
            if c.get(i + 1 + hashes) == Some(&'"') {
                let body = i + 2 + hashes;
                let mut k = body;
                while k < c.len() {
                    if c[k] == '"'
                        && c[k + 1..]
                            .iter()
                            .take(hashes)
                            .filter(|&&h| h == '#')
                            .count()
                            == hashes
                    {
                        break;
                    }
                    k += 1;
                }
                blank(&mut out, body, k.min(c.len()));
                i = (k + 1 + hashes).min(c.len());
            } else {
                i += 1;
            }
        } else if c[i] == '"' {
            let mut k = i + 1;
            while k < c.len() && c[k] != '"' {
                k += if c[k] == '\\' { 2 } else { 1 };
            }
            blank(&mut out, i + 1, k.min(c.len()));
            i = k + 1;
        } else if c[i] == '\'' {
            // A character literal ('x', '\n', '\u{..}'), or a lifetime ('a), left alone.
            if next == Some('\\') {
                let k = (i + 2..c.len()).find(|&k| c[k] == '\'').unwrap_or(c.len());
                blank(&mut out, i + 1, k);
                i = k + 1;
            } else if c.get(i + 2) == Some(&'\'') {
                blank(&mut out, i + 1, i + 2);
                i += 3;
            } else {
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    out
}

/// The functions of a text longer than `limit` lines: (name, first line, lines).
fn long_functions(text: &str, limit: usize) -> Vec<(String, usize, usize)> {
    let c = code_only(text);
    let is_word = |ch: char| ch.is_alphanumeric() || ch == '_';
    let line_at = |k: usize| 1 + c[..k].iter().filter(|&&ch| ch == '\n').count();
    let mut out = Vec::new();
    for i in 0..c.len().saturating_sub(2) {
        let starts_fn = c[i] == 'f'
            && c[i + 1] == 'n'
            && c[i + 2].is_whitespace()
            && (i == 0 || !is_word(c[i - 1]));
        if !starts_fn {
            continue;
        }
        let mut k = i + 2;
        while k < c.len() && c[k].is_whitespace() {
            k += 1;
        }
        let name: String = c[k..].iter().take_while(|&&ch| is_word(ch)).collect();
        if name.is_empty() {
            continue;
        }
        // The body: the first `{` before any `;` (a declaration without a body).
        let Some(open) = (k..c.len()).find(|&j| c[j] == '{' || c[j] == ';') else {
            continue;
        };
        if c[open] == ';' {
            continue;
        }
        let mut depth = 0usize;
        let mut close = None;
        for (j, &ch) in c.iter().enumerate().skip(open) {
            match ch {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        close = Some(j);
                        break;
                    }
                }
                _ => {}
            }
        }
        let Some(close) = close else { continue };
        let (first, last) = (line_at(i), line_at(close));
        if last - first + 1 > limit {
            out.push((name, first, last - first + 1));
        }
    }
    out
}

fn sources_of(files: &[(&str, &str)]) -> Sources {
    files
        .iter()
        .map(|(rel, text)| ((*rel).to_owned(), (*text).to_owned()))
        .collect()
}

#[test]
fn no_import_cycle_between_source_files_beyond_the_known_ones() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut sources = Sources::new();
    read_sources(&src, "", &mut sources);
    assert!(
        sources.len() > 50,
        "read {} files under {src:?}",
        sources.len()
    );

    let mut long = Vec::new();
    for (rel, text) in &sources {
        for (name, line, lines) in long_functions(without_unit_tests(text), LONG_FUNCTION) {
            long.push(format!("  src/{rel}:{line} fn {name}: {lines} lines"));
        }
    }
    println!(
        "functions longer than {LONG_FUNCTION} lines (listed, not asserted): {}",
        long.len()
    );
    for l in &long {
        println!("{l}");
    }

    let edges = imports(&sources);
    let found = cycles(&edges);
    let known: Vec<Vec<String>> = KNOWN_CYCLES
        .iter()
        .map(|c| c.iter().map(|s| (*s).to_owned()).collect())
        .collect();
    let new: Vec<String> = found
        .iter()
        .filter(|c| !known.contains(c))
        .map(|c| describe(&edges, c))
        .collect();
    let gone: Vec<String> = known
        .iter()
        .filter(|c| !found.contains(c))
        .map(|c| c.join(", "))
        .collect();
    assert!(
        new.is_empty() && gone.is_empty(),
        "import cycles between source files:\n  new (break them): {}\n  known but gone \
         (remove them from KNOWN_CYCLES): {}",
        if new.is_empty() {
            "none".to_owned()
        } else {
            new.join("\n  ")
        },
        if gone.is_empty() {
            "none".to_owned()
        } else {
            gone.join("; ")
        },
    );
}

#[test]
fn the_reader_finds_cycles_through_use_super_and_inline_paths_only() {
    // a → b by `use super::b::{X, y as z}`, b → c by an inline path, c → a by `use crate::`:
    // one cycle of three. The front door's re-export, the unit tests and a path through the
    // front door (`crate::m::D`) tie nothing; d is outside the cycle.
    let sources = sources_of(&[
        ("lib.rs", "pub mod m;\npub use crate::m::a::A;\n"),
        (
            "m/mod.rs",
            "mod a;\nmod b;\npub use a::A;\npub(crate) use self::d::D;\n",
        ),
        (
            "m/a.rs",
            "use super::b::{\n    X, y as z,\n};\npub struct A;\n",
        ),
        (
            "m/b.rs",
            "pub struct X;\nfn f() -> crate::m::c::C { todo!() }\n\
             #[cfg(test)]\nmod tests {\n    use crate::m::d::D;\n}\n",
        ),
        (
            "m/c.rs",
            "pub(crate) use crate::m::a::A;\nuse crate::m::D;\npub struct C;\n",
        ),
        (
            "m/d.rs",
            "use super::a::A;\n/// See [`crate::m::c::C`].\npub struct D;\n",
        ),
    ]);
    let edges = imports(&sources);
    let found = cycles(&edges);
    assert_eq!(found, vec![vec!["m/a.rs", "m/b.rs", "m/c.rs"]], "{edges:?}");
    assert_eq!(
        edges["m/a.rs"]["m/b.rs"],
        BTreeSet::from(["X".into(), "y".into()])
    );
    assert!(!edges["m/b.rs"].contains_key("m/d.rs"), "unit tests count");
    assert!(!edges.contains_key("lib.rs") && !edges.contains_key("m/mod.rs"));
    // d imports a and, through a doc link, c; nothing imports d: it is in no cycle.
    assert_eq!(edges["m/d.rs"].len(), 2);
    let text = describe(&edges, &found[0]);
    assert!(
        text.starts_with("m/a.rs -> m/b.rs (X, y) -> m/c.rs (C) -> m/a.rs (A)"),
        "{text}"
    );
    // Without the inline path, the cycle is broken.
    let mut broken = sources.clone();
    broken.insert("m/b.rs".into(), "pub struct X;\n".into());
    assert!(cycles(&imports(&broken)).is_empty());
}

#[test]
fn long_functions_are_measured_from_fn_to_its_closing_brace() {
    // Braces inside strings, characters and comments do not count; a declaration has no body.
    let mut text = String::from("trait T { fn decl(&self); }\nfn long() {\n    let s = \"}}\";\n");
    text += "    let c = '{'; // }\n    let r = r#\"}\"#;\n";
    for _ in 0..4 {
        text += "    let x = 1;\n";
    }
    text += "}\nfn short() {}\n";
    assert_eq!(long_functions(&text, 8), vec![("long".to_owned(), 2, 9)]);
    assert!(long_functions(&text, 9).is_empty());
}

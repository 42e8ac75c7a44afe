//! The documentation stands on its own: every relative link in README.md, cli/README.md,
//! ARCHITECTURE.md, CHANGELOG.md and docs/*.md leads to a file of the repository (and to an
//! anchor in it, where it names one), every `docs/<file>.md#anchor` cited in the code (the
//! program's too) exists, and no source file cites a document kept outside the repository (the source texts and their errata live elsewhere; the crate's own
//! account of them is docs/sources.md and docs/errata.md).

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The markdown documents whose links must resolve.
fn documents() -> Vec<PathBuf> {
    let mut docs = vec![
        root().join("README.md"),
        root().join("ARCHITECTURE.md"),
        root().join("cli/README.md"),
        root().join("CHANGELOG.md"),
    ];
    let mut more: Vec<PathBuf> = fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    more.sort();
    docs.extend(more);
    docs
}

/// Every `.rs` file under `dir`, recursively.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for e in entries {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The anchors a markdown file offers: explicit `id="…"` attributes and GitHub's slugs of its
/// headings (lower case; letters, digits, `-` and `_` kept, spaces turned into `-`).
fn anchors(text: &str) -> BTreeSet<String> {
    let mut set = BTreeSet::new();
    let mut rest = text;
    while let Some(i) = rest.find("id=\"") {
        rest = &rest[i + 4..];
        if let Some(j) = rest.find('"') {
            set.insert(rest[..j].to_string());
        }
    }
    let mut in_code = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
        }
        if in_code || !line.starts_with('#') {
            continue;
        }
        let title = line.trim_start_matches('#').trim();
        let slug: String = title
            .to_lowercase()
            .chars()
            .filter_map(|c| match c {
                ' ' => Some('-'),
                c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
                _ => None,
            })
            .collect();
        set.insert(slug);
    }
    set
}

/// The targets of the inline links `[text](target)` of a markdown text, outside code blocks.
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_code = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            continue;
        }
        let mut rest = line;
        while let Some(i) = rest.find("](") {
            rest = &rest[i + 2..];
            if let Some(j) = rest.find(')') {
                out.push(rest[..j].to_string());
                rest = &rest[j..];
            }
        }
    }
    out
}

/// Checks that `target` (a path relative to `from`'s folder, with an optional `#anchor`)
/// names an existing file and anchor. Returns a description of what is wrong, if anything.
fn check(from: &Path, target: &str) -> Option<String> {
    let (path, anchor) = match target.split_once('#') {
        Some((p, a)) => (p, Some(a)),
        None => (target, None),
    };
    let file = if path.is_empty() {
        from.to_path_buf()
    } else {
        from.parent().unwrap().join(path)
    };
    if !file.exists() {
        return Some(format!("{}: {target}: no such file", from.display()));
    }
    let anchor = anchor?;
    if file.extension().is_some_and(|e| e == "md") {
        let text = fs::read_to_string(&file).unwrap();
        if !anchors(&text).contains(anchor) {
            return Some(format!("{}: {target}: no such anchor", from.display()));
        }
    }
    None
}

#[test]
fn relative_links_in_the_documents_resolve() {
    let mut bad = Vec::new();
    let mut count = 0;
    for doc in documents() {
        let text = fs::read_to_string(&doc).unwrap();
        for target in links(&text) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            count += 1;
            bad.extend(check(&doc, &target));
        }
    }
    assert!(count > 10, "only {count} links found: is the parser right?");
    assert!(bad.is_empty(), "broken links:\n{}", bad.join("\n"));
}

/// The folders whose files must not cite documents outside the repository.
fn sources() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in [
        "src",
        "tests",
        "examples",
        "benches",
        "bench",
        "cli/src",
        "cli/tests",
    ] {
        rust_files(&root().join(dir), &mut files);
    }
    files.sort();
    files
}

#[test]
fn code_cites_only_documents_of_the_repository() {
    // Spelled in pieces, so that this file does not match itself.
    let errata_file = ["ERRATA", ".md"].concat();
    let outside = [
        ["../", "shared"].concat(),
        ["/work/", "shared"].concat(),
        ["seeds", "/"].concat(),
    ];
    let mut bad = Vec::new();
    for file in sources() {
        let text = fs::read_to_string(&file).unwrap();
        for (n, line) in text.lines().enumerate() {
            let at = format!("{}:{}", file.display(), n + 1);
            if outside.iter().any(|o| line.contains(o.as_str())) {
                bad.push(format!("{at}: a path outside the repository: {line}"));
            }
            // The source texts' errata are cited as docs/errata.md, never by the external
            // file's name or as a bare upper-case errata word before an id.
            if line.contains(&errata_file) || line.contains(["ERRATA", " "].concat().as_str()) {
                bad.push(format!("{at}: cite docs/errata.md instead: {line}"));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn anchors_cited_in_the_code_exist() {
    let mut bad = Vec::new();
    let mut count = 0;
    for file in sources() {
        let text = fs::read_to_string(&file).unwrap();
        let mut rest = text.as_str();
        while let Some(i) = rest.find("docs/") {
            rest = &rest[i..];
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || "/._-#".contains(c)))
                .unwrap_or(rest.len());
            let cited = rest[..end].trim_end_matches(['.', '#']);
            rest = &rest[end..];
            if !cited.contains(".md") {
                continue;
            }
            count += 1;
            let from = root().join("Cargo.toml");
            if let Some(e) = check(&from, cited) {
                bad.push(format!("{}: {e}", file.display()));
            }
            // Later anchors of the same citation: "docs/errata.md#e3, #e4".
            let doc = cited.split('#').next().unwrap().to_string();
            let mut tail = rest;
            while let Some(stripped) = tail
                .strip_prefix(", #")
                .or_else(|| tail.strip_prefix(" and #"))
            {
                let end = stripped
                    .find(|c: char| !(c.is_alphanumeric() || c == '-'))
                    .unwrap_or(stripped.len());
                let target = format!("{doc}#{}", &stripped[..end]);
                if let Some(e) = check(&from, &target) {
                    bad.push(format!("{}: {e}", file.display()));
                }
                tail = &stripped[end..];
            }
        }
    }
    assert!(
        count > 20,
        "only {count} citations found: is the parser right?"
    );
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// Every repository path a document quotes in code spans (`tests/…`, `src/…`, `benches/…`,
/// `examples/…`, `cli/…`, `linkages/…`, `docs/…`) names a file or folder that exists, from
/// the root or from the document's folder: a renamed or moved file leaves no stale pointer.
#[test]
fn every_quoted_repository_path_exists() {
    let prefixes = [
        "tests/",
        "src/",
        "benches/",
        "examples/",
        "cli/",
        "linkages/",
        "docs/",
    ];
    let mut missing = Vec::new();
    let mut quoted = 0;
    // The changelog is a history: it names files as they were when it was written.
    for doc in documents()
        .into_iter()
        .filter(|d| !d.ends_with("CHANGELOG.md"))
    {
        let text = fs::read_to_string(&doc).unwrap();
        for (k, span) in text.split('`').enumerate() {
            // The odd pieces are inside code spans; a path is one word there.
            if k % 2 == 0 || span.contains(char::is_whitespace) {
                continue;
            }
            let path = span.split(['#', ':']).next().unwrap_or("");
            if !prefixes.iter().any(|p| path.starts_with(p)) || path.contains(['*', '<', '…', '{'])
            {
                continue;
            }
            quoted += 1;
            // From the root, or (cli/README.md's `src/main.rs`) from the document's folder.
            if !root().join(path).exists() && !doc.parent().unwrap().join(path).exists() {
                missing.push(format!("{}: {path}", doc.display()));
            }
        }
    }
    println!("{quoted} quoted paths checked");
    assert!(
        quoted >= 20,
        "only {quoted} quoted paths found: the scan lost them"
    );
    assert!(missing.is_empty(), "{missing:#?}");
}

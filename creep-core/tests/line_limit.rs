//! Size limit of library source files: every `src/**/*.rs` of the workspace's member crates has at most [`MAX_LINES`] lines.
//!
//! Functions have their own limit, clippy's `too_many_lines` (clippy.toml at the workspace
//! root). Tests, benches and examples are outside `src` and not limited.

use std::path::{Path, PathBuf};

/// The most lines a source file under a member crate's `src` may have.
const MAX_LINES: usize = 900;

/// The member crates' directories, from the `members` array of the workspace's Cargo.toml.
fn members(root: &Path) -> Vec<PathBuf> {
    let manifest = root.join("Cargo.toml");
    let text = std::fs::read_to_string(&manifest)
        .unwrap_or_else(|e| panic!("{}: {e}", manifest.display()));
    let start = text
        .find("members")
        .and_then(|k| text[k..].find('[').map(|b| k + b + 1))
        .expect("a `members = [...]` array in the workspace's Cargo.toml");
    let end = start + text[start..].find(']').expect("the end of `members`");
    let names: Vec<&str> = text[start..end]
        .split(',')
        .map(|s| s.trim().trim_matches('"'))
        .filter(|s| !s.is_empty())
        .collect();
    for n in &names {
        assert!(
            !n.contains('*'),
            "member '{n}': globs are not expanded here"
        );
    }
    names.iter().map(|n| root.join(n)).collect()
}

/// Every `.rs` file under `dir`, recursively.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|x| x == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn library_source_files_stay_within_the_line_limit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the workspace root above creep-core");
    let members = members(root);
    assert!(members.len() >= 2, "members: {members:?}");
    let mut files = Vec::new();
    for m in &members {
        rust_files(&m.join("src"), &mut files);
    }
    files.sort();
    let mut over = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let n = text.lines().count();
        if n > MAX_LINES {
            over.push(format!(
                "  {}: {n} lines",
                f.strip_prefix(root).unwrap_or(f).display()
            ));
        }
    }
    assert!(
        over.is_empty(),
        "{} of {} library source files have more than {MAX_LINES} lines; split each by \
         meaning (a coherent part into a submodule):\n{}",
        over.len(),
        files.len(),
        over.join("\n")
    );
}

//! ARCHITECTURE.md's "may use" table is kept true: every `crate::MODULE` a module's code names
//! (outside its tests) is listed in that module's row, and in `mark` no kind imports another
//! kind and the shared room imports no kind.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `dir` (or the file `dir.rs`).
fn sources(module: &str) -> Vec<PathBuf> {
    let src = root().join("src");
    let mut out = Vec::new();
    let file = src.join(format!("{module}.rs"));
    if file.is_file() {
        out.push(file);
    }
    let mut stack = vec![src.join(module)];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else { continue };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// A file's code before its first top-level `#[cfg(test)]`, without comment lines (doc links
/// name modules without using them).
fn code(path: &Path) -> String {
    let text = std::fs::read_to_string(path).expect("source file reads");
    let text = match text.find("\n#[cfg(test)]") {
        Some(i) => &text[..i],
        None => &text,
    };
    text.lines().filter(|l| !l.trim_start().starts_with("//")).collect::<Vec<_>>().join("\n")
}

/// The crate modules named as `{prefix}NAME` in `text`.
fn named(text: &str, prefix: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for (i, _) in text.match_indices(prefix) {
        let rest = &text[i + prefix.len()..];
        let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
        if !name.is_empty() {
            out.insert(name);
        }
    }
    out
}

/// The table's rows: module → the crate modules it may use. "everything above" allows every
/// module of the rows before it.
fn table() -> BTreeMap<String, BTreeSet<String>> {
    let text = std::fs::read_to_string(root().join("ARCHITECTURE.md")).expect("ARCHITECTURE.md reads");
    let mut rows: Vec<(String, String)> = Vec::new();
    for line in text.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = line.split(" | ").collect();
        let Some(module) = cells.first().and_then(|c| c.trim_start_matches("| ").split('`').nth(1)) else { continue };
        let allowed = cells.last().copied().unwrap_or_default().to_string();
        rows.push((module.to_string(), allowed));
    }
    let modules: BTreeSet<String> = rows.iter().map(|(m, _)| m.clone()).collect();
    let mut out = BTreeMap::new();
    for (k, (module, allowed)) in rows.iter().enumerate() {
        let mut set = BTreeSet::new();
        for (j, quoted) in allowed.split('`').enumerate() {
            let first = quoted.split("::").next().unwrap_or_default();
            if j % 2 == 1 && modules.contains(first) {
                set.insert(first.to_string());
            }
        }
        if allowed.contains("everything above") {
            set.extend(rows[..k].iter().map(|(m, _)| m.clone()));
        }
        out.insert(module.clone(), set);
    }
    out
}

#[test]
fn every_module_uses_only_what_architecture_md_lists() {
    let table = table();
    assert!(table.len() >= 18, "the table lists the crate's modules: {:?}", table.keys());
    let mut problems = Vec::new();
    for (module, allowed) in &table {
        let (files, prefix) = if module == "cli" {
            let mut files = sources("cli");
            files.push(root().join("src/main.rs"));
            (files, "dataink::")
        } else {
            (sources(module), "crate::")
        };
        assert!(!files.is_empty(), "module `{module}` of ARCHITECTURE.md has no source");
        for file in files {
            for used in named(&code(&file), prefix) {
                if used != *module && table.contains_key(&used) && !allowed.contains(&used) {
                    problems.push(format!("{} uses `{used}`, not in `{module}`'s row", file.display()));
                }
            }
        }
    }
    assert!(problems.is_empty(), "ARCHITECTURE.md is out of date:\n{}", problems.join("\n"));
}

#[test]
fn no_kind_imports_another_kind_and_the_shared_room_imports_none() {
    let mark = root().join("src/mark");
    // A kind is a module with its `KIND` registration.
    let mut kinds: BTreeMap<String, String> = BTreeMap::new();
    for file in sources("mark") {
        let family = file.parent().and_then(Path::file_name).and_then(|f| f.to_str()).unwrap_or_default().to_string();
        let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or_default().to_string();
        if code(&file).contains("pub static KIND: KindInfo") {
            kinds.insert(stem, family);
        }
    }
    assert_eq!(kinds.len(), dataink::mark::registry::KINDS.len(), "one registered kind per module: {kinds:?}");
    let mut problems = Vec::new();
    for file in sources("mark") {
        let text = code(&file);
        let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or_default();
        let in_shared = file.starts_with(mark.join("shared"));
        for (kind, family) in &kinds {
            if kind == stem {
                continue;
            }
            let paths =
                [format!("crate::mark::{family}::{kind}"), format!("super::{kind}::"), format!("super::{kind};")];
            if (in_shared || kinds.contains_key(stem)) && paths.iter().any(|p| text.contains(p.as_str())) {
                problems.push(format!("{} imports the kind `{kind}`", file.display()));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_check_sees_a_use_the_table_does_not_list() {
    // The parser reads the real table: `scene` may use nothing, and `render` may use `scene`.
    let table = table();
    assert_eq!(table.get("scene"), Some(&BTreeSet::new()));
    assert!(table.get("render").is_some_and(|r| r.contains("scene") && !r.contains("spec")));
    assert!(named("use crate::spec::Chart; crate::data::Table", "crate::").contains("data"));
}

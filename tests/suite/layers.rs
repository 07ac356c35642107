//! The crate's layers point one way: a file in `src/<layer>/` names nothing of a layer above
//! its own, directly (`crate::physics::…`) or through the crate root's re-exports
//! (`crate::Rope`). The order is the one `src/lib.rs` declares and ARCHITECTURE.md draws.

use std::collections::HashMap;
use std::fs;
use std::path::Path;

const LAYERS: [&str; 7] = [
    "number", "geometry", "curves", "physics", "contact", "objects", "io",
];

/// The identifier at the start of `s`.
fn ident(s: &str) -> &str {
    let end = s
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(s.len());
    &s[..end]
}

/// What `src/lib.rs` re-exports at the root, by name: the layer it comes from.
fn root_names(lib: &str) -> HashMap<String, usize> {
    let mut names = HashMap::new();
    for line in lib.lines() {
        let Some(rest) = line.trim().strip_prefix("pub use ") else {
            continue;
        };
        let Some(layer) = LAYERS.iter().position(|l| ident(rest) == *l) else {
            continue;
        };
        for word in rest.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')) {
            if !word.is_empty() {
                names.entry(word.to_string()).or_insert(layer);
            }
        }
    }
    names
}

/// Every first path segment after `crate::` in `code`, groups (`crate::{a::B, C}`) included.
fn crate_paths(code: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        rest = &rest[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let mut depth = 1;
            let mut start = 0;
            for (i, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 1 => {
                        found.push(ident(group[start..].trim_start()).to_string());
                        start = i + 1;
                    }
                    _ => {}
                }
                if depth == 0 {
                    found.push(ident(group[start..].trim_start()).to_string());
                    break;
                }
            }
        } else {
            found.push(ident(rest).to_string());
        }
    }
    found
}

fn check_dir(dir: &Path, layer: usize, names: &HashMap<String, usize>, bad: &mut Vec<String>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            check_dir(&path, layer, names, bad);
            continue;
        }
        let text = fs::read_to_string(&path).unwrap();
        // The code only: no comments (doc links may point anywhere), no unit tests.
        let code: String = text
            .split("#[cfg(test)]\nmod tests")
            .next()
            .unwrap()
            .lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n");
        for name in crate_paths(&code) {
            let used = LAYERS
                .iter()
                .position(|l| *l == name)
                .or_else(|| names.get(&name).copied());
            if let Some(used) = used.filter(|&u| u > layer) {
                bad.push(format!(
                    "{} ({}) uses {name} ({})",
                    path.display(),
                    LAYERS[layer],
                    LAYERS[used]
                ));
            }
        }
    }
}

#[test]
fn every_layer_uses_only_the_layers_below_it() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let lib = fs::read_to_string(src.join("lib.rs")).unwrap();
    // The layers are declared in their order.
    let declared: Vec<&str> = lib
        .lines()
        .filter_map(|l| {
            l.trim()
                .strip_prefix("mod ")
                .or(l.trim().strip_prefix("pub mod "))
        })
        .map(|l| l.trim_end_matches(';'))
        .filter(|m| LAYERS.contains(m))
        .collect();
    assert_eq!(
        declared, LAYERS,
        "src/lib.rs declares the layers in this order"
    );
    let names = root_names(&lib);
    assert!(names.get("Rope") == Some(&5) && names.get("Q16") == Some(&0));
    let mut bad = Vec::new();
    for (layer, name) in LAYERS.iter().enumerate() {
        check_dir(&src.join(name), layer, &names, &mut bad);
    }
    assert!(bad.is_empty(), "upward dependencies:\n{}", bad.join("\n"));
}

/// The checker sees a use through a group and through a root re-export.
#[test]
fn the_checker_finds_paths_in_groups() {
    let paths =
        crate_paths("use crate::{physics::system::X, Rope};\nlet a = crate::io::view::f();");
    assert_eq!(paths, ["physics", "Rope", "io"]);
}

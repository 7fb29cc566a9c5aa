//! The shape of the code, held true: the runtime's layers import only
//! downwards, no crate has an import circle between its modules, and no file
//! or function outgrows what one reads at once (ARCHITECTURE.md has the map).
//!
//! These read the sources as text: an import is a `crate::module` path outside
//! a comment. That is what a newcomer reads too.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The runtime's layers, bottom first. A module may import from its own layer
/// and the layers below it; the services share a layer but must not import
/// one another in a circle.
const RUNTIME_LAYERS: &[&[&str]] = &[
    &["numeric"],
    &["error"],
    &["ode"],
    &["system", "pose", "orientation"],
    &["mechanics"],
    &[
        "atlas",
        "contact",
        "control",
        "event",
        "identify",
        "linear",
        "plan",
        "study",
        "table",
        "ensemble",
        "scene",
        "picture",
        "task_space",
    ],
    &["simulation"],
];

/// Files allowed past the size limits, with the reason. Kept short on purpose.
const LONG_FILES: &[(&str, &str)] = &[];

/// Functions allowed past 80 lines: ones that read better whole, with the
/// reason. (RADAU5's step is split into the phases of Hairer and Wanner's
/// radau5.f.)
const LONG_FUNCTIONS: &[(&str, &str, &str)] = &[
    (
        "lagrange-codegen/src/emit/lagrangian.rs",
        "lagrangian_trait",
        "one `impl Lagrangian` template and the bindings it interpolates: split, \
         the impl would be read in pieces",
    ),
    (
        "lagrange-runtime/src/linear/build.rs",
        "constrained",
        "the constrained linearisation's steps in their published order (the \
         saddle point, its sensitivities, the embedding of the independent \
         states, the named model), each a few lines that read the one before",
    ),
];

const MAX_FILE_LINES: usize = 600;
const MAX_FUNCTION_LINES: usize = 80;

fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if path.is_dir() {
            if name != "target" && !name.starts_with('.') {
                rust_files(&path, out);
            }
        } else if name.ends_with(".rs") {
            out.push(path);
        }
    }
}

fn relative(path: &Path) -> String {
    path.strip_prefix(workspace())
        .unwrap_or(path)
        .to_string_lossy()
        .replace('\\', "/")
}

/// The code of a line without its comment (a `//` outside a string).
fn code(line: &str) -> &str {
    let mut in_string = false;
    let bytes = line.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'\\' if in_string => i += 1,
            b'"' => in_string = !in_string,
            b'/' if !in_string && bytes.get(i + 1) == Some(&b'/') => return &line[..i],
            _ => {}
        }
        i += 1;
    }
    line
}

/// The top-level modules a source file names through `crate::module`.
fn crate_imports(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in text.lines() {
        let mut rest = code(line);
        while let Some(at) = rest.find("crate::") {
            let after = &rest[at + "crate::".len()..];
            let name: String = after
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.insert(name);
            }
            rest = after;
        }
    }
    out
}

/// The top-level module a file of `src` belongs to (`None` for the crate root).
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).ok()?;
    let first = rel.components().next()?.as_os_str().to_string_lossy();
    let name = first.trim_end_matches(".rs").to_string();
    (name != "lib" && name != "main").then_some(name)
}

/// Module → the modules it imports, for one crate's `src`.
fn module_graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in files {
        let Some(module) = module_of(src, &file) else {
            continue;
        };
        let text = fs::read_to_string(&file).unwrap();
        let entry = graph.entry(module.clone()).or_default();
        entry.extend(crate_imports(&text).into_iter().filter(|m| *m != module));
    }
    graph
}

/// A circle in the graph (as a path that returns to its start), if any.
fn find_circle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(at) = path.iter().position(|n| n == node) {
            let mut circle = path[at..].to_vec();
            circle.push(node.to_string());
            return Some(circle);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            if graph.contains_key(next)
                && let Some(c) = visit(next, graph, path, done)
            {
                return Some(c);
            }
        }
        path.pop();
        done.insert(node.to_string());
        None
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|n| visit(n, graph, &mut Vec::new(), &mut done))
}

fn layer_of(module: &str) -> Option<usize> {
    RUNTIME_LAYERS.iter().position(|l| l.contains(&module))
}

#[test]
fn runtime_imports_point_down() {
    let src = workspace().join("lagrange-runtime/src");
    let mut wrong = Vec::new();
    for (module, imports) in module_graph(&src) {
        let Some(own) = layer_of(&module) else {
            wrong.push(format!(
                "`{module}` is in no layer: add it to RUNTIME_LAYERS"
            ));
            continue;
        };
        for import in imports {
            match layer_of(&import) {
                Some(l) if l <= own => {}
                Some(_) => wrong.push(format!("`{module}` imports `{import}`, a higher layer")),
                None => wrong.push(format!(
                    "`{module}` imports `crate::{import}`: name the layer's path, not the root's re-export"
                )),
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn no_import_circle_in_any_crate() {
    for krate in ["lagrange-runtime", "lagrange-codegen", "lagrange-symbolic"] {
        let graph = module_graph(&workspace().join(krate).join("src"));
        assert_eq!(find_circle(&graph), None, "{krate} has an import circle");
    }
}

#[test]
fn the_circle_finder_finds_circles() {
    let graph: BTreeMap<String, BTreeSet<String>> = [
        ("a", vec!["b"]),
        ("b", vec!["c"]),
        ("c", vec!["a"]),
        ("d", vec!["a"]),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v.into_iter().map(String::from).collect()))
    .collect();
    let circle = find_circle(&graph).unwrap();
    assert_eq!(circle.first(), circle.last());
    assert_eq!(circle.len(), 4, "{circle:?}");
    assert_eq!(
        crate_imports("use crate::ode::X; // crate::linear"),
        ["ode".to_string()].into()
    );
}

/// Every `fn` item of a file with its line count, from its first line to the
/// line that closes its body (braces counted outside strings and comments).
fn functions(text: &str) -> Vec<(String, usize, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (start, line) in lines.iter().enumerate() {
        let Some(name) = fn_name(code(line)) else {
            continue;
        };
        let (mut depth, mut opened) = (0i32, false);
        for (end, body) in lines.iter().enumerate().skip(start) {
            let body = strip_literals(code(body));
            for c in body.chars() {
                match c {
                    '{' => (depth, opened) = (depth + 1, true),
                    '}' => depth -= 1,
                    _ => {}
                }
            }
            if !opened && body.trim_end().ends_with(';') {
                break;
            }
            if opened && depth <= 0 {
                out.push((name.clone(), start + 1, end - start + 1));
                break;
            }
        }
    }
    out
}

fn fn_name(line: &str) -> Option<String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let at = words.iter().position(|w| *w == "fn")?;
    let before_ok = words[..at].iter().all(|w| {
        w.starts_with("pub") || matches!(*w, "const" | "async" | "unsafe" | "extern" | "\"C\"")
    });
    let name: String = words
        .get(at + 1)?
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    (before_ok && !name.is_empty()).then_some(name)
}

/// The line with string and char literals emptied (their braces are not code).
fn strip_literals(line: &str) -> String {
    let mut out = String::new();
    let mut chars = line.chars().peekable();
    let mut in_string = false;
    while let Some(c) = chars.next() {
        match c {
            '\\' if in_string => {
                chars.next();
            }
            '"' => in_string = !in_string,
            '\'' if !in_string => {
                // A char literal such as '{' or '\n'; a lifetime has no closing quote.
                let ahead: String = chars.clone().take(3).collect();
                if ahead.chars().nth(1) == Some('\'') {
                    chars.nth(1);
                } else if ahead.starts_with('\\') && ahead.chars().nth(2) == Some('\'') {
                    chars.nth(2);
                }
            }
            _ if !in_string => out.push(c),
            _ => {}
        }
    }
    out
}

fn sources() -> Vec<PathBuf> {
    let mut files = Vec::new();
    rust_files(&workspace(), &mut files);
    files.sort();
    files
}

#[test]
fn no_file_past_what_one_reads_at_once() {
    let long: Vec<String> = sources()
        .iter()
        .filter_map(|f| {
            let n = fs::read_to_string(f).unwrap().lines().count();
            let rel = relative(f);
            (n > MAX_FILE_LINES && !LONG_FILES.iter().any(|(p, _)| *p == rel))
                .then(|| format!("{rel}: {n} lines"))
        })
        .collect();
    assert!(
        long.is_empty(),
        "files over {MAX_FILE_LINES} lines:\n{}",
        long.join("\n")
    );
}

#[test]
fn no_function_past_what_one_reads_at_once() {
    let mut long = Vec::new();
    for file in sources() {
        let rel = relative(&file);
        for (name, line, n) in functions(&fs::read_to_string(&file).unwrap()) {
            let allowed = LONG_FUNCTIONS
                .iter()
                .any(|(p, f, _)| *p == rel && *f == name);
            if n > MAX_FUNCTION_LINES && !allowed {
                long.push(format!("{rel}:{line} `{name}`: {n} lines"));
            }
        }
    }
    assert!(
        long.is_empty(),
        "functions over {MAX_FUNCTION_LINES} lines:\n{}",
        long.join("\n")
    );
}

#[test]
fn function_lengths_are_counted_from_fn_to_closing_brace() {
    let text = "fn a() {\n    let s = \"{\";\n    let c = '}';\n}\npub(crate) fn b<'x>(y: &'x str) -> usize { y.len() }\nfn c();\n";
    assert_eq!(
        functions(text),
        vec![("a".to_string(), 1, 4), ("b".to_string(), 5, 1)]
    );
}

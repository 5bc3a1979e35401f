//! The library keeps no state between calls (style: the caller owns what
//! is costly to build). No `static` item of any kind (`static`, `static mut`,
//! `thread_local!`, lazily initialised cells) may appear in `src/`: constants are
//! `const`, caches are values such as `KernelCache` that the caller creates.

use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().and_then(|e| e.to_str()) == Some("rs") {
            out.push(path);
        }
    }
}

/// The code part of a line: comments and string literals are not code.
fn code_of(line: &str) -> String {
    let mut out = String::new();
    let mut in_string = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' => in_string = !in_string,
            '\\' if in_string => {
                chars.next();
            }
            '/' if !in_string && chars.peek() == Some(&'/') => break,
            _ if !in_string => out.push(c),
            _ => {}
        }
    }
    out
}

#[test]
fn the_library_has_no_static_items() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    assert!(files.len() > 20, "found only {} source files", files.len());
    let forbidden = [
        "static ",
        "thread_local!",
        "OnceLock",
        "OnceCell",
        "LazyLock",
        "lazy_static",
    ];
    let mut found = Vec::new();
    for path in &files {
        let text = std::fs::read_to_string(path).unwrap();
        for (k, line) in text.lines().enumerate() {
            let code = code_of(line);
            // `&'static str` and `'static` bounds are lifetimes, not items.
            let code = code.replace("'static", "");
            if forbidden.iter().any(|f| code.contains(f)) {
                found.push(format!("{}:{}: {}", path.display(), k + 1, line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "static state in the library:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_scan_sees_a_static_item() {
    // The scan must be able to fail: a static item in code is found, the same words
    // in a comment or a string are not.
    assert!(code_of("static CACHE: Mutex<Vec<u8>> = Mutex::new(Vec::new());").contains("static "));
    assert!(!code_of("// a static cache").contains("static "));
    assert!(!code_of("let s = \"static \";").contains("static "));
}

//! The shape of the source: no file in `src/` over 1,000 lines and at most five functions over
//! 100, so that a long file or function is split along a concept before it grows further. Run
//! with `--nocapture` to see the longest of each.

use std::fs;
use std::path::{Path, PathBuf};

/// Most lines a file in `src/` may have.
const MAX_FILE_LINES: usize = 1000;
/// Functions longer than this count against [`MAX_LONG_FUNCTIONS`].
const LONG_FUNCTION_LINES: usize = 100;
/// Most functions in `src/` that may be longer than [`LONG_FUNCTION_LINES`].
const MAX_LONG_FUNCTIONS: usize = 5;

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut folders = vec![dir.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

/// `line` with comments, string and character literals blanked, so that only code braces,
/// brackets and semicolons are left; `in_block` carries a block comment across lines.
fn code_of(line: &str, in_block: &mut bool) -> String {
    let chars: Vec<char> = line.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    while i < chars.len() {
        let next = chars.get(i + 1).copied();
        if *in_block {
            if chars[i] == '*' && next == Some('/') {
                *in_block = false;
                i += 1;
            }
        } else if chars[i] == '/' && next == Some('/') {
            break;
        } else if chars[i] == '/' && next == Some('*') {
            *in_block = true;
            i += 1;
        } else if chars[i] == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
        } else if chars[i] == '\'' && (chars.get(i + 2) == Some(&'\'') || next == Some('\\')) {
            // A character literal ('{', '\n'); a lifetime has no closing quote nearby.
            i += 1;
            while i < chars.len() && chars[i] != '\'' {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
        } else {
            out.push(chars[i]);
        }
        i += 1;
    }
    out
}

/// Whether `code` starts a function: `fn name` after optional qualifiers.
fn starts_fn(code: &str) -> Option<String> {
    let mut words = code.split_whitespace().peekable();
    while let Some(w) = words.next() {
        match w {
            "pub" | "const" | "unsafe" | "async" | "extern" | "\"C\"" => continue,
            _ if w.starts_with("pub(") => continue,
            "fn" => {
                let name = words.next()?;
                let end = name.find(['(', '<']).unwrap_or(name.len());
                return Some(name[..end].to_string());
            }
            _ => return None,
        }
    }
    None
}

/// The functions of `text` with their lengths in lines, from the `fn` line to the closing brace
/// (declarations without a body are left out).
fn function_lengths(text: &str) -> Vec<(String, usize, usize)> {
    let mut in_block = false;
    let code: Vec<String> = text.lines().map(|l| code_of(l, &mut in_block)).collect();
    let mut found = Vec::new();
    for (start, line) in code.iter().enumerate() {
        let Some(name) = starts_fn(line) else {
            continue;
        };
        let (mut depth, mut nesting, mut opened) = (0i32, 0i32, false);
        'lines: for (end, line) in code.iter().enumerate().skip(start) {
            for c in line.chars() {
                match c {
                    '(' | '[' => nesting += 1,
                    ')' | ']' => nesting -= 1,
                    '{' => (depth, opened) = (depth + 1, true),
                    '}' => depth -= 1,
                    ';' if !opened && nesting == 0 => break 'lines,
                    _ => {}
                }
            }
            if opened && depth == 0 {
                found.push((name, start + 1, end - start + 1));
                break;
            }
        }
    }
    found
}

#[test]
fn function_lengths_count_from_fn_to_its_closing_brace() {
    let text = "fn a() {\n    let s = \"}\";\n}\nfn b(x: [u8; 2]) -> u8 {\n    x[0] // }\n}\n\
                trait T {\n    fn c(&self);\n}\n";
    let lengths = function_lengths(text);
    assert_eq!(
        lengths,
        [("a".to_string(), 1, 3), ("b".to_string(), 4, 3)],
        "{lengths:?}"
    );
}

#[test]
fn no_source_file_or_function_is_too_long() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    let mut functions = Vec::new();
    for path in rust_files(&src) {
        let text = fs::read_to_string(&path).unwrap();
        let shown = path.strip_prefix(&src).unwrap().display().to_string();
        files.push((text.lines().count(), shown.clone()));
        for (name, line, length) in function_lengths(&text) {
            functions.push((length, format!("src/{shown}:{line} {name}")));
        }
    }
    files.sort_unstable_by(|a, b| b.cmp(a));
    functions.sort_unstable_by(|a, b| b.cmp(a));
    println!("longest files: {:?}", &files[..3.min(files.len())]);
    println!(
        "longest functions: {:?}",
        &functions[..6.min(functions.len())]
    );
    let long_files: Vec<_> = files.iter().filter(|f| f.0 > MAX_FILE_LINES).collect();
    assert!(
        long_files.is_empty(),
        "files over {MAX_FILE_LINES} lines: {long_files:?}"
    );
    let long: Vec<_> = functions
        .iter()
        .filter(|f| f.0 > LONG_FUNCTION_LINES)
        .collect();
    println!("{} functions over {LONG_FUNCTION_LINES} lines", long.len());
    assert!(
        long.len() <= MAX_LONG_FUNCTIONS,
        "{} functions over {LONG_FUNCTION_LINES} lines (at most {MAX_LONG_FUNCTIONS}): {long:?}",
        long.len()
    );
}

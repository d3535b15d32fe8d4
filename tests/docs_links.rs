//! Every repository path and every Rust item that README.md and docs/*.md name in backticks or
//! link to exists. A renamed file, module, type or function fails this test until the
//! documentation that names it follows.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

/// Backticked text starting with one of these is a path from the repository root.
const PATH_PREFIXES: &[&str] = &[
    "src/",
    "tests/",
    "benches/",
    "docs/",
    "scenes/",
    "examples/",
    "farm/",
    "fuzz/",
    "assets/",
    "textures/",
    ".ci/",
    "../shared/",
];

/// Top-level files that backticked text may name without a folder.
const TOP_LEVEL_FILES: &[&str] = &[
    "Cargo.toml",
    "Cargo.lock",
    "README.md",
    "LICENSE",
    "CHANGELOG.md",
    "rust-toolchain.toml",
    "rustfmt.toml",
    "clippy.toml",
    "build.rs",
    ".gitignore",
];

/// Upper-case file stems that are real names, not placeholders such as `SCENE.json`.
const UPPER_CASE_NAMES: &[&str] = &["README", "ARCHITECTURE", "LICENSE", "CHANGELOG"];

/// Names that are not this crate's; dependencies in Cargo.toml are skipped as well.
const EXTERNAL_NAMES: &[&str] = &[
    "std",       // the standard library
    "core",      // the standard library
    "alloc",     // the standard library
    "glam",      // vector maths
    "clap",      // command-line parsing
    "serde",     // named when comparing scene parsers
    "rayon",     // thread pool
    "mi",        // Mitsuba 3's Python module (docs/path-tracing-vs-mitsuba.md)
    "dr",        // Dr.Jit's Python module, Mitsuba's array library
    "arbitrary", // the fuzz targets' input type, through libfuzzer-sys (docs/fuzzing.md)
    "Vec2",      // glam's type, re-exported by `math`: its methods are glam's
    "Vec3",      // glam's type, re-exported by `math`: its methods are glam's
    "Vec4",      // glam's type
];

/// Paths that name files in other repositories: the coursework corpus's submissions.
const EXTERNAL_PATHS: &[&str] = &[
    "tests/tri_mesh_test.json", // a corpus submission's scene (docs/scene-format.md)
    "examples/example.json",    // a corpus submission's scene (docs/scene-format.md)
];

/// Folders of the repository's other crates: integration tests, fuzz targets, examples.
const CRATE_FOLDERS: &[&str] = &["tests", "fuzz/fuzz_targets", "examples", "benches"];

/// Methods that derived or std-trait impls give a type without a `fn` in the source.
const STD_TRAIT_METHODS: &[&str] = &[
    "default",
    "clone",
    "fmt",
    "from",
    "into",
    "eq",
    "ne",
    "cmp",
    "partial_cmp",
    "hash",
    "drop",
    "deref",
    "deref_mut",
    "next",
    "try_from",
    "from_str",
    "as_ref",
    "to_string",
];

/// Keywords after which a name is defined.
const ITEM_KEYWORDS: &[&str] = &[
    "fn",
    "struct",
    "enum",
    "trait",
    "type",
    "const",
    "static",
    "mod",
    "union",
    "macro_rules",
];

/// Keywords after which a name is a type.
const TYPE_KEYWORDS: &[&str] = &["struct", "enum", "trait", "type", "union"];

#[derive(Debug, PartialEq)]
enum Kind {
    Code,
    Link,
}

/// Backticked text or a link target, with the line it starts on.
#[derive(Debug)]
struct Span {
    line: usize,
    kind: Kind,
    text: String,
}

/// The code spans and link targets of a markdown text, outside fenced code blocks.
fn scan(markdown: &str) -> Vec<Span> {
    let mut spans = Vec::new();
    let mut fence: Option<String> = None;
    let mut paragraph: Vec<(usize, &str)> = Vec::new();
    for (i, line) in markdown.lines().enumerate() {
        let trimmed = line.trim_start();
        if let Some(open) = &fence {
            if trimmed.starts_with(open.as_str()) {
                fence = None;
            }
            continue;
        }
        let marker = fence_marker(trimmed);
        if marker.is_some() || trimmed.is_empty() {
            scan_paragraph(&paragraph, &mut spans);
            paragraph.clear();
            fence = marker;
        } else {
            paragraph.push((i + 1, line));
        }
    }
    scan_paragraph(&paragraph, &mut spans);
    spans
}

/// The backtick or tilde run that opens a fenced code block on this line, if any.
fn fence_marker(trimmed: &str) -> Option<String> {
    let c = trimmed.chars().next()?;
    let run: String = trimmed.chars().take_while(|&d| d == c).collect();
    ((c == '`' || c == '~') && run.len() >= 3).then_some(run)
}

/// Code spans (which may run over lines) and links of one paragraph.
fn scan_paragraph(lines: &[(usize, &str)], spans: &mut Vec<Span>) {
    let Some(&(first, _)) = lines.first() else {
        return;
    };
    for &(line, text) in lines {
        if let Some(target) = reference_definition(text) {
            spans.push(Span {
                line,
                kind: Kind::Link,
                text: target.to_string(),
            });
        }
    }
    let text = lines.iter().map(|(_, l)| *l).collect::<Vec<_>>().join("\n");
    let bytes = text.as_bytes();
    let line_at = |i: usize| first + text[..i].matches('\n').count();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'`' {
            let run = bytes[i..].iter().take_while(|&&b| b == b'`').count();
            let Some((start, end)) = closing_run(&bytes[i + run..], run) else {
                i += run;
                continue;
            };
            let code = text[i + run..i + run + start].replace('\n', " ");
            spans.push(Span {
                line: line_at(i),
                kind: Kind::Code,
                text: code.trim().to_string(),
            });
            i += run + end;
        } else if bytes[i..].starts_with(b"](") {
            if let Some(target) = link_target(&text[i + 2..]) {
                spans.push(Span {
                    line: line_at(i),
                    kind: Kind::Link,
                    text: target,
                });
            }
            i += 2;
        } else {
            i += 1;
        }
    }
}

/// Start and end of the first backtick run exactly `len` long.
fn closing_run(bytes: &[u8], len: usize) -> Option<(usize, usize)> {
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] != b'`' {
            i += 1;
            continue;
        }
        let run = bytes[i..].iter().take_while(|&&b| b == b'`').count();
        if run == len {
            return Some((i, i + run));
        }
        i += run;
    }
    None
}

/// The target of an inline link, given the text after `](`.
fn link_target(rest: &str) -> Option<String> {
    let mut depth = 0;
    let close = rest.char_indices().find(|&(_, c)| {
        depth += i32::from(c == '(') - i32::from(c == ')');
        depth < 0
    })?;
    let inner = rest[..close.0].trim();
    let target = match inner.strip_prefix('<') {
        Some(angled) => angled.split('>').next()?,
        None => inner.split_whitespace().next()?,
    };
    Some(target.to_string())
}

/// The target of a reference definition line, `[label]: target`.
fn reference_definition(line: &str) -> Option<&str> {
    let rest = line.trim_start().strip_prefix('[')?;
    let (_, after) = rest.split_once("]:")?;
    after.split_whitespace().next()
}

/// The repository path that backticked text names, without `:LINE` or `#anchor`.
fn named_path(code: &str) -> Option<String> {
    let token = code.split_whitespace().next()?;
    let token = token.split([':', '#']).next()?;
    let token = token.strip_prefix("./").unwrap_or(token);
    let is_path =
        PATH_PREFIXES.iter().any(|p| token.starts_with(p)) || TOP_LEVEL_FILES.contains(&token);
    is_path.then(|| token.to_string())
}

/// A link target as a path from the repository root (`../` when it leaves it), or `None` for
/// URLs, anchors and build output.
fn link_path(markdown_dir: &str, target: &str) -> Option<String> {
    let target = target.split(['#', '?']).next()?;
    let scheme = target.split('/').next()?.contains(':');
    if target.is_empty() || target.starts_with('/') || scheme {
        return None;
    }
    let mut parts: Vec<&str> = markdown_dir.split('/').filter(|p| !p.is_empty()).collect();
    let mut above = 0;
    for part in target.split('/') {
        match part {
            "" | "." => {}
            ".." if parts.pop().is_none() => above += 1,
            ".." => {}
            _ => parts.push(part),
        }
    }
    let slash = if target.ends_with('/') { "/" } else { "" };
    let path = format!("{}{}{slash}", "../".repeat(above), parts.join("/"));
    (!path.starts_with("target/")).then_some(path)
}

/// Whether a path component stands for many files or for a name to fill in.
fn is_placeholder(component: &str) -> bool {
    if component.contains(['*', '?', '[', '{', '<', '>', '…']) || component.contains("...") {
        return true;
    }
    let stem = component.split('.').next().unwrap_or("");
    stem.chars().any(|c| c.is_ascii_uppercase())
        && !stem.chars().any(|c| c.is_ascii_lowercase())
        && !UPPER_CASE_NAMES.contains(&stem)
}

/// The part of a path before its first placeholder (a folder, ending in `/`), or the whole path.
fn fixed_part(path: &str) -> Option<String> {
    let components: Vec<&str> = path.split('/').collect();
    match components.iter().position(|c| is_placeholder(c)) {
        None => Some(path.to_string()),
        Some(0) => None,
        Some(k) => Some(format!("{}/", components[..k].join("/"))),
    }
}

/// Whether a `.gitignore` in the path's folders ignores it: such files are written by tools.
fn ignored(root: &Path, path: &str) -> bool {
    let components: Vec<&str> = path.trim_end_matches('/').split('/').collect();
    (0..components.len()).any(|k| {
        let rules = fs::read_to_string(root.join(components[..k].join("/")).join(".gitignore"));
        let rest = &components[k..];
        rules
            .unwrap_or_default()
            .lines()
            .any(|rule| ignore_rule_matches(rule.trim(), rest))
    })
}

/// A simple `.gitignore` rule (a name, `*.ext` or an anchored path) against a relative path.
fn ignore_rule_matches(rule: &str, rest: &[&str]) -> bool {
    if rule.is_empty() || rule.starts_with(['#', '!']) {
        return false;
    }
    let pattern = rule.trim_matches('/');
    if rule.starts_with('/') || pattern.contains('/') {
        let fixed: Vec<&str> = pattern.split('/').collect();
        return rest.starts_with(&fixed);
    }
    rest.iter().any(|c| match pattern.strip_prefix('*') {
        Some(suffix) => c.ends_with(suffix),
        None => *c == pattern,
    })
}

/// Checks that a path from the repository root exists; `../shared/` only where that folder does.
fn check_path(root: &Path, path: &str) -> Result<(), String> {
    let Some(fixed) = fixed_part(path) else {
        return Ok(());
    };
    if EXTERNAL_PATHS.contains(&path) {
        return Ok(());
    }
    let target = if let Some(shared) = fixed.strip_prefix("../shared/") {
        let folder = root.parent().map(|p| p.join("shared")).unwrap_or_default();
        if !folder.is_dir() {
            return Ok(());
        }
        folder.join(shared)
    } else if fixed.starts_with("../") {
        return Err("points outside the repository".to_string());
    } else if ignored(root, &fixed) {
        return Ok(());
    } else {
        root.join(&fixed)
    };
    let found = if fixed.ends_with('/') {
        target.is_dir()
    } else {
        target.exists()
    };
    match (found, fixed == path) {
        (true, _) => Ok(()),
        (false, true) => Err("no such file or folder".to_string()),
        (false, false) => Err(format!("its fixed part `{fixed}` does not exist")),
    }
}

/// The segments of backticked text shaped like a Rust path (`a::b`), or `None`.
fn item_segments(code: &str) -> Option<Vec<&str>> {
    let code = code.trim().trim_start_matches("..").trim_start_matches('&');
    let code = code.split('(').next()?.trim_end_matches('!');
    let segments: Vec<&str> = code.split("::").collect();
    let ident = |s: &&str| {
        let first = s
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
        first && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    };
    (segments.len() > 1 && segments.iter().all(ident)).then_some(segments)
}

/// The Rust sources of src/ and of `CRATE_FOLDERS`, by path from the repository root, and the
/// dependencies the manifests name.
struct Sources {
    files: BTreeMap<String, String>,
    dependencies: Vec<String>,
}

impl Sources {
    fn load(root: &Path) -> Sources {
        let mut files = BTreeMap::new();
        for dir in ["src"].iter().chain(CRATE_FOLDERS) {
            read_rust_files(root, &root.join(dir), &mut files);
        }
        let mut dependencies = Vec::new();
        for manifest in ["Cargo.toml", "fuzz/Cargo.toml"] {
            let text = fs::read_to_string(root.join(manifest)).unwrap_or_default();
            dependencies.extend(dependency_names(&text));
        }
        Sources {
            files,
            dependencies,
        }
    }

    /// The file of module `name` inside the folder `dir`.
    fn module_file(&self, dir: &str, name: &str) -> Option<String> {
        let candidates = [format!("{dir}/{name}.rs"), format!("{dir}/{name}/mod.rs")];
        let binary_root = format!("{dir}/{name}/main.rs");
        candidates
            .into_iter()
            .chain([binary_root])
            .find(|f| self.files.contains_key(f))
    }

    /// Whether `name` is defined in a module file or the files of its submodules.
    fn defined_in_tree(&self, file: &str, name: &str) -> bool {
        let below = format!("{}/", module_dir(file));
        self.files
            .iter()
            .filter(|(path, _)| *path == file || path.starts_with(&below))
            .any(|(_, text)| defines(text, name, ITEM_KEYWORDS))
    }
}

/// Reads every `.rs` file under `dir` into `files`.
fn read_rust_files(root: &Path, dir: &Path, files: &mut BTreeMap<String, String>) {
    let mut entries: Vec<PathBuf> = match fs::read_dir(dir) {
        Ok(entries) => entries.filter_map(|e| e.ok().map(|e| e.path())).collect(),
        Err(_) => return,
    };
    entries.sort();
    for path in entries {
        if path.is_dir() {
            read_rust_files(root, &path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let relative = path.strip_prefix(root).unwrap_or(&path);
            let key = relative.to_string_lossy().replace('\\', "/");
            files.insert(key, fs::read_to_string(&path).unwrap_or_default());
        }
    }
}

/// Crate names in a manifest's `[…dependencies]` tables, with `-` as `_`.
fn dependency_names(manifest: &str) -> Vec<String> {
    let mut in_table = false;
    let mut names = Vec::new();
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            in_table = line.ends_with("dependencies]");
        } else if let (true, Some((name, _))) = (in_table, line.split_once('=')) {
            names.push(name.trim().replace('-', "_"));
        }
    }
    names
}

/// The folder holding a module file's submodules.
fn module_dir(file: &str) -> &str {
    for root in ["/mod.rs", "/main.rs", "/lib.rs"] {
        if let Some(dir) = file.strip_suffix(root) {
            return dir;
        }
    }
    file.strip_suffix(".rs").unwrap_or(file)
}

/// The module name a file stands for.
fn module_name(file: &str) -> &str {
    module_dir(file).rsplit('/').next().unwrap_or("")
}

/// Whether a source text defines `name`: after one of `keywords`, as a field or enum variant,
/// or in a `pub use`.
fn defines(text: &str, name: &str, keywords: &[&str]) -> bool {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.starts_with("//"))
        .any(|line| {
            let tokens: Vec<&str> = line
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .filter(|t| !t.is_empty() && *t != "mut")
                .collect();
            let after_keyword = tokens
                .windows(2)
                .any(|w| w[1] == name && keywords.contains(&w[0]));
            let types_only = keywords == TYPE_KEYWORDS;
            after_keyword || (!types_only && member_or_reexport(line, name, &tokens))
        })
}

/// Whether a trimmed line declares a field or variant `name`, or re-exports it with `pub use`.
fn member_or_reexport(line: &str, name: &str, tokens: &[&str]) -> bool {
    let line = match line.strip_prefix("pub") {
        Some(rest) if rest.starts_with('(') => rest.split_once(')').map_or(rest, |(_, r)| r),
        Some(rest) => rest,
        None => line,
    };
    let line = line.trim_start();
    if line.starts_with("use ") && tokens.first() == Some(&"pub") {
        return tokens.contains(&name);
    }
    let Some(rest) = line.strip_prefix(name) else {
        return false;
    };
    if rest.starts_with(':') {
        return !rest.starts_with("::");
    }
    let rest = rest.trim_start();
    let variant = name.starts_with(|c: char| c.is_ascii_uppercase());
    variant && (rest.is_empty() || rest.starts_with([',', '(', '{']) || rest.starts_with("= "))
}

/// Checks that a Rust path names an item of this crate (or of one of its test crates).
fn resolve(sources: &Sources, segments: &[&str]) -> Result<(), String> {
    let segments = match segments {
        ["raytracer" | "crate", rest @ ..] => rest,
        _ => segments,
    };
    let Some(&first) = segments.first() else {
        return Ok(());
    };
    if EXTERNAL_NAMES.contains(&first) || first == "self" || first == "super" {
        return Ok(());
    }
    if first.starts_with(|c: char| c.is_ascii_uppercase()) {
        return resolve_type(sources, segments);
    }
    let top = sources.module_file("src", first);
    if top.is_none() && sources.dependencies.iter().any(|d| d == first) {
        return Ok(());
    }
    let candidates = module_candidates(sources, top, first);
    if candidates.is_empty() {
        return Err(format!(
            "no module `{first}` under src/, nor a crate or module `{first}` in {}",
            CRATE_FOLDERS.join(", ")
        ));
    }
    let results: Vec<Result<(), String>> = candidates
        .iter()
        .map(|file| walk(sources, file, &segments[1..]))
        .collect();
    results
        .iter()
        .find(|r| r.is_ok())
        .cloned()
        .unwrap_or_else(|| results[0].clone())
}

/// Files that module `name` may be: the top-level one under src/, a crate or module in
/// `CRATE_FOLDERS`, then modules of that name deeper in src/.
fn module_candidates(sources: &Sources, top: Option<String>, name: &str) -> Vec<String> {
    let crates = CRATE_FOLDERS
        .iter()
        .filter_map(|dir| sources.module_file(dir, name));
    let nested = sources
        .files
        .keys()
        .filter(|f| f.starts_with("src/") && module_name(f) == name);
    top.into_iter()
        .chain(crates)
        .chain(nested.cloned())
        .collect()
}

/// Follows module segments through files from `file`, then finds the rest defined there.
fn walk(sources: &Sources, file: &str, segments: &[&str]) -> Result<(), String> {
    let mut file = file.to_string();
    let mut rest = segments;
    while let Some((next, after)) = rest.split_first() {
        match sources.module_file(module_dir(&file), next) {
            Some(child) => file = child,
            None => break,
        }
        rest = after;
    }
    for name in rest {
        if !STD_TRAIT_METHODS.contains(name) && !sources.defined_in_tree(&file, name) {
            return Err(format!(
                "`{name}` is not defined in {file} or its submodules"
            ));
        }
    }
    Ok(())
}

/// Checks `Type::member…`: the type is defined under src/, the members where it or its impls are.
fn resolve_type(sources: &Sources, segments: &[&str]) -> Result<(), String> {
    let ty = segments[0];
    let src = || {
        sources
            .files
            .iter()
            .filter(|(path, _)| path.starts_with("src/"))
    };
    let defining: Vec<&String> = src()
        .filter(|(_, text)| defines(text, ty, TYPE_KEYWORDS))
        .map(|(_, t)| t)
        .collect();
    if defining.is_empty() {
        // A type this crate lacks with a PascalCase member (`Sampler::Get1D`) is C++: pbrt's.
        let cpp = segments
            .last()
            .is_some_and(|m| m.starts_with(|c: char| c.is_uppercase()));
        return if cpp && segments.len() > 1 {
            Ok(())
        } else {
            Err(format!("no type `{ty}` is defined under src/"))
        };
    }
    let impls = src().map(|(_, t)| t).filter(|text| implements(text, ty));
    let homes: Vec<&String> = defining.into_iter().chain(impls).collect();
    for name in &segments[1..] {
        let found = homes.iter().any(|text| defines(text, name, ITEM_KEYWORDS));
        if !found && !STD_TRAIT_METHODS.contains(name) {
            return Err(format!(
                "`{name}` is not defined where `{ty}` or its impls are"
            ));
        }
    }
    Ok(())
}

/// Whether a source text has an `impl` block for `ty`.
fn implements(text: &str, ty: &str) -> bool {
    text.lines()
        .map(str::trim)
        .filter(|l| l.starts_with("impl"))
        .any(|line| {
            line.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .any(|t| t == ty)
        })
}

/// Why a span names something that does not exist, or `None` when it is fine or not a name.
fn check_span(root: &Path, sources: &Sources, markdown_dir: &str, span: &Span) -> Option<String> {
    match span.kind {
        Kind::Code => {
            if let Some(path) = named_path(&span.text) {
                check_path(root, &path).err()
            } else {
                let segments = item_segments(&span.text)?;
                resolve(sources, &segments).err()
            }
        }
        Kind::Link => check_path(root, &link_path(markdown_dir, &span.text)?).err(),
    }
}

/// README.md and docs/*.md, by path from the repository root.
fn markdown_files(root: &Path) -> Vec<String> {
    let mut docs: Vec<String> = fs::read_dir(root.join("docs"))
        .expect("docs/ is readable")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|name| name.ends_with(".md"))
        .map(|name| format!("docs/{name}"))
        .collect();
    docs.sort();
    let mut files = vec!["README.md".to_string()];
    files.extend(docs);
    files
}

#[test]
fn every_path_and_item_named_in_the_docs_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let sources = Sources::load(root);
    let mut problems = Vec::new();
    for file in markdown_files(root) {
        let text = fs::read_to_string(root.join(&file)).expect("markdown is readable");
        let dir = file.rsplit_once('/').map_or("", |(dir, _)| dir);
        for span in scan(&text) {
            if let Some(why) = check_span(root, &sources, dir, &span) {
                problems.push(format!("{file}:{}: `{}` — {why}", span.line, span.text));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "{} names in the docs do not exist:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[cfg(test)]
mod scanner {
    use super::*;

    fn sources(files: &[(&str, &str)]) -> Sources {
        let files = files
            .iter()
            .map(|(p, t)| (p.to_string(), t.to_string()))
            .collect();
        Sources {
            files,
            dependencies: vec!["tobj".to_string()],
        }
    }

    fn example_crate() -> Sources {
        sources(&[
            (
                "src/accel/mod.rs",
                "mod bvh;\npub use bvh::Bvh;\npub const LIMIT: u32 = 4;",
            ),
            (
                "src/accel/bvh.rs",
                "pub struct Bvh {\n    pub nodes: Vec<u32>,\n}",
            ),
            (
                "src/material.rs",
                "pub enum Material {\n    Glass,\n}\nimpl Material {}",
            ),
            (
                "src/shading.rs",
                "impl Material {\n    pub fn shares(&self) {}\n}",
            ),
            ("src/cli/main.rs", "mod render;\nfn main() {}"),
            ("src/cli/render.rs", "pub fn run() {}"),
            ("tests/render.rs", "#[test]\nfn glass_is_bounded() {}"),
        ])
    }

    #[test]
    fn finds_backticked_text_and_links_with_their_lines() {
        let spans = scan("Intro.\n\nSee `src/lib.rs` and\n[the guide](docs/x.md#top).\n");
        let found: Vec<(usize, &str)> = spans.iter().map(|s| (s.line, s.text.as_str())).collect();
        assert_eq!(found, [(3, "src/lib.rs"), (4, "docs/x.md#top")]);
        assert_eq!(spans[1].kind, Kind::Link);
    }

    #[test]
    fn skips_fenced_blocks_and_joins_spans_over_lines() {
        let spans = scan("```\n`src/gone.rs`\n```\nrun `cargo test\n--release` now\n");
        assert_eq!(spans.len(), 1);
        assert_eq!(
            (spans[0].line, spans[0].text.as_str()),
            (4, "cargo test --release")
        );
    }

    #[test]
    fn named_paths_lose_line_numbers_and_skip_other_text() {
        assert_eq!(
            named_path("src/scene/load.rs:10–18").as_deref(),
            Some("src/scene/load.rs")
        );
        assert_eq!(
            named_path("benches/a.py --runs 3").as_deref(),
            Some("benches/a.py")
        );
        assert_eq!(named_path("Cargo.toml").as_deref(), Some("Cargo.toml"));
        assert_eq!(named_path("target/release/raytracer"), None);
        assert_eq!(named_path("out.png"), None);
        assert_eq!(named_path("raytracer scenes/demo.json demo.png"), None);
    }

    #[test]
    fn globs_and_placeholders_are_checked_up_to_their_fixed_folder() {
        assert_eq!(fixed_part("scenes/*.json").as_deref(), Some("scenes/"));
        assert_eq!(
            fixed_part("fuzz/artifacts/<target>/x").as_deref(),
            Some("fuzz/artifacts/")
        );
        assert_eq!(fixed_part("scenes/SCENE.json").as_deref(), Some("scenes/"));
        assert_eq!(
            fixed_part("docs/ARCHITECTURE.md").as_deref(),
            Some("docs/ARCHITECTURE.md")
        );
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        assert_eq!(check_path(root, "src/{a,b}.rs"), Ok(()));
        assert_eq!(check_path(root, "src/lib.rs"), Ok(()));
        assert!(check_path(root, "src/no_such_file.rs").is_err());
        assert!(check_path(root, "no_such_folder/<name>.rs").is_err());
    }

    #[test]
    fn links_resolve_from_the_markdown_folder() {
        assert_eq!(
            link_path("docs", "images/a.png").as_deref(),
            Some("docs/images/a.png")
        );
        assert_eq!(
            link_path("docs", "../farm/x.sh").as_deref(),
            Some("farm/x.sh")
        );
        assert_eq!(
            link_path("", "docs/x.md#part").as_deref(),
            Some("docs/x.md")
        );
        assert_eq!(link_path("docs", "../../x").as_deref(), Some("../x"));
        assert_eq!(link_path("docs", "https://example.com/a"), None);
        assert_eq!(link_path("docs", "#section"), None);
    }

    #[test]
    fn items_resolve_through_modules_types_and_test_crates() {
        let crate_ = example_crate();
        for item in [
            "accel::Bvh",
            "raytracer::accel::bvh::Bvh::nodes",
            "crate::accel::LIMIT",
            "Material::shares",
            "Material::Glass",
            "cli::render::run",
            "render::glass_is_bounded",
            "Bvh::default()",
        ] {
            let segments = item_segments(item).expect(item);
            assert_eq!(resolve(&crate_, &segments), Ok(()), "{item}");
        }
        for item in [
            "accel::Missing",
            "Material::Wood",
            "Missing::new",
            "nothing::here",
        ] {
            assert!(
                resolve(&crate_, &item_segments(item).unwrap()).is_err(),
                "{item}"
            );
        }
    }

    #[test]
    fn external_and_non_rust_names_are_skipped() {
        let crate_ = example_crate();
        for item in [
            "std::fs::read",
            "glam::Vec4",
            "mi::load_file",
            "tobj::load_obj",
        ] {
            assert_eq!(
                resolve(&crate_, &item_segments(item).unwrap()),
                Ok(()),
                "{item}"
            );
        }
        assert_eq!(resolve(&crate_, &["Sampler", "Get1D"]), Ok(()));
        for text in [
            "std::vector<int>",
            "echo ::error::x",
            "a ::: b",
            "http://x",
            "plain",
        ] {
            assert_eq!(item_segments(text), None, "{text}");
        }
    }
}

//! The repository stands alone and its tests cannot be switched off from outside: nothing in it
//! names a path above its root (a fresh clone has nothing beside it), and no test reads an
//! environment variable (the test command must check the same things whatever shell runs it).

use std::path::{Component, Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace root").to_path_buf()
}

/// What `.gitignore` leaves out: directory patterns and `*.suffix` file patterns (all it holds).
struct Ignored {
    dirs: Vec<String>,
    suffixes: Vec<String>,
}

impl Ignored {
    fn read(root: &Path) -> Self {
        let text = std::fs::read_to_string(root.join(".gitignore")).unwrap_or_default();
        let mut ignored = Ignored { dirs: vec![".git".into()], suffixes: Vec::new() };
        for line in text.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')) {
            match line.strip_prefix('*') {
                Some(suffix) => ignored.suffixes.push(suffix.to_string()),
                None => ignored.dirs.push(line.trim_matches('/').to_string()),
            }
        }
        ignored
    }

    /// `relative`: a path under the root, with `/` separators.
    fn covers(&self, relative: &str, is_dir: bool) -> bool {
        if !is_dir {
            return self.suffixes.iter().any(|s| relative.ends_with(s.as_str()));
        }
        let name = relative.rsplit('/').next().unwrap_or(relative);
        // A pattern with a slash is anchored at the root; one without matches a name anywhere.
        self.dirs.iter().any(|d| if d.contains('/') { relative == d } else { name == d })
    }
}

/// Every text file of the repository (not what `.gitignore` leaves out), as (relative path, text).
fn text_files() -> Vec<(String, String)> {
    let root = root();
    let ignored = Ignored::read(&root);
    let mut out = Vec::new();
    let mut stack = vec![root.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.unwrap().path();
            let relative = path.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
            let is_dir = path.is_dir();
            if ignored.covers(&relative, is_dir) {
                continue;
            }
            if is_dir {
                stack.push(path);
            } else if let Ok(text) = String::from_utf8(std::fs::read(&path).unwrap()) {
                if !text.contains('\0') {
                    out.push((relative, text));
                }
            }
        }
    }
    assert!(out.len() > 100, "found only {} text files under {}", out.len(), root.display());
    out
}

/// The folder a relative path on `line` of `file` is resolved against: a crate's manifest folder
/// for `CARGO_MANIFEST_DIR` paths; the file's own folder for Markdown links, `include_str!`,
/// scripts (`$(dirname "$0")`) and strings in code; the root for paths in Markdown's prose and
/// code spans (commands are run from the root).
fn base_of(file: &str, line: &str, token_start: usize) -> PathBuf {
    let root = root();
    let dir = root.join(file).parent().unwrap().to_path_buf();
    if line.contains("CARGO_MANIFEST_DIR") {
        return dir.ancestors().find(|d| d.join("Cargo.toml").exists()).expect("a crate").to_path_buf();
    }
    if file.ends_with(".md") {
        let in_link = line[..token_start].ends_with("](");
        return if in_link { dir } else { root };
    }
    dir
}

/// Each relative path on `line` that climbs (`..`), with where it starts.
fn climbing_paths(line: &str) -> Vec<(usize, &str)> {
    let stop = |c: char| c.is_whitespace() || "\"'`()[]<>,;=".contains(c);
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(at) = line[from..].find("../").map(|i| from + i) {
        let start = line[..at].rfind(stop).map_or(0, |i| i + 1);
        let end = line[at..].find(stop).map_or(line.len(), |i| at + i);
        out.push((start, &line[start..end]));
        from = end.max(at + 3);
    }
    out
}

/// Whether `path` (relative, maybe led by a `{}` placeholder or a `/` joined onto its base)
/// climbs above the root when resolved against `base`.
fn escapes(base: &Path, path: &str) -> bool {
    let path = path.trim_start_matches("{}").trim_start_matches('/');
    let mut depth = base.strip_prefix(root()).expect("a base inside the root").components().count() as i64;
    for part in Path::new(path).components() {
        match part {
            Component::ParentDir => depth -= 1,
            Component::Normal(_) => depth += 1,
            _ => {}
        }
        if depth < 0 {
            return true;
        }
    }
    false
}

#[test]
fn nothing_names_a_path_above_the_repository_root() {
    let mut found = Vec::new();
    // This file names such paths on purpose, to show the check catches them.
    for (file, text) in text_files().into_iter().filter(|(file, _)| file != "tests/repository.rs") {
        for (n, line) in text.lines().enumerate() {
            for (start, path) in climbing_paths(line) {
                if escapes(&base_of(&file, line, start), path) {
                    found.push(format!("{file}:{}: '{path}' reaches above the repository root", n + 1));
                }
            }
        }
    }
    assert!(found.is_empty(), "the repository must stand alone:\n{}", found.join("\n"));
}

#[test]
fn the_path_check_catches_what_it_is_for() {
    let root = root();
    let crate_dir = root.join("engine/scene");
    // The paths the conformance tests once read, from a crate two levels down and from docs.
    assert!(escapes(&crate_dir, "/../../../shared/testdata/khronos/Box.gltf"));
    assert!(escapes(&root.join("game"), "{}/../../shared/testdata/khronos/{file}"));
    assert!(escapes(&root, "../shared/DESIGN.md"));
    assert!(!escapes(&crate_dir, "/../../levels/cellar"));
    assert!(!escapes(&root.join("engine/src/passes"), "../../../shaders/composite.wgsl"));
    assert!(!escapes(&root.join("docs"), "../levels/cellar/preview.png"));
    let line = r#"const BOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/Box.gltf");"#;
    let paths = climbing_paths(line);
    assert_eq!(paths.iter().map(|p| p.1).collect::<Vec<_>>(), ["/../../../shared/Box.gltf"]);
    assert_eq!(base_of("engine/scene/tests/x.rs", line, paths[0].0), crate_dir);
    let md = "see [modding](../MODDING.md) and `../shared/DESIGN.md`";
    let paths = climbing_paths(md);
    assert_eq!(base_of("docs/x.md", md, paths[0].0), root.join("docs"));
    assert_eq!(base_of("docs/x.md", md, paths[1].0), root);
}

/// The source of every test, as (file, its lines that are test code): files under a `tests/`
/// folder and `tests.rs` modules whole, and in other sources each inline `#[cfg(test)]` module.
fn test_sources() -> Vec<(String, Vec<(usize, String)>)> {
    text_files()
        .into_iter()
        .filter(|(file, _)| file.ends_with(".rs"))
        .map(|(file, text)| {
            let lines: Vec<(usize, String)> = text.lines().map(String::from).enumerate().collect();
            let whole = file.starts_with("tests/") || file.contains("/tests/") || file.ends_with("/tests.rs");
            let test_lines = if whole { lines } else { inline_test_modules(&lines) };
            (file, test_lines)
        })
        .collect()
}

/// The lines of each `#[cfg(test)] mod NAME { … }` (to its closing brace); a `mod NAME;` names a
/// file the scan reads on its own.
fn inline_test_modules(lines: &[(usize, String)]) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut at = 0;
    while let Some(start) = lines[at..].iter().position(|(_, l)| l.trim() == "#[cfg(test)]").map(|i| at + i) {
        let opens = lines.get(start + 1).is_some_and(|(_, l)| l.trim_start().starts_with("mod ") && l.contains('{'));
        at = start + 1;
        if !opens {
            continue;
        }
        let mut depth = 0i64;
        for (n, line) in &lines[start + 1..] {
            depth += line.matches('{').count() as i64 - line.matches('}').count() as i64;
            out.push((*n, line.clone()));
            at = n + 1;
            if depth <= 0 {
                break;
            }
        }
    }
    out
}

#[test]
fn no_test_reads_the_environment() {
    // (Spelt in two halves so that this file does not find itself.)
    let reads = [concat!("env::", "var"), concat!("option_", "env!")];
    let sources = test_sources();
    let scanned = |file: &str| sources.iter().any(|(f, lines)| f == file && !lines.is_empty());
    assert!(scanned("tests/level_frames.rs") && scanned("game/src/golden.rs"), "the scan sees the tests");
    assert!(!scanned("game/ui/src/config.rs"), "only test modules are scanned");
    let mut found = Vec::new();
    for (file, lines) in &sources {
        for (n, line) in lines {
            if reads.iter().any(|r| line.contains(r)) {
                found.push(format!("{file}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "tests must not read the environment (an argument, a constant or a binary instead):\n{}",
        found.join("\n")
    );
}

/// Every Markdown file of the repository (README.md, MODDING.md, docs/, any other), as
/// (relative path, text).
fn markdown_files() -> Vec<(String, String)> {
    let files: Vec<_> = text_files().into_iter().filter(|(file, _)| file.ends_with(".md")).collect();
    assert!(files.iter().any(|(f, _)| f == "docs/gi.md"), "the scan sees the docs");
    files
}

/// The lines of Markdown `text` outside code fences, as (line number from 1, line).
fn prose_lines(text: &str) -> Vec<(usize, &str)> {
    let mut fenced = false;
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced {
            out.push((n + 1, line));
        }
    }
    out
}

/// The anchors of a Markdown file's headings as GitHub makes them: lower case, spaces to `-`,
/// all but letters, digits, `-` and `_` dropped; a repeated one gets `-1`, `-2`, ….
fn anchors(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut slugs: Vec<String> = Vec::new();
    for (_, line) in prose_lines(text) {
        let title = line.trim_start_matches('#');
        if title.len() == line.len() || !title.starts_with(' ') {
            continue;
        }
        let slug: String = title
            .trim()
            .to_lowercase()
            .chars()
            .filter_map(|c| match c {
                ' ' => Some('-'),
                c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
                _ => None,
            })
            .collect();
        let seen = slugs.iter().filter(|s| **s == slug).count();
        out.push(if seen == 0 { slug.clone() } else { format!("{slug}-{seen}") });
        slugs.push(slug);
    }
    out
}

/// Each link target on `line`, `[text](target)` or `![alt](target)`, without a title.
fn link_targets(line: &str) -> Vec<&str> {
    line.match_indices("](")
        .filter_map(|(at, _)| {
            let rest = &line[at + 2..];
            let end = rest.find([')', ' '])?;
            Some(&rest[..end])
        })
        .collect()
}

#[test]
fn markdown_links_resolve() {
    let root = root();
    let files = markdown_files();
    let mut found = Vec::new();
    for (file, text) in &files {
        for (n, line) in prose_lines(text) {
            for target in link_targets(line) {
                if target.contains("://") || target.starts_with("mailto:") {
                    continue;
                }
                let (path, anchor) = target.split_once('#').unwrap_or((target, ""));
                let linked =
                    if path.is_empty() { root.join(file) } else { root.join(file).parent().unwrap().join(path) };
                if !linked.exists() {
                    found.push(format!("{file}:{n}: '{target}': no such file"));
                } else if !anchor.is_empty() && linked.extension().is_some_and(|e| e == "md") {
                    let headings = anchors(&std::fs::read_to_string(&linked).unwrap());
                    if !headings.iter().any(|a| a == anchor) {
                        found.push(format!("{file}:{n}: '{target}': no heading makes #{anchor}"));
                    }
                }
            }
        }
    }
    assert!(found.is_empty(), "links in the docs must lead somewhere:\n{}", found.join("\n"));
}

#[test]
fn the_link_check_reads_links_and_headings_as_github_does() {
    let line = "see [the method](docs/gi.md#views) and ![a picture](levels/cellar/preview.png \"title\")";
    assert_eq!(link_targets(line), ["docs/gi.md#views", "levels/cellar/preview.png"]);
    let text = "# Title\n\n```\n# a comment in a code block\n```\n\
                ### The article's method (`gi.method = article`)\n## 2026-12-04: 640×360, a/b\n## Views\n## Views\n";
    assert_eq!(
        anchors(text),
        ["title", "the-articles-method-gimethod--article", "2026-12-04-640360-ab", "views", "views-1"]
    );
}

/// Phrases that tell how the project came to be rather than what it is. History lives in
/// `git log`, and measurements in docs/benchmarks.md's dated tables, not in the docs' prose.
const NARRATION: &[&str] = &[
    "until now",
    "until then",
    "until this",
    "last stop",
    "this stop",
    "previous stop",
    "stops ago",
    "this issue",
    "the issue's",
    "no longer",
    "used to",
    "since removed",
    "before this change",
    "after this change",
];

/// Where `text` (Markdown) tells its history: (line from 1, the phrase).
fn narration(text: &str) -> Vec<(usize, &'static str)> {
    narration_in(prose_lines(text), NARRATION)
}

/// [`NARRATION`] less what code says of what it does at run time ("the crawler no longer sees
/// you", "until then the old level runs").
fn code_narration() -> Vec<&'static str> {
    NARRATION.iter().copied().filter(|p| !["no longer", "until then", "until this"].contains(p)).collect()
}

/// The comments of Rust or WGSL `code`, as (line number from 1, the text after `//`).
fn comment_lines(code: &str) -> Vec<(usize, &str)> {
    code.lines().enumerate().filter_map(|(n, line)| line.find("//").map(|at| (n + 1, &line[at + 2..]))).collect()
}

/// Where `lines` tell their history: (line from 1, the phrase). Phrases are matched word by
/// word, so one wrapped across lines is found at its first word's line, and in any case; "used
/// to" in the passive ("is used to draw") is not history.
fn narration_in(lines: Vec<(usize, &str)>, phrases: &[&'static str]) -> Vec<(usize, &'static str)> {
    let words: Vec<(String, usize)> = lines
        .into_iter()
        .flat_map(|(n, line)| {
            line.split_whitespace()
                .map(move |w| (w.trim_matches(|c: char| !c.is_alphanumeric()).to_ascii_lowercase(), n))
        })
        .collect();
    let mut found = Vec::new();
    for i in 0..words.len() {
        for phrase in phrases {
            let here = words[i..].iter().map(|(w, _)| w.as_str());
            if !here.take(phrase.split(' ').count()).eq(phrase.split(' ')) {
                continue;
            }
            let before = if i > 0 { words[i - 1].0.as_str() } else { "" };
            if *phrase == "used to" && ["is", "are", "be", "been"].contains(&before) {
                continue;
            }
            found.push((words[i].1, *phrase));
        }
    }
    found
}

#[test]
fn no_doc_tells_its_history() {
    let mut found = Vec::new();
    for (file, text) in markdown_files() {
        for (n, phrase) in narration(&text) {
            found.push(format!("{file}:{n}: \"{phrase}\""));
        }
    }
    assert!(
        found.is_empty(),
        "docs describe the project as it is; how it got there is git log's (or a dated table in \
         docs/benchmarks.md):\n{}",
        found.join("\n")
    );
}

#[test]
fn no_comment_tells_its_history() {
    let mut found = Vec::new();
    let code = text_files().into_iter().filter(|(file, _)| file.ends_with(".rs") || file.ends_with(".wgsl"));
    for (file, text) in code {
        // This file names the phrases it looks for.
        if file == "tests/repository.rs" {
            continue;
        }
        for (n, phrase) in narration_in(comment_lines(&text), &code_narration()) {
            found.push(format!("{file}:{n}: \"{phrase}\""));
        }
    }
    assert!(
        found.is_empty(),
        "comments say why the code is as it is; how it got there is git log's:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_history_check_catches_what_it_is_for() {
    let sample = "The flicker, two stops\n  ago → now: 0.64 %.\nIt Used To be 45 rows; the\
                  \nsampler is used to draw.\n```\nno longer (in a code block)\n```\n";
    assert_eq!(narration(sample), [(1, "stops ago"), (3, "used to")]);
    assert_eq!(narration("Light volumes no longer exist."), [(1, "no longer")]);
    assert!(narration("The cuts split a light while it is wider than 0.45 of its distance.").is_empty());
    let code = "let x = 1; // a wall used to\n/// stop it, and since this stop\nlet s = \"used to\"; let t = 2;\n";
    assert_eq!(narration_in(comment_lines(code), &code_narration()), [(1, "used to"), (2, "this stop")]);
}

#[test]
fn the_readme_is_a_tour() {
    let lines = std::fs::read_to_string(root().join("README.md")).unwrap().lines().count();
    assert!(lines <= 150, "README.md has {lines} lines: it is a tour of 150 at most, the depth is docs/'s");
}

/// docs/architecture.md's table of the GI's stages names every GI shader and pass module, so a
/// stage's Rust, WGSL and tests are one search away.
#[test]
fn the_gi_stage_table_names_every_gi_shader_and_pass() {
    let root = root();
    let docs = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let start = docs.find("## The GI's stages").expect("docs/architecture.md has a section \"The GI's stages\"");
    let section = &docs[start..];
    let section = &section[..section[3..].find("\n## ").map_or(section.len(), |i| i + 3)];
    let mut missing = Vec::new();
    for (dir, ext) in [("shaders/gi", "wgsl"), ("plugin_gi/src/passes", "rs")] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let name = entry.unwrap().file_name().to_string_lossy().into_owned();
            if name.ends_with(ext) && name != "mod.rs" && !section.contains(&name) {
                missing.push(format!("{dir}/{name}"));
            }
        }
    }
    assert!(missing.is_empty(), "docs/architecture.md's table of the GI's stages does not name: {missing:?}");
}

/// A GI pass module and its WGSL are found by one name: `cuts` is passes/cuts.rs and cuts.wgsl.
#[test]
fn each_gi_pass_and_its_wgsl_share_a_name() {
    let root = root();
    let wgsl: Vec<String> = std::fs::read_dir(root.join("shaders/gi"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let mut unmatched = Vec::new();
    for entry in std::fs::read_dir(root.join("plugin_gi/src/passes")).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        let stem = name.trim_end_matches(".rs");
        // The parameters are a struct of gi_common.wgsl, which every stage includes.
        if ["mod", "params"].contains(&stem) {
            continue;
        }
        if !wgsl.iter().any(|w| w.starts_with(stem) && w.ends_with(".wgsl")) {
            unmatched.push(format!("plugin_gi/src/passes/{name}"));
        }
    }
    assert!(unmatched.is_empty(), "GI passes with no WGSL of their name in shaders/gi: {unmatched:?}");
}

//! The GI, golden and bench checks hold every figure through `bounds`, and their limits mean
//! something:
//! - no figure is compared with a bare `<`, `>`, `<=` or `>=` where a test decides (inside an
//!   `assert!`, an `if` that records a failure or panics, or a comparison kept for either),
//!   and no NaN-dropping `f64::max`/`min` is used: a NaN would pass either way;
//! - docs/testing.md's table of tolerances is the `bounds::tolerance!` declarations, and each
//!   leaves at most twice its measured worst's room, but for at most three, each with its
//!   reason.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the workspace root").to_path_buf()
}

/// The GI, golden and bench checks: the GI's and its reference's tests, the game's GI and bench
/// tests, the frame tests, and the golden comparison itself.
fn checked_files() -> Vec<String> {
    let root = root();
    let mut files = Vec::new();
    let mut walk = |dir: &str, keep: &dyn Fn(&str) -> bool| {
        let mut stack = vec![root.join(dir)];
        while let Some(d) = stack.pop() {
            for entry in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
                let path = entry.unwrap().path();
                let relative = path.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
                if path.is_dir() {
                    stack.push(path);
                } else if relative.ends_with(".rs") && keep(&relative) {
                    files.push(relative);
                }
            }
        }
    };
    walk("plugin_gi/tests", &|_| true);
    walk("plugin_gi/reference/tests", &|_| true);
    walk("game/tests", &|f| {
        let name = f.rsplit('/').next().unwrap();
        name.starts_with("gi_") || ["world_reference.rs", "bench_cli.rs"].contains(&name) || f.contains("/common/")
    });
    walk("tests", &|f| {
        ["tests/level_frames.rs", "tests/replay_frames.rs", "tests/golden_bounds.rs", "tests/view_model.rs"]
            .contains(&f)
    });
    files.extend(["game/src/golden.rs", "plugin_gi/src/metrics.rs"].map(String::from));
    files.sort();
    files
}

/// `source` with its comments and the insides of its string and character literals blanked
/// (newlines kept): code alone, at the same places as in the file.
fn code_only(source: &str) -> String {
    let s: Vec<char> = source.chars().collect();
    let mut out: Vec<char> = Vec::with_capacity(s.len());
    let blank = |c: char| if c == '\n' { '\n' } else { ' ' };
    let mut i = 0;
    while i < s.len() {
        let at = |k: usize| s.get(k).copied().unwrap_or('\0');
        if at(i) == '/' && at(i + 1) == '/' {
            while i < s.len() && s[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if at(i) == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            loop {
                if at(i) == '/' && at(i + 1) == '*' {
                    depth += 1;
                    out.extend([' ', ' ']);
                    i += 2;
                } else if at(i) == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    out.extend([' ', ' ']);
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else if i >= s.len() {
                    break;
                } else {
                    out.push(blank(s[i]));
                    i += 1;
                }
            }
        } else if at(i) == 'r'
            && (at(i + 1) == '"' || (at(i + 1) == '#' && matches!(at(i + 2), '"' | '#')))
            && !at(i.wrapping_sub(1)).is_alphanumeric()
        {
            // A raw string: r"…", r#"…"#.
            let mut hashes = 0;
            out.push('r');
            i += 1;
            while at(i) == '#' {
                hashes += 1;
                out.push('#');
                i += 1;
            }
            out.push('"');
            i += 1;
            while i < s.len() && !(s[i] == '"' && (1..=hashes).all(|k| at(i + k) == '#')) {
                out.push(blank(s[i]));
                i += 1;
            }
            out.push('"');
            out.extend(std::iter::repeat_n('#', hashes));
            i += 1 + hashes;
        } else if at(i) == '"' {
            out.push('"');
            i += 1;
            while i < s.len() && s[i] != '"' {
                if s[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                out.push(blank(at(i)));
                i += 1;
            }
            out.push('"');
            i += 1;
        } else if at(i) == '\'' && (at(i + 1) == '\\' || at(i + 2) == '\'') {
            // A character literal ('x', '\n', '\''); a lifetime ('a) has no closing quote there.
            out.push('\'');
            i += 1;
            if at(i) == '\\' {
                out.extend([' ', ' ']);
                i += 2;
            }
            while i < s.len() && s[i] != '\'' {
                out.push(' ');
                i += 1;
            }
            out.push('\'');
            i += 1;
        } else {
            out.push(s[i]);
            i += 1;
        }
    }
    out.into_iter().collect()
}

/// Whether `code` holds a comparison: `<`, `>`, `<=` or `>=` with a space either side (as
/// rustfmt writes them; generics, arrows and shifts have none).
fn has_comparison(code: &[char]) -> bool {
    (1..code.len()).any(|i| {
        let after = |k: usize| code.get(i + k).copied().unwrap_or('\n');
        matches!(code[i], '<' | '>')
            && code[i - 1] == ' '
            && (after(1).is_whitespace() || (after(1) == '=' && after(2).is_whitespace()))
    })
}

/// The index just past the bracket that closes the one at `open`.
fn closing(code: &[char], open: usize) -> usize {
    let mut depth = 0i32;
    for (i, &c) in code.iter().enumerate().skip(open) {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => {
                depth -= 1;
                if depth == 0 {
                    return i + 1;
                }
            }
            _ => {}
        }
    }
    code.len()
}

/// Where the word `word` starts in `code`, not as part of a longer name.
fn words(code: &[char], word: &str) -> Vec<usize> {
    let w: Vec<char> = word.chars().collect();
    let name = |c: char| c.is_alphanumeric() || c == '_';
    (0..code.len().saturating_sub(w.len() - 1))
        .filter(|&i| code[i..i + w.len()] == w[..])
        .filter(|&i| (i == 0 || !name(code[i - 1])) && !code.get(i + w.len()).is_some_and(|&c| name(c)))
        .collect()
}

fn text(code: &[char], range: std::ops::Range<usize>) -> String {
    code[range].iter().collect()
}

/// Each place in `source` where a figure escapes `bounds`, as `LINE: what`.
fn bare_checks(source: &str) -> Vec<String> {
    let code: Vec<char> = code_only(source).chars().collect();
    let line = |at: usize| code[..at].iter().filter(|&&c| c == '\n').count() + 1;
    let mut found = Vec::new();
    // Comparisons inside an assertion.
    let mut assertions = Vec::new();
    for name in ["assert", "debug_assert", "assert_ne", "debug_assert_ne"] {
        for at in words(&code, name) {
            let open = at + name.len() + 1;
            if code.get(at + name.len()) == Some(&'!') && code.get(open) == Some(&'(') {
                let end = closing(&code, open);
                assertions.push(open..end);
                if has_comparison(&code[open..end]) {
                    found.push(format!("{}: a comparison inside {name}!", line(at)));
                }
            }
        }
    }
    // An `if` on a comparison whose block records a failure or panics.
    for at in words(&code, "if") {
        let Some(open) = (at..code.len()).find(|&i| code[i] == '{' || code[i] == ';') else { continue };
        if code[open] != '{' || !has_comparison(&code[at..open]) {
            continue;
        }
        let body = text(&code, open..closing(&code, open));
        if ["failures", "panic!", "return Err", "format!"].iter().any(|f| body.contains(f)) {
            found.push(format!("{}: an if on a comparison that decides a failure", line(at)));
        }
    }
    // A comparison kept in a `let` and then asserted or turned into a failure.
    for at in words(&code, "let") {
        let Some(end) = (at..code.len()).find(|&i| code[i] == ';') else { continue };
        let statement = text(&code, at..end);
        let Some((binding, value)) = statement.split_once(" = ") else { continue };
        // (A comparison inside a closure, as a filter's or `all`'s, computes; it is not kept.)
        if value.contains('|') || !has_comparison(&value.chars().collect::<Vec<_>>()) {
            continue;
        }
        if value.contains(".then(") || value.contains(".then_some(") {
            found.push(format!("{}: a comparison turned into a failure", line(at)));
            continue;
        }
        let name = binding.trim_start_matches("let").trim().trim_start_matches("mut ").trim();
        let rest: Vec<char> = code[end..].to_vec();
        let used_in_assert = assertions.iter().any(|r| r.start > end && !words(&code[r.clone()], name).is_empty());
        let then = words(&rest, name)
            .into_iter()
            .any(|i| text(&rest, i..rest.len().min(i + name.len() + 6)).ends_with(".then("));
        if used_in_assert || then {
            found.push(format!("{}: a comparison kept in `{name}` and then asserted", line(at)));
        }
    }
    // Folds and pairs that drop a NaN.
    for ty in ["f32", "f64"] {
        for f in ["max", "min"] {
            let path = format!("{ty}::{f}");
            for at in words(&code, &path) {
                found.push(format!("{}: {path} drops a NaN (bounds::worst or bounds::least keep it)", line(at)));
            }
        }
    }
    // A running worst: `worst = worst.max(error)` (a clamp such as `cos.max(0.01)` computes).
    for f in ["max", "min"] {
        for at in words(&code, f) {
            if at == 0 || code[at - 1] != '.' || code.get(at + f.len()) != Some(&'(') {
                continue;
            }
            let receiver_start =
                (0..at - 1).rev().find(|&i| !(code[i].is_alphanumeric() || code[i] == '_')).map_or(0, |i| i + 1);
            let receiver = text(&code, receiver_start..at - 1);
            let before = text(&code, receiver_start.saturating_sub(receiver.len() + 3)..receiver_start);
            if !receiver.is_empty() && before == format!("{receiver} = ") {
                found
                    .push(format!("{}: {receiver} = {receiver}.{f}(…) drops a NaN (bounds::worst keeps it)", line(at)));
            }
        }
    }
    found.sort_by_key(|f| f.split(':').next().unwrap().parse::<usize>().unwrap());
    found
}

#[test]
fn no_gi_golden_or_bench_check_compares_a_figure_bare() {
    let files = checked_files();
    assert!(files.len() > 25, "found only {files:?}");
    let mut found = Vec::new();
    for file in &files {
        let source = std::fs::read_to_string(root().join(file)).unwrap();
        found.extend(bare_checks(&source).into_iter().map(|f| format!("{file}:{f}")));
    }
    assert!(found.is_empty(), "hold these through `bounds` (NaN passes a bare comparison):\n{}", found.join("\n"));
}

#[test]
fn each_way_a_nan_could_pass_is_found() {
    let cases = [
        ("fn t() { assert!(error < 0.05, \"{error}\"); }", "1: a comparison inside assert!"),
        (
            "fn t() {\n    if error > goal || gain.abs() > energy_goal {\n        failures.push(name);\n    }\n}",
            "2: an if",
        ),
        ("fn t() { let bad = f.error > limit.0; bad.then(|| 1) }", "1: a comparison kept in `bad`"),
        ("fn t() { let ok = x <= 1.0;\n assert!(ok); }", "1: a comparison kept in `ok`"),
        ("fn t() { (x >= 1.0).then(|| 2); let b = (x >= 1.0).then_some(2); }", "1: a comparison turned"),
        ("fn t() { let w = v.iter().copied().fold(0.0, f64::max); }", "1: f64::max drops a NaN"),
        ("fn t() { worst = worst.max(error.abs()); }", "1: worst = worst.max(…) drops a NaN"),
    ];
    for (source, expected) in cases {
        let found = bare_checks(source);
        assert!(found.iter().any(|f| f.starts_with(expected)), "{source}: {found:?}");
    }
    // What is not a check: generics, arrows, shifts, equality, a mask's comparison, words in
    // strings and comments, a comparison that only steers a loop, an iterator's max.
    let fine = "fn t(v: Vec<f64>) -> Option<u32> {\n    let m: Vec<bool> = v.iter().map(|x| *x > 0.5).collect();\n    \
                assert!(a == b, \"x < y, {} > {}\", 1 << 20, 2 >> 1); // a > b\n    \
                if t < 0 { continue; }\n    let n = v.iter().map(|_| 1u32).max();\n    let c = cos.max(0.01);\n    \
                assert!((0.0..1.0).contains(&e), 'x');\n    None\n}";
    assert_eq!(bare_checks(fine), Vec::<String>::new());
}

/// A `bounds::tolerance!` declaration as written in its file.
#[derive(Debug)]
struct Declared {
    name: String,
    what: String,
    kind: &'static str,
    /// The limit and the measured worst as written.
    limit_text: String,
    measured_text: String,
    limit: f64,
    measured: f64,
    wider: Option<String>,
}

impl Declared {
    /// Limit ÷ measured (measured ÷ limit for a floor); 1 for an exact check, 0 that measured 0.
    fn room(&self) -> f64 {
        if self.limit == self.measured {
            return 1.0;
        }
        match self.kind {
            "≥" => self.measured / self.limit,
            _ => self.limit / self.measured.abs(),
        }
    }
}

/// Every `tolerance!` declaration in `source` (`file` names them).
fn declarations(file: &str, source: &str) -> Vec<Declared> {
    let code: Vec<char> = code_only(source).chars().collect();
    let raw: Vec<char> = source.chars().collect();
    let mut out = Vec::new();
    for at in words(&code, "tolerance") {
        let Some(open) = code.get(at + 9..).and_then(|r| {
            (r.first() == Some(&'!')).then(|| (at + 10..code.len()).find(|&i| !code[i].is_whitespace()))?
        }) else {
            continue;
        };
        if !matches!(code[open], '(' | '{') {
            continue;
        }
        let body = text(&raw, open + 1..closing(&code, open) - 1);
        if body.contains("$name") {
            continue; // the macro's own definition
        }
        let what: Vec<&str> = body.lines().filter_map(|l| l.trim().strip_prefix("///")).map(str::trim).collect();
        let decl = body.lines().filter(|l| !l.trim().starts_with("///")).collect::<Vec<_>>().join(" ");
        let (name, rest) = decl.split_once(':').unwrap_or_else(|| panic!("{file}: a tolerance without a name: {body}"));
        let name = name.trim().trim_start_matches("pub(crate)").trim_start_matches("pub").trim().to_string();
        let (rest, wider) = match rest.split_once(", wider ") {
            Some((r, w)) => (r, Some(w.trim().trim_end_matches(';').trim().trim_matches('"').to_string())),
            None => (rest, None),
        };
        let (limit, measured) = rest.split_once(", measured ").unwrap_or_else(|| panic!("{file}: {name}: {rest}"));
        let (kind, limit) = limit.trim().split_once(' ').unwrap_or_else(|| panic!("{file}: {name}: {limit}"));
        let kind = match kind {
            "at_most" => "≤",
            "at_least" => "≥",
            "magnitude" => "|x| ≤",
            other => panic!("{file}: {name}: no kind {other}"),
        };
        let written = |s: &str| s.trim().trim_end_matches(';').trim().to_string();
        let number = |s: &str| -> f64 { s.parse().unwrap_or_else(|e| panic!("{file}: {name}: '{s}': {e}")) };
        let (limit_text, measured_text) = (written(limit), written(measured));
        out.push(Declared {
            name: format!("{file}: {name}"),
            what: what.join(" "),
            kind,
            limit: number(&limit_text),
            measured: number(&measured_text),
            limit_text,
            measured_text,
            wider,
        });
    }
    out
}

/// Every tolerance declared in the repository's crates.
fn all_declarations() -> Vec<Declared> {
    let root = root();
    let mut out = Vec::new();
    let mut stack = vec![root.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let relative = path.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
            if path.is_dir() {
                if !["target", ".git"].contains(&relative.as_str()) && !relative.starts_with("engine/bounds") {
                    stack.push(path);
                }
            } else if relative.ends_with(".rs") && relative != "tests/figure_checks.rs" {
                let source = std::fs::read_to_string(&path).unwrap();
                out.extend(declarations(&relative, &source));
            }
        }
    }
    out.sort_by(|a, b| a.name.cmp(&b.name));
    out
}

/// docs/testing.md's table of tolerances, from the declarations.
fn table(declared: &[Declared]) -> String {
    let mut s = String::from(
        "| tolerance | what it holds | limit | measured worst | room | why wider than 2× |\n\
         | --- | --- | ---: | ---: | ---: | --- |\n",
    );
    for d in declared {
        s += &format!(
            "| `{}` | {} | {} {} | {} | {:.1}× | {} |\n",
            d.name,
            d.what,
            // A `|` would end the cell.
            if d.kind == "|x| ≤" { "±" } else { d.kind },
            d.limit_text,
            d.measured_text,
            d.room(),
            d.wider.as_deref().unwrap_or("")
        );
    }
    s
}

const TABLE_START: &str = "<!-- tolerances: tests/figure_checks.rs keeps this table equal to the declarations -->";
const TABLE_END: &str = "<!-- end of tolerances -->";

#[test]
fn the_tolerances_table_is_the_declarations_and_each_limit_is_near_what_it_measures() {
    let declared = all_declarations();
    assert!(declared.len() >= 20, "found only {} tolerances", declared.len());
    let docs = std::fs::read_to_string(root().join("docs/testing.md")).unwrap();
    let expected = table(&declared);
    let start = docs.find(TABLE_START).map(|i| i + TABLE_START.len() + 1);
    let end = docs.find(TABLE_END);
    let written = start.zip(end).map(|(s, e)| &docs[s..e]);
    assert!(
        written == Some(expected.as_str()),
        "docs/testing.md's table of tolerances (between `{TABLE_START}` and `{TABLE_END}`) is not the \
         declarations; put this there:\n\n{expected}"
    );
    let mut wrong = Vec::new();
    for d in &declared {
        let room = d.room();
        // Each comparison is true only for a number, so a NaN room is wrong on every line.
        let near = room <= 2.0;
        let far = room > 2.0;
        let holds = room >= 1.0;
        match &d.wider {
            None if !near => wrong.push(format!("{}: {room:.2}× the measured worst, no reason given", d.name)),
            Some(_) if !far => wrong.push(format!("{}: a reason to be wider, but only {room:.2}×", d.name)),
            Some(why) if why.len() < 20 => wrong.push(format!("{}: the reason '{why}' says too little", d.name)),
            _ => {}
        }
        if !holds {
            wrong.push(format!("{}: the measured worst {} already breaks the limit", d.name, d.measured));
        }
    }
    let wider = declared.iter().filter(|d| d.wider.is_some()).count();
    if wider > 3 {
        wrong.push(format!("{wider} tolerances are wider than twice their measured worst (at most 3)"));
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn a_declaration_is_read_with_its_reason_and_its_room() {
    let source = "bounds::tolerance! {\n    /// The box's error.\n    /// Second line.\n    pub ERROR: at_most 0.05, \
                  measured 0.03\n}\nbounds::tolerance!(LEAK: at_least 0.02, measured 0.035, wider \"a floor the \
                  unseen case sets\");\n";
    let d = declarations("x.rs", source);
    assert_eq!(d.len(), 2);
    assert_eq!(
        (d[0].name.as_str(), d[0].what.as_str(), d[0].kind),
        ("x.rs: ERROR", "The box's error. Second line.", "≤")
    );
    assert_eq!((d[0].limit, d[0].measured, d[0].wider.as_deref()), (0.05, 0.03, None));
    assert_eq!((d[1].kind, d[1].wider.as_deref()), ("≥", Some("a floor the unseen case sets")));
    assert!(table(&d).contains("| `x.rs: LEAK` |  | ≥ 0.02 | 0.035 | 1.8× | a floor the unseen case sets |"));
}

//! Shared numbers (`engine::shared_constants`) compared between Rust and WGSL: each WGSL
//! constant's value as naga evaluates it, each entry point's workgroup size as naga reads it,
//! and, for the values a file could repeat as a literal, no such literal where the constant is
//! meant. Shared by engine/tests/shared_constants.rs and plugin_gi/tests/shared_constants.rs.
#![allow(dead_code)] // Each test uses part of it.

use std::collections::BTreeMap;
use std::fmt::Write;

use engine::shared_constants::{SharedConstant, Workgroup};

fn parse(file: &str, source: &str) -> naga::Module {
    naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{file}: {}", e.emit_to_string(source)))
}

/// An integer WGSL constant: its value, and the suffix a literal of its type takes (`u`, `i`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Value {
    pub value: i64,
    pub suffix: Option<char>,
}

/// Every integer `const` of an assembled WGSL source (includes expanded), by name.
pub fn wgsl_constants(file: &str, source: &str) -> BTreeMap<String, Value> {
    let module = parse(file, source);
    let mut constants = BTreeMap::new();
    for (_, c) in module.constants.iter() {
        let Some(name) = &c.name else { continue };
        let naga::Expression::Literal(literal) = module.global_expressions[c.init] else { continue };
        let value = match literal {
            naga::Literal::U32(v) => Value { value: v.into(), suffix: Some('u') },
            naga::Literal::I32(v) => Value { value: v.into(), suffix: Some('i') },
            naga::Literal::U64(v) => Value { value: v as i64, suffix: None },
            naga::Literal::I64(v) | naga::Literal::AbstractInt(v) => Value { value: v, suffix: None },
            _ => continue,
        };
        constants.insert(name.clone(), value);
    }
    constants
}

/// Every compute entry point's workgroup size, by name.
pub fn workgroup_sizes(file: &str, source: &str) -> BTreeMap<String, [u32; 3]> {
    let module = parse(file, source);
    module
        .entry_points
        .iter()
        .filter(|e| e.stage == naga::ShaderStage::Compute)
        .map(|e| (e.name.clone(), e.workgroup_size))
        .collect()
}

/// The size in bytes of the global variable `name` of an assembled WGSL source.
pub fn global_size(file: &str, source: &str, name: &str) -> usize {
    let module = parse(file, source);
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap_or_else(|e| panic!("{file}: {e}"));
    let (_, var) = module
        .global_variables
        .iter()
        .find(|(_, v)| v.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("{file} has no global {name}"));
    layouter[var.ty].size as usize
}

/// Checks that each of `constants` has its Rust value in every assembled file of `files`
/// (name, source) that has a constant of its name, that at least one has it, and that the
/// file it names declares it (`raw`: every file and include before assembly). The error names
/// each constant that differs, the file, and both values. Returns how many comparisons held.
pub fn check_constants(
    files: &[(&str, String)],
    raw: &[(&str, &str)],
    constants: &[SharedConstant],
) -> Result<usize, String> {
    let values: Vec<(&str, BTreeMap<String, Value>)> =
        files.iter().map(|(file, source)| (*file, wgsl_constants(file, source))).collect();
    let mut errors = String::new();
    let mut compared = 0;
    for c in constants {
        let declared = raw.iter().find(|(f, _)| *f == c.file).is_some_and(|(_, s)| declares(s, c.wgsl));
        if !declared {
            writeln!(errors, "{} is not declared in {} (listed for Rust {})", c.wgsl, c.file, c.rust).unwrap();
        }
        let mut seen = false;
        // The files that assembled each wrong value.
        let mut wrong: BTreeMap<i64, Vec<&str>> = BTreeMap::new();
        for (file, found) in &values {
            let Some(v) = found.get(c.wgsl) else { continue };
            seen = true;
            if v.value == c.value {
                compared += 1;
            } else {
                wrong.entry(v.value).or_default().push(file);
            }
        }
        for (value, modules) in wrong {
            let assembled = match modules[..] {
                [only] if only == c.file => String::new(),
                [only] => format!(", as {only} assembles it"),
                [first, ..] => format!(", as {first} and {} more assemble it", modules.len() - 1),
                [] => unreachable!("a value comes from a file"),
            };
            writeln!(errors, "{} ({}{assembled}): WGSL {value}, Rust {} {}", c.wgsl, c.file, c.rust, c.value).unwrap();
        }
        if !seen {
            writeln!(errors, "{} ({}): no WGSL module has it as an integer constant", c.wgsl, c.file).unwrap();
        }
    }
    if errors.is_empty() {
        Ok(compared)
    } else {
        Err(errors)
    }
}

/// Checks that each of `workgroups` names a compute entry point of its file in `files`
/// (assembled) with the size its Rust dispatch counts with.
pub fn check_workgroups(files: &[(&str, String)], workgroups: &[Workgroup]) -> Result<(), String> {
    let mut errors = String::new();
    for w in workgroups {
        let Some((file, source)) = files.iter().find(|(f, _)| *f == w.file) else {
            writeln!(errors, "{}: no such file", w.file).unwrap();
            continue;
        };
        match workgroup_sizes(file, source).get(w.entry) {
            None => writeln!(errors, "{file}: no compute entry point {}", w.entry).unwrap(),
            Some(size) if *size != w.size => writeln!(
                errors,
                "{file} {}: WGSL workgroup size {size:?}, Rust dispatches count with {} = {:?}",
                w.entry, w.rust, w.size
            )
            .unwrap(),
            Some(_) => {}
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

/// Where a value may not be written as a literal.
#[derive(Clone, Copy, Debug)]
pub enum Within {
    /// Anywhere in the files, but the constant's own declaration.
    Everywhere,
    /// In the functions whose bodies name this word (a field or a function).
    FunctionsNaming(&'static str),
}

/// A constant whose value no file may write as a literal `within` a place: a literal of its
/// value, bare or with its type's suffix, stands for it there.
#[derive(Clone, Copy, Debug)]
pub struct Guard {
    pub constant: &'static str,
    pub within: Within,
}

/// Checks `raw` (each file and include before assembly) for literals that repeat a guarded
/// constant, whose value (the Rust one) and type's suffix are `values`' (by constant name).
/// The error names the file, the line, the literal and the constant.
pub fn check_literals(raw: &[(&str, &str)], values: &BTreeMap<String, Value>, guards: &[Guard]) -> Result<(), String> {
    let mut errors = String::new();
    for g in guards {
        let Some(value) = values.get(g.constant) else {
            writeln!(errors, "guarded {} is no WGSL integer constant", g.constant).unwrap();
            continue;
        };
        for (file, source) in raw {
            let code = without_comments(source);
            let ranges: Vec<std::ops::Range<usize>> = match g.within {
                Within::Everywhere => std::iter::once(0..code.len()).collect(),
                Within::FunctionsNaming(word) => {
                    function_bodies(&code).into_iter().filter(|r| has_word(&code[r.clone()], word)).collect()
                }
            };
            for range in ranges {
                for (at, literal) in int_literals(&code[range.clone()]) {
                    let at = range.start + at;
                    let line = &code[code[..at].rfind('\n').map_or(0, |i| i + 1)..];
                    let line = &line[..line.find('\n').unwrap_or(line.len())];
                    let declaration = line.trim_start().starts_with(&format!("const {}", g.constant));
                    if literal.value == value.value
                        && (literal.suffix.is_none() || literal.suffix == value.suffix)
                        && !declaration
                    {
                        let number = code[..at].matches('\n').count() + 1;
                        writeln!(
                            errors,
                            "{file}:{number}: {} where {} is meant: `{}`",
                            literal.text,
                            g.constant,
                            line.trim()
                        )
                        .unwrap();
                    }
                }
            }
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

/// Whether WGSL `source` declares a `const` called `name`.
fn declares(source: &str, name: &str) -> bool {
    without_comments(source).lines().any(|l| {
        l.trim_start().strip_prefix("const ").is_some_and(|rest| {
            rest.trim_start().strip_prefix(name).is_some_and(|after| after.trim_start().starts_with([':', '=']))
        })
    })
}

/// `source` with each `//` comment blanked out (so offsets and lines stay where they were).
fn without_comments(source: &str) -> String {
    source
        .lines()
        .map(|l| match l.find("//") {
            Some(i) => format!("{}{}", &l[..i], " ".repeat(l.len() - i)),
            None => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn is_word_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

fn has_word(text: &str, word: &str) -> bool {
    text.match_indices(word).any(|(i, _)| {
        let before = text[..i].chars().next_back().is_none_or(|c| !is_word_char(c));
        let after = text[i + word.len()..].chars().next().is_none_or(|c| !is_word_char(c));
        before && after
    })
}

/// The byte ranges of the bodies (braces included) of the `fn`s of comment-free WGSL.
fn function_bodies(code: &str) -> Vec<std::ops::Range<usize>> {
    let mut bodies = Vec::new();
    let mut from = 0;
    while let Some(i) = code[from..].find("fn ") {
        let start = from + i;
        from = start + 3;
        if code[..start].chars().next_back().is_some_and(is_word_char) {
            continue;
        }
        let Some(open) = code[start..].find('{').map(|o| start + o) else { break };
        let mut depth = 0;
        for (j, c) in code[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        bodies.push(open..open + j + 1);
                        from = open + j + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
    }
    bodies
}

/// An integer literal as written.
pub struct Literal {
    pub text: String,
    pub value: i64,
    /// `u` or `i`, or none (an abstract integer).
    pub suffix: Option<char>,
}

/// The integer literals of comment-free WGSL, with their offsets: decimal or hexadecimal,
/// with or without a suffix. Floats (`12.0`, `1e-12`, `2f`) are not among them.
pub fn int_literals(code: &str) -> Vec<(usize, Literal)> {
    let bytes = code.as_bytes();
    let mut literals = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i] as char;
        if !c.is_ascii_digit() || (i > 0 && is_word_char(bytes[i - 1] as char)) {
            i += 1;
            continue;
        }
        // The whole number token: word characters and points, and an exponent's sign.
        let start = i;
        let hex = code[i..].starts_with("0x") || code[i..].starts_with("0X");
        while i < bytes.len() {
            let d = bytes[i] as char;
            let exponent = if hex { "pP" } else { "eE" };
            let sign = (d == '+' || d == '-') && exponent.contains(bytes[i - 1] as char);
            if !(is_word_char(d) || d == '.' || sign) {
                break;
            }
            i += 1;
        }
        let text = &code[start..i];
        let (digits, suffix) = match text.chars().last() {
            Some(s @ ('u' | 'i')) => (&text[..text.len() - 1], Some(s)),
            _ => (text, None),
        };
        let value = if hex {
            i64::from_str_radix(&digits[2..], 16).ok()
        } else if digits.chars().all(|d| d.is_ascii_digit()) {
            digits.parse().ok()
        } else {
            None
        };
        if let Some(value) = value {
            literals.push((start, Literal { text: text.to_string(), value, suffix }));
        }
    }
    literals
}

//! What one source file says about modules: the modules it declares, the items it defines, its
//! `use` items and the paths in its code. Test code (`#[cfg(test)]` items) is left out: tests may
//! use anything.

use std::collections::{BTreeMap, BTreeSet};

use super::tokens::{tokenize, Kind, Token};

/// Names of inline modules (`mod names { … }`) around a place in a file, outermost first.
pub type Scope = Vec<String>;

#[derive(Debug, Default)]
pub struct Syntax {
    /// `mod NAME;`: a module in a file of its own.
    pub mods: Vec<ModDecl>,
    /// One entry per name a `use` brings in (a group `{a, b}` gives two).
    pub uses: Vec<UseLeaf>,
    /// Paths of two or more segments in code (`crate::a::f`, `super::X`, `child::g`).
    pub paths: Vec<CodePath>,
    /// Names of the items the file defines at module level (functions, types, constants,
    /// modules, macros).
    pub defined: BTreeSet<String>,
    /// Each name that leads a path or stands alone in code, with the first line it does.
    pub names_in_code: BTreeMap<String, usize>,
}

#[derive(Debug)]
pub struct ModDecl {
    pub scope: Scope,
    pub name: String,
    pub line: usize,
}

#[derive(Debug)]
pub struct UseLeaf {
    pub scope: Scope,
    /// The path as written (for `a::{self}`, `a`). A leading `::` stays as a `::` segment.
    pub segments: Vec<String>,
    /// The name it binds (None for `*` and `as _`).
    pub local: Option<String>,
    pub glob: bool,
    /// `pub use` or `pub(…) use`: a re-export.
    pub public: bool,
    pub line: usize,
}

#[derive(Debug)]
pub struct CodePath {
    pub scope: Scope,
    pub segments: Vec<String>,
    pub line: usize,
}

/// Keywords that may follow an item keyword without being the item's name (`const fn f`).
const NOT_NAMES: &[&str] = &["fn", "unsafe", "async", "extern", "mut"];

impl Syntax {
    pub fn parse(source: &str) -> Syntax {
        let tokens = without_test_items(tokenize(source));
        let mut syntax = Syntax::default();
        // Inline modules open around here, each with the brace depth inside it.
        let mut scopes: Vec<(String, usize)> = Vec::new();
        let mut depth = 0;
        let mut at = 0;
        while at < tokens.len() {
            let token = &tokens[at];
            let scope = || scopes.iter().map(|(name, _)| name.clone()).collect::<Scope>();
            match &token.kind {
                Kind::Punct('{') => depth += 1,
                Kind::Punct('}') => {
                    depth -= 1;
                    if scopes.last().is_some_and(|(_, inside)| depth < *inside) {
                        scopes.pop();
                    }
                }
                Kind::Ident(word) if word == "use" && !tokens.get(at + 1).is_some_and(|t| t.is_punct('<')) => {
                    let public = is_public(&tokens, at);
                    at = parse_use(&tokens, at + 1, &scope(), public, &mut syntax.uses);
                    continue;
                }
                Kind::Ident(word) if word == "mod" => {
                    if let Some(name) = tokens.get(at + 1).and_then(Token::ident) {
                        syntax.defined.insert(name.to_string());
                        match tokens.get(at + 2) {
                            Some(t) if t.is_punct(';') => {
                                syntax.mods.push(ModDecl { scope: scope(), name: name.to_string(), line: token.line })
                            }
                            Some(t) if t.is_punct('{') => {
                                scopes.push((name.to_string(), depth + 1));
                                depth += 1;
                                at += 3;
                                continue;
                            }
                            _ => {}
                        }
                    }
                    at += 2; // the name declares a module; it is not a use of one
                    continue;
                }
                // Only the module's own items: not a function's locals nor an impl's methods.
                Kind::Ident(word) if is_item_keyword(word) && depth == scopes.last().map_or(0, |(_, d)| *d) => {
                    let name = tokens.get(at + 1).and_then(Token::ident).filter(|n| !NOT_NAMES.contains(n));
                    if let Some(name) = name {
                        syntax.defined.insert(name.to_string());
                        at += 2;
                        continue;
                    }
                }
                Kind::Ident(word) if word == "macro_rules" && tokens.get(at + 1).is_some_and(|t| t.is_punct('!')) => {
                    syntax.defined.extend(tokens.get(at + 2).and_then(Token::ident).map(String::from));
                }
                Kind::Ident(word) if !follows_path_or_field(&tokens, at) => {
                    syntax.names_in_code.entry(word.clone()).or_insert(token.line);
                    let segments = path_from(&tokens, at);
                    if segments.len() >= 2 {
                        at += 2 * segments.len() - 1;
                        syntax.paths.push(CodePath { scope: scope(), segments, line: token.line });
                        continue;
                    }
                }
                _ => {}
            }
            at += 1;
        }
        syntax
    }
}

fn is_item_keyword(word: &str) -> bool {
    matches!(word, "fn" | "struct" | "enum" | "union" | "trait" | "type" | "const" | "static")
}

/// Whether the identifier at `at` continues a path or names a field or method (`a::b`, `x.b`).
fn follows_path_or_field(tokens: &[Token], at: usize) -> bool {
    at > 0 && (tokens[at - 1].kind == Kind::PathSep || tokens[at - 1].is_punct('.'))
}

/// The segments of `a::b::c` from `at`: identifiers joined by `::` (a turbofish ends it).
fn path_from(tokens: &[Token], at: usize) -> Vec<String> {
    let mut segments = Vec::new();
    let mut at = at;
    while let Some(name) = tokens.get(at).and_then(Token::ident) {
        segments.push(name.to_string());
        let joined = tokens.get(at + 1).is_some_and(|t| t.kind == Kind::PathSep);
        if !joined || tokens.get(at + 2).and_then(Token::ident).is_none() {
            break;
        }
        at += 2;
    }
    segments
}

/// Whether the `use` at `at` is led by `pub` or `pub(…)`.
fn is_public(tokens: &[Token], at: usize) -> bool {
    let before = |n: usize| at.checked_sub(n).map(|i| &tokens[i]);
    if before(1).is_some_and(|t| t.is_ident("pub")) {
        return true;
    }
    if !before(1).is_some_and(|t| t.is_punct(')')) {
        return false;
    }
    // `pub(crate)`, `pub(super)`, `pub(in path)`: back to the `(`.
    let open = (0..at - 1).rev().find(|&i| tokens[i].is_punct('('));
    open.is_some_and(|i| i > 0 && tokens[i - 1].is_ident("pub"))
}

/// Reads the use tree from `at` to its `;` into `out`; returns where the next item starts.
fn parse_use(tokens: &[Token], at: usize, scope: &Scope, public: bool, out: &mut Vec<UseLeaf>) -> usize {
    let mut at = at;
    let mut leaf = |segments: Vec<String>, local: Option<String>, glob: bool, line: usize| {
        out.push(UseLeaf { scope: scope.clone(), segments, local, glob, public, line });
    };
    tree(tokens, &mut at, Vec::new(), &mut leaf);
    while at < tokens.len() && !tokens[at].is_punct(';') {
        at += 1;
    }
    at + 1
}

/// One use tree (`a::b`, `a::b as c`, `a::*`, `a::{…}`) under `prefix`.
fn tree(
    tokens: &[Token],
    at: &mut usize,
    mut prefix: Vec<String>,
    leaf: &mut impl FnMut(Vec<String>, Option<String>, bool, usize),
) {
    while let Some(token) = tokens.get(*at) {
        *at += 1;
        match &token.kind {
            Kind::PathSep if prefix.is_empty() => prefix.push("::".into()),
            Kind::PathSep => {}
            Kind::Punct('*') => return leaf(prefix, None, true, token.line),
            Kind::Punct('{') => {
                while tokens.get(*at).is_some_and(|t| !t.is_punct('}')) {
                    tree(tokens, at, prefix.clone(), leaf);
                    if tokens.get(*at).is_some_and(|t| t.is_punct(',')) {
                        *at += 1;
                    }
                }
                *at += 1;
                return;
            }
            Kind::Ident(name) => {
                if tokens.get(*at).is_some_and(|t| t.kind == Kind::PathSep) {
                    prefix.push(name.clone());
                    continue;
                }
                // `a::{self}` binds `a`.
                let (segments, mut local) = if name == "self" && !prefix.is_empty() {
                    let local = prefix.last().cloned();
                    (prefix, local)
                } else {
                    prefix.push(name.clone());
                    (prefix, Some(name.clone()))
                };
                if tokens.get(*at).is_some_and(|t| t.is_ident("as")) {
                    local = tokens.get(*at + 1).and_then(Token::ident).filter(|n| *n != "_").map(String::from);
                    *at += 2;
                }
                return leaf(segments, local, false, token.line);
            }
            _ => return,
        }
    }
}

/// The tokens without the items under `#[cfg(test)]`.
fn without_test_items(tokens: Vec<Token>) -> Vec<Token> {
    let mut out = Vec::with_capacity(tokens.len());
    let mut at = 0;
    while at < tokens.len() {
        if is_cfg_test(&tokens[at..]) {
            at = item_end(&tokens, at);
        } else {
            out.push(tokens[at].clone());
            at += 1;
        }
    }
    out
}

fn is_cfg_test(tokens: &[Token]) -> bool {
    let expected = ["#", "[", "cfg", "(", "test", ")", "]"];
    tokens.len() >= expected.len()
        && tokens.iter().zip(expected).all(|(t, e)| match &t.kind {
            Kind::Ident(name) => name == e,
            Kind::Punct(c) => e.len() == 1 && e.starts_with(*c),
            _ => false,
        })
}

/// Where the item that starts at `at` (attributes first) ends: after its `;` or the brace
/// that closes its body, whichever comes first outside brackets.
fn item_end(tokens: &[Token], at: usize) -> usize {
    let mut depth = 0i32;
    let mut at = at;
    // The attributes, each a bracketed group after `#`.
    while tokens.get(at).is_some_and(|t| t.is_punct('#')) {
        at += 1;
        while let Some(token) = tokens.get(at) {
            at += 1;
            match token.kind {
                Kind::Punct('[') => depth += 1,
                Kind::Punct(']') => depth -= 1,
                _ => {}
            }
            if depth == 0 {
                break;
            }
        }
    }
    while let Some(token) = tokens.get(at) {
        at += 1;
        match token.kind {
            Kind::Punct('{' | '(' | '[') => depth += 1,
            Kind::Punct(')' | ']') => depth -= 1,
            Kind::Punct('}') => {
                depth -= 1;
                if depth == 0 {
                    return at;
                }
            }
            Kind::Punct(';') if depth == 0 => return at,
            _ => {}
        }
    }
    at
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leaves(source: &str) -> Vec<(String, Option<String>, bool, bool)> {
        let syntax = Syntax::parse(source);
        syntax.uses.into_iter().map(|u| (u.segments.join("/"), u.local, u.glob, u.public)).collect()
    }

    #[test]
    fn use_trees_are_read_leaf_by_leaf() {
        let source = "use crate::{a, b::{self, C as D}, e::*};\npub(crate) use ::std::f;\nuse g as _;";
        let some = |s: &str| Some(s.to_string());
        assert_eq!(
            leaves(source),
            [
                ("crate/a".into(), some("a"), false, false),
                ("crate/b".into(), some("b"), false, false),
                ("crate/b/C".into(), some("D"), false, false),
                ("crate/e".into(), None, true, false),
                ("::/std/f".into(), some("f"), false, true),
                ("g".into(), None, false, false),
            ]
        );
    }

    #[test]
    fn test_items_are_left_out() {
        let source = "#[cfg(test)]\nmod tests;\n#[cfg(test)]\n#[allow(x)]\nmod more { use crate::a::B; }\n\
                      #[cfg(test)]\nuse crate::c::D;\nfn f() { crate::e::g() }";
        let syntax = Syntax::parse(source);
        assert!(syntax.mods.is_empty() && syntax.uses.is_empty());
        assert_eq!(syntax.paths.len(), 1);
        assert_eq!(syntax.paths[0].segments, ["crate", "e", "g"]);
        assert_eq!(syntax.paths[0].line, 8);
    }

    #[test]
    fn inline_modules_scope_what_is_inside_them() {
        let source = "mod names { pub const A: u8 = super::B; mod deeper; }\nconst B: u8 = 1;\nfn f() { x.y::z(); }";
        let syntax = Syntax::parse(source);
        assert_eq!(syntax.paths.len(), 1);
        assert_eq!(syntax.paths[0].scope, ["names"]);
        assert_eq!(syntax.mods[0].scope, ["names"]);
        assert!(syntax.defined.contains("names") && syntax.defined.contains("A") && syntax.defined.contains("B"));
    }
}

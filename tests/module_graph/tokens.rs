//! Rust source as tokens, just enough to read its paths: comments, strings, characters and
//! numbers are dropped or kept as one opaque token, so that a `crate::x` inside any of them is
//! never taken for a path.

/// One token and the line (1-based) it starts on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Token {
    pub kind: Kind,
    pub line: usize,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Kind {
    /// An identifier or a keyword (a raw identifier without its `r#`).
    Ident(String),
    /// `::`
    PathSep,
    /// Any other punctuation, one character at a time.
    Punct(char),
    /// A string, character or number literal, or a lifetime.
    Literal,
}

impl Token {
    pub fn ident(&self) -> Option<&str> {
        match &self.kind {
            Kind::Ident(name) => Some(name),
            _ => None,
        }
    }

    pub fn is_ident(&self, name: &str) -> bool {
        self.ident() == Some(name)
    }

    pub fn is_punct(&self, c: char) -> bool {
        self.kind == Kind::Punct(c)
    }
}

/// The tokens of `source`, comments left out.
pub fn tokenize(source: &str) -> Vec<Token> {
    Lexer { chars: source.chars().collect(), at: 0, line: 1 }.run()
}

struct Lexer {
    chars: Vec<char>,
    at: usize,
    line: usize,
}

impl Lexer {
    fn peek(&self, ahead: usize) -> Option<char> {
        self.chars.get(self.at + ahead).copied()
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek(0)?;
        self.at += 1;
        if c == '\n' {
            self.line += 1;
        }
        Some(c)
    }

    fn run(mut self) -> Vec<Token> {
        let mut out = Vec::new();
        while let Some(c) = self.peek(0) {
            let line = self.line;
            let kind = match c {
                c if c.is_whitespace() => {
                    self.bump();
                    continue;
                }
                '/' if self.peek(1) == Some('/') => {
                    self.line_comment();
                    continue;
                }
                '/' if self.peek(1) == Some('*') => {
                    self.block_comment();
                    continue;
                }
                '"' => {
                    self.quoted('"');
                    Kind::Literal
                }
                '\'' => self.char_or_lifetime(),
                ':' if self.peek(1) == Some(':') => {
                    self.at += 2;
                    Kind::PathSep
                }
                c if c.is_ascii_digit() => {
                    self.bump_while(|c| c.is_alphanumeric() || c == '_');
                    Kind::Literal
                }
                c if c == '_' || c.is_alphabetic() => self.word(),
                c => {
                    self.bump();
                    Kind::Punct(c)
                }
            };
            out.push(Token { kind, line });
        }
        out
    }

    fn bump_while(&mut self, keep: impl Fn(char) -> bool) {
        while self.peek(0).is_some_and(&keep) {
            self.bump();
        }
    }

    fn line_comment(&mut self) {
        self.bump_while(|c| c != '\n');
    }

    /// Block comments nest.
    fn block_comment(&mut self) {
        let mut depth = 0;
        while let Some(c) = self.bump() {
            if c == '/' && self.peek(0) == Some('*') {
                self.bump();
                depth += 1;
            } else if c == '*' && self.peek(0) == Some('/') {
                self.bump();
                depth -= 1;
                if depth == 0 {
                    return;
                }
            }
        }
    }

    /// From an opening quote to its closing one, escapes skipped.
    fn quoted(&mut self, quote: char) {
        self.bump();
        while let Some(c) = self.bump() {
            if c == '\\' {
                self.bump();
            } else if c == quote {
                return;
            }
        }
    }

    /// `r"…"`, `r#"…"#` and so on: no escapes, ended by a quote and as many `#`.
    fn raw_string(&mut self) {
        let mut hashes = 0;
        while self.peek(0) == Some('#') {
            self.bump();
            hashes += 1;
        }
        self.bump(); // the opening quote
        while let Some(c) = self.bump() {
            if c == '"' && (0..hashes).all(|i| self.peek(i) == Some('#')) {
                self.at += hashes;
                return;
            }
        }
    }

    /// `'a'`, `'\n'` and `'\u{1F600}'` are characters; `'a` (no closing quote) a lifetime.
    fn char_or_lifetime(&mut self) -> Kind {
        if self.peek(1) == Some('\\') || self.peek(2) == Some('\'') {
            self.quoted('\'');
        } else {
            self.bump();
            self.bump_while(|c| c == '_' || c.is_alphanumeric());
        }
        Kind::Literal
    }

    /// An identifier, or a literal led by letters (`b"…"`, `r#"…"#`, `b'x'`), or a raw
    /// identifier (`r#type`).
    fn word(&mut self) -> Kind {
        let start = self.at;
        self.bump_while(|c| c == '_' || c.is_alphanumeric());
        let word: String = self.chars[start..self.at].iter().collect();
        let raw = matches!(word.as_str(), "r" | "br" | "cr");
        match self.peek(0) {
            Some('"') if raw => self.raw_string(),
            Some('#') if raw && matches!(self.peek(1), Some('"' | '#')) => self.raw_string(),
            Some('#') if word == "r" => {
                self.bump();
                let start = self.at;
                self.bump_while(|c| c == '_' || c.is_alphanumeric());
                return Kind::Ident(self.chars[start..self.at].iter().collect());
            }
            Some('"') if matches!(word.as_str(), "b" | "c") => self.quoted('"'),
            Some('\'') if word == "b" => self.quoted('\''),
            _ => return Kind::Ident(word),
        }
        Kind::Literal
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn idents(source: &str) -> Vec<String> {
        tokenize(source).into_iter().filter_map(|t| t.ident().map(String::from)).collect()
    }

    #[test]
    fn comments_strings_and_characters_hide_their_contents() {
        let source = r###"
            // crate::a
            /* crate::b /* nested */ crate::c */
            let s = "crate::d \" crate::e";
            let r = r##"crate::f "# crate::g"##;
            let c = '"'; let q = '\''; let l: &'static str = b"x";
            fn r#type() {}
        "###;
        assert_eq!(idents(source), ["let", "s", "let", "r", "let", "c", "let", "q", "let", "l", "str", "fn", "type"]);
    }

    #[test]
    fn lines_are_counted() {
        let tokens = tokenize("a\n/* \n */ b::c\n\"\n\" d");
        let lines: Vec<usize> = tokens.iter().map(|t| t.line).collect();
        assert_eq!(lines, [1, 3, 3, 3, 4, 5]);
        assert_eq!(tokens[2].kind, Kind::PathSep);
    }
}

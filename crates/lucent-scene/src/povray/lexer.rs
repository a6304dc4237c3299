//! POV-Ray's tokens: numbers, strings, words (keywords and identifiers alike), directives
//! (`#declare`) and symbols, each with its place in the file.

use crate::error::LoadError;
use std::fmt;
use std::path::Path;
use std::rc::Rc;

pub use crate::mitsuba::xml::Loc;

/// What a token is.
#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    /// A number literal.
    Number(f64),
    /// A string literal, escapes resolved.
    Str(Rc<str>),
    /// A keyword or identifier.
    Word(Rc<str>),
    /// `#` and the word after it (`#declare` is `Directive("declare")`).
    Directive(Rc<str>),
    /// Punctuation and operators: `{ } ( ) [ ] < > , ; = + - * / ? : ! & | . <= >= !=`.
    Symbol(&'static str),
}

impl fmt::Display for Tok {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Tok::Number(v) => write!(f, "the number {v}"),
            Tok::Str(s) => write!(f, "the string \"{s}\""),
            Tok::Word(w) => write!(f, "`{w}`"),
            Tok::Directive(d) => write!(f, "`#{d}`"),
            Tok::Symbol(s) => write!(f, "`{s}`"),
        }
    }
}

/// A token and its place.
#[derive(Clone, Debug)]
pub struct Token {
    /// What it is.
    pub tok: Tok,
    /// Where it starts.
    pub loc: Loc,
}

impl Token {
    /// Whether it is the word `w`.
    pub fn is_word(&self, w: &str) -> bool {
        matches!(&self.tok, Tok::Word(x) if &**x == w)
    }

    /// Whether it is the symbol `s`.
    pub fn is_symbol(&self, s: &str) -> bool {
        matches!(&self.tok, Tok::Symbol(x) if *x == s)
    }
}

const SYMBOLS: [&str; 24] = [
    "<=", ">=", "!=", "{", "}", "(", ")", "[", "]", "<", ">", ",", ";", "=", "+", "-", "*", "/",
    "?", ":", "!", "&", "|", ".",
];

/// The tokens of `text`, read from `file`: comments (`//` to the line's end, `/* */` nested)
/// dropped. An unclosed string or comment, or a character POV-Ray does not know, is an error.
pub fn tokens(file: &Rc<Path>, text: &str) -> Result<Vec<Token>, LoadError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line, mut column) = (0usize, 1usize, 1usize);
    let at = |line, column| Loc {
        file: file.clone(),
        line,
        column,
    };
    // Moves past `n` characters, keeping the line and column.
    let advance = |i: &mut usize, line: &mut usize, column: &mut usize, n: usize| {
        for _ in 0..n {
            if chars.get(*i) == Some(&'\n') {
                *line += 1;
                *column = 1;
            } else {
                *column += 1;
            }
            *i += 1;
        }
    };
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        let loc = at(line, column);
        if c.is_whitespace() || c == '\u{feff}' || c == '\u{1a}' {
            advance(&mut i, &mut line, &mut column, 1);
        } else if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                advance(&mut i, &mut line, &mut column, 1);
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            loop {
                if i >= chars.len() {
                    return Err(loc.error("a comment `/*` is never closed by `*/`"));
                }
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    advance(&mut i, &mut line, &mut column, 2);
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    advance(&mut i, &mut line, &mut column, 2);
                    if depth == 0 {
                        break;
                    }
                } else {
                    advance(&mut i, &mut line, &mut column, 1);
                }
            }
        } else if c == '"' {
            advance(&mut i, &mut line, &mut column, 1);
            let mut s = String::new();
            loop {
                match chars.get(i) {
                    None | Some('\n') => return Err(loc.error("a string is never closed by `\"`")),
                    Some('"') => break,
                    Some('\\') => {
                        let escaped = match chars.get(i + 1) {
                            Some('n') => '\n',
                            Some('t') => '\t',
                            Some(&e @ ('"' | '\\')) => e,
                            // POV-Ray keeps other backslashes (Windows paths).
                            _ => {
                                s.push('\\');
                                advance(&mut i, &mut line, &mut column, 1);
                                continue;
                            }
                        };
                        s.push(escaped);
                        advance(&mut i, &mut line, &mut column, 2);
                    }
                    Some(&ch) => {
                        s.push(ch);
                        advance(&mut i, &mut line, &mut column, 1);
                    }
                }
            }
            advance(&mut i, &mut line, &mut column, 1);
            out.push(Token {
                tok: Tok::Str(s.into()),
                loc,
            });
        } else if c.is_ascii_digit() || (c == '.' && next.is_some_and(|n| n.is_ascii_digit())) {
            let start = i;
            let mut j = i;
            while j < chars.len() && (chars[j].is_ascii_digit() || chars[j] == '.') {
                j += 1;
            }
            if j < chars.len() && (chars[j] == 'e' || chars[j] == 'E') {
                let mut k = j + 1;
                if k < chars.len() && (chars[k] == '+' || chars[k] == '-') {
                    k += 1;
                }
                if k < chars.len() && chars[k].is_ascii_digit() {
                    j = k;
                    while j < chars.len() && chars[j].is_ascii_digit() {
                        j += 1;
                    }
                }
            }
            let text: String = chars[start..j].iter().collect();
            let value: f64 = text
                .parse()
                .map_err(|_| loc.error(format!("`{text}` is not a number")))?;
            advance(&mut i, &mut line, &mut column, j - start);
            out.push(Token {
                tok: Tok::Number(value),
                loc,
            });
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            let mut j = i;
            while j < chars.len() && (chars[j].is_alphanumeric() || chars[j] == '_') {
                j += 1;
            }
            let word: String = chars[start..j].iter().collect();
            advance(&mut i, &mut line, &mut column, j - start);
            out.push(Token {
                tok: Tok::Word(word.into()),
                loc,
            });
        } else if c == '#' {
            advance(&mut i, &mut line, &mut column, 1);
            while i < chars.len() && (chars[i] == ' ' || chars[i] == '\t') {
                advance(&mut i, &mut line, &mut column, 1);
            }
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                advance(&mut i, &mut line, &mut column, 1);
            }
            if start == i {
                return Err(loc.error("`#` is not followed by a directive's name"));
            }
            let word: String = chars[start..i].iter().collect();
            out.push(Token {
                tok: Tok::Directive(word.into()),
                loc,
            });
        } else {
            let two: String = chars[i..(i + 2).min(chars.len())].iter().collect();
            let symbol = SYMBOLS
                .iter()
                .find(|s| two.starts_with(**s))
                .ok_or_else(|| loc.error(format!("`{c}` is not part of POV-Ray's language")))?;
            advance(&mut i, &mut line, &mut column, symbol.chars().count());
            out.push(Token {
                tok: Tok::Symbol(symbol),
                loc,
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(text: &str) -> Vec<Tok> {
        let file: Rc<Path> = Rc::from(Path::new("t.pov"));
        tokens(&file, text)
            .unwrap()
            .into_iter()
            .map(|t| t.tok)
            .collect()
    }

    #[test]
    fn numbers_words_symbols_and_directives() {
        let t = kinds("#declare R = 1.5e1; // gone\nsphere{<0,.5,-2>, R} /* a /* nested */ one */");
        assert_eq!(t[0], Tok::Directive("declare".into()));
        assert_eq!(t[1], Tok::Word("R".into()));
        assert_eq!(t[3], Tok::Number(15.0));
        assert!(t.contains(&Tok::Number(0.5)));
        assert_eq!(t.last(), Some(&Tok::Symbol("}")));
        assert_eq!(
            kinds("a<=b"),
            [
                Tok::Word("a".into()),
                Tok::Symbol("<="),
                Tok::Word("b".into())
            ]
        );
    }

    #[test]
    fn places_and_errors() {
        let file: Rc<Path> = Rc::from(Path::new("t.pov"));
        let t = tokens(&file, "a\n  \"x\\\"y\" 3").unwrap();
        assert_eq!((t[1].loc.line, t[1].loc.column), (2, 3));
        assert_eq!(t[1].tok, Tok::Str("x\"y".into()));
        let e = tokens(&file, "a\n /* open").unwrap_err().to_string();
        assert!(e.starts_with("t.pov:2:2: a comment"), "{e}");
        let e = tokens(&file, "sphere { @ }").unwrap_err().to_string();
        assert!(e.starts_with("t.pov:1:10:"), "{e}");
    }
}

//! Tokens of the formula language, read one at a time so that errors come out in the
//! order of the text.

use std::ops::Range;

use crate::error::Error;

/// What a token is.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// A decimal literal (its text is the span).
    Number,
    /// A name: `[A-Za-z_][A-Za-z0-9_]*`.
    Ident,
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    LParen,
    RParen,
    Comma,
    /// The end of the input (an empty span at its length).
    End,
}

/// A token and its byte span.
#[derive(Clone, Debug)]
pub(crate) struct Token {
    pub kind: Kind,
    pub span: Range<usize>,
}

/// Splits a formula into [`Token`]s.
pub(crate) struct Lexer<'t> {
    text: &'t str,
    pos: usize,
}

fn is_ident_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_'
}

fn is_ident_continue(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

pub(crate) fn syntax(message: String, span: Range<usize>, hint: Option<String>) -> Error {
    Error::Syntax {
        message,
        span,
        hint,
    }
}

impl<'t> Lexer<'t> {
    pub fn new(text: &'t str) -> Self {
        Self { text, pos: 0 }
    }

    fn byte(&self, i: usize) -> Option<u8> {
        self.text.as_bytes().get(i).copied()
    }

    fn skip_while(&mut self, pred: impl Fn(u8) -> bool) {
        while self.byte(self.pos).is_some_and(&pred) {
            self.pos += 1;
        }
    }

    /// The next token, or an error for a character or number that is not valid.
    pub fn next_token(&mut self) -> Result<Token, Error> {
        // Skip whitespace (Unicode whitespace included).
        while let Some(c) = self.text[self.pos..].chars().next() {
            if !c.is_whitespace() {
                break;
            }
            self.pos += c.len_utf8();
        }
        let start = self.pos;
        let Some(c) = self.text[start..].chars().next() else {
            return Ok(Token {
                kind: Kind::End,
                span: start..start,
            });
        };
        let kind = match c {
            '+' => Kind::Plus,
            '-' => Kind::Minus,
            '*' => Kind::Star,
            '/' => Kind::Slash,
            '^' => Kind::Caret,
            '(' => Kind::LParen,
            ')' => Kind::RParen,
            ',' => Kind::Comma,
            '0'..='9' | '.' => return self.number(),
            c if c.is_ascii() && is_ident_start(c as u8) => {
                self.skip_while(is_ident_continue);
                return Ok(Token {
                    kind: Kind::Ident,
                    span: start..self.pos,
                });
            }
            _ => return Err(self.unexpected_char(c)),
        };
        self.pos += 1;
        Ok(Token {
            kind,
            span: start..self.pos,
        })
    }

    fn unexpected_char(&self, c: char) -> Error {
        let span = self.pos..self.pos + c.len_utf8();
        let hint = match c {
            '=' => Some(
                "a formula is an expression f(x, y, z) whose zero set is drawn: write \
                 'lhs - (rhs)' for the surface lhs = rhs"
                    .to_string(),
            ),
            '[' | '{' => Some("use '(' for grouping".to_string()),
            ']' | '}' => Some("use ')' for grouping".to_string()),
            _ => None,
        };
        syntax(format!("unexpected character '{c}'"), span, hint)
    }

    /// A decimal literal: `digits [. digits] [(e|E) [+|-] digits]` with at least one
    /// mantissa digit.
    fn number(&mut self) -> Result<Token, Error> {
        let start = self.pos;
        self.skip_while(|b| b.is_ascii_digit());
        let int_digits = self.pos - start;
        let mut frac_digits = 0;
        if self.byte(self.pos) == Some(b'.') {
            self.pos += 1;
            let f = self.pos;
            self.skip_while(|b| b.is_ascii_digit());
            frac_digits = self.pos - f;
        }
        if int_digits + frac_digits == 0 {
            return Err(syntax(
                "malformed number '.'".to_string(),
                start..self.pos,
                Some("expected digits before or after '.'".to_string()),
            ));
        }
        if matches!(self.byte(self.pos), Some(b'e' | b'E')) {
            let mut j = self.pos + 1;
            if matches!(self.byte(j), Some(b'+' | b'-')) {
                j += 1;
            }
            if self.byte(j).is_some_and(|b| b.is_ascii_digit()) {
                self.pos = j;
                self.skip_while(|b| b.is_ascii_digit());
            } else if j == self.pos + 1 && self.byte(j).is_some_and(is_ident_start) {
                // `2exp(x)`, `2e_x`: the number ends before the name (and the parser then
                // reports the missing operator).
            } else {
                let text = &self.text[start..j];
                return Err(syntax(
                    format!("malformed number '{text}'"),
                    start..j,
                    Some("expected digits after the exponent 'e'".to_string()),
                ));
            }
        }
        if self.byte(self.pos) == Some(b'.') {
            // `1.2.3`, `1e5.5`: take the whole run of digits and dots into the error.
            self.skip_while(|b| b.is_ascii_digit() || b == b'.');
            let text = &self.text[start..self.pos];
            return Err(syntax(
                format!("malformed number '{text}'"),
                start..self.pos,
                Some("a number has at most one '.'".to_string()),
            ));
        }
        Ok(Token {
            kind: Kind::Number,
            span: start..self.pos,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(text: &str) -> Vec<(Kind, &str)> {
        let mut lx = Lexer::new(text);
        let mut out = Vec::new();
        loop {
            let t = lx.next_token().unwrap();
            out.push((t.kind, &text[t.span.clone()]));
            if t.kind == Kind::End {
                return out;
            }
        }
    }

    #[test]
    fn tokens() {
        use Kind::*;
        assert_eq!(
            kinds(" 1.5e-3*x_1^(2.)/ .5,y"),
            vec![
                (Number, "1.5e-3"),
                (Star, "*"),
                (Ident, "x_1"),
                (Caret, "^"),
                (LParen, "("),
                (Number, "2."),
                (RParen, ")"),
                (Slash, "/"),
                (Number, ".5"),
                (Comma, ","),
                (Ident, "y"),
                (End, ""),
            ]
        );
        assert_eq!(
            kinds("2exp"),
            vec![(Number, "2"), (Ident, "exp"), (End, "")]
        );
        assert_eq!(kinds("1E+2"), vec![(Number, "1E+2"), (End, "")]);
    }

    #[test]
    fn bad_numbers() {
        for (text, span) in [
            ("1e", 0..2),
            ("1e+", 0..3),
            ("1.2.3", 0..5),
            (".", 0..1),
            ("2e-x", 0..3),
        ] {
            let err = Lexer::new(text).next_token().unwrap_err();
            let Error::Syntax { span: s, .. } = err else {
                panic!()
            };
            assert_eq!(s, span, "{text}");
        }
    }
}

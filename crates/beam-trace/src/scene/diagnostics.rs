//! Span-based diagnostics of a scene file: the [`Doc`] being loaded, field paths matched to
//! the spans of the TOML syntax tree, line and column numbers, and the checks of single
//! values (finite, positive, in range) that report an error at a field path.

use std::fmt::Display;
use std::ops::Range;

use glam::DVec3;
use implicit_expr::parse::suggest;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use crate::error::Error;

/// The document being loaded: its name, text and syntax tree (with spans), for messages.
pub(super) struct Doc<'a> {
    pub(super) file: &'a str,
    pub(super) text: &'a str,
    pub(super) tree: Option<Spanned<DeTable<'a>>>,
}

/// One step of a field path.
pub(super) enum Seg<'p> {
    Key(&'p str),
    Index(usize),
}

/// `surfaces[0].params.a` → `surfaces`, `[0]`, `params`, `a`.
pub(super) fn segments(path: &str) -> Vec<Seg<'_>> {
    let mut out = Vec::new();
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let (key, mut rest) = part.split_at(part.find('[').unwrap_or(part.len()));
        if !key.is_empty() {
            out.push(Seg::Key(key));
        }
        while let Some(r) = rest.strip_prefix('[') {
            let end = r.find(']').unwrap_or(r.len());
            if let Ok(i) = r[..end].parse() {
                out.push(Seg::Index(i));
            }
            rest = r.get(end + 1..).unwrap_or("");
        }
    }
    out
}

pub(super) fn table_entry<'t, 'i>(
    t: &'t DeTable<'i>,
    key: &str,
) -> Option<&'t Spanned<DeValue<'i>>> {
    t.iter()
        .find(|(k, _)| k.get_ref().as_ref() == key)
        .map(|(_, v)| v)
}

/// A candidate field for an error span: (exact, width, depth, path).
pub(super) type Candidate = (bool, usize, usize, String);

pub(super) fn better(a: &Candidate, b: &Option<Candidate>) -> bool {
    match b {
        None => true,
        Some(b) => match (a.0, b.0) {
            (true, false) => true,
            (false, true) => false,
            (true, true) => a.2 > b.2,
            (false, false) => a.1 < b.1 || (a.1 == b.1 && a.2 > b.2),
        },
    }
}

pub(super) fn consider(
    span: Range<usize>,
    at: &Range<usize>,
    depth: usize,
    path: &str,
    best: &mut Option<Candidate>,
) {
    let exact = span == *at;
    if exact || (span.start <= at.start && at.end <= span.end) {
        let c = (exact, span.end - span.start, depth, path.to_string());
        if better(&c, best) {
            *best = Some(c);
        }
    }
}

/// Visits every key and value of `v`, keeping the field whose span fits `at` best.
pub(super) fn visit(
    v: &DeValue<'_>,
    at: &Range<usize>,
    depth: usize,
    path: &str,
    best: &mut Option<Candidate>,
) {
    match v {
        DeValue::Table(t) => visit_table(t, at, depth, path, best),
        DeValue::Array(a) => {
            for (i, e) in a.iter().enumerate() {
                let p = format!("{path}[{i}]");
                consider(e.span(), at, depth + 1, &p, best);
                visit(e.get_ref(), at, depth + 1, &p, best);
            }
        }
        _ => {}
    }
}

pub(super) fn visit_table(
    t: &DeTable<'_>,
    at: &Range<usize>,
    depth: usize,
    path: &str,
    best: &mut Option<Candidate>,
) {
    for (k, v) in t.iter() {
        let p = if path.is_empty() {
            k.get_ref().to_string()
        } else {
            format!("{path}.{}", k.get_ref())
        };
        consider(k.span(), at, depth + 1, &p, best);
        consider(v.span(), at, depth + 1, &p, best);
        visit(v.get_ref(), at, depth + 1, &p, best);
    }
}

/// A serde message with `'` quotes and a did-you-mean for unknown fields and variants.
pub(super) fn polish(msg: &str) -> String {
    let quoted: Vec<&str> = msg.split('`').skip(1).step_by(2).collect();
    let mut out = msg.trim_end().replace('`', "'");
    if (msg.starts_with("unknown field") || msg.starts_with("unknown variant"))
        && quoted.len() >= 2
        && let Some(h) = suggest::did_you_mean(quoted[0], quoted[1..].iter().copied())
    {
        out.push_str("; ");
        out.push_str(&h);
    }
    out
}

impl<'a> Doc<'a> {
    /// The document of `text`, parsed into its syntax tree (with spans).
    pub(super) fn parse(file: &'a str, text: &'a str) -> Result<Self, Error> {
        let mut doc = Doc {
            file,
            text,
            tree: None,
        };
        doc.tree = Some(DeTable::parse(text).map_err(|e| doc.syntax_error(&e))?);
        Ok(doc)
    }

    /// Whether the document's top level has the table or key `key`.
    pub(super) fn has_key(&self, key: &str) -> bool {
        self.tree
            .as_ref()
            .is_some_and(|t| table_entry(t.get_ref(), key).is_some())
    }

    /// A document without text (a scene built in code).
    pub(super) fn detached(file: &'a str) -> Self {
        Doc {
            file,
            text: "",
            tree: None,
        }
    }

    /// 1-based line and column (in characters) of byte `offset`.
    pub(super) fn line_col(&self, offset: usize) -> (usize, usize) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let col = before[before.rfind('\n').map_or(0, |i| i + 1)..]
            .chars()
            .count()
            + 1;
        (line, col)
    }

    pub(super) fn location(&self, offset: usize) -> String {
        let (line, col) = self.line_col(offset);
        format!(" (line {line}, column {col})")
    }

    /// The span where the field `path` is written, if it is.
    pub(super) fn span_of(&self, path: &str) -> Option<Range<usize>> {
        let tree = self.tree.as_ref()?;
        let mut segs = segments(path).into_iter();
        let Some(Seg::Key(first)) = segs.next() else {
            return None;
        };
        let mut cur = table_entry(tree.get_ref(), first)?;
        for s in segs {
            cur = match (s, cur.get_ref()) {
                (Seg::Key(k), DeValue::Table(t)) => table_entry(t, k)?,
                (Seg::Index(i), DeValue::Array(a)) => a.get(i)?,
                _ => return None,
            };
        }
        Some(cur.span())
    }

    /// An error at the field `path` (its line and column added when it is written).
    pub(super) fn err(&self, path: &str, message: impl Display) -> Error {
        self.err_detail(path, message, "")
    }

    /// [`Doc::err`] with `detail` (more lines) after the location.
    pub(super) fn err_detail(&self, path: &str, message: impl Display, detail: &str) -> Error {
        let loc = self
            .span_of(path)
            .map(|s| self.location(s.start))
            .unwrap_or_default();
        Error::Scene {
            file: self.file.to_string(),
            path: path.to_string(),
            message: format!("{message}{loc}{detail}"),
        }
    }

    /// A TOML syntax error.
    pub(super) fn syntax_error(&self, e: &toml::de::Error) -> Error {
        let loc = e.span().map(|s| self.location(s.start)).unwrap_or_default();
        Error::Scene {
            file: self.file.to_string(),
            path: String::new(),
            message: format!("invalid TOML{loc}: {}", polish(e.message())),
        }
    }

    /// A deserialisation error: the field path found from its span.
    pub(super) fn serde_error(&self, e: &toml::de::Error) -> Error {
        let mut path = String::new();
        let mut loc = String::new();
        if let (Some(span), Some(tree)) = (e.span(), &self.tree)
            && !span.is_empty()
        {
            let mut best = None;
            visit_table(tree.get_ref(), &span, 0, "", &mut best);
            if let Some((_, _, _, p)) = best {
                path = p;
            }
            loc = self.location(span.start);
        }
        Error::Scene {
            file: self.file.to_string(),
            path,
            message: format!("{}{loc}", polish(e.message())),
        }
    }
}

pub(super) fn fmt3(v: &[f64; 3]) -> String {
    format!("[{}, {}, {}]", v[0], v[1], v[2])
}

impl Doc<'_> {
    pub(super) fn finite(&self, path: &str, v: f64) -> Result<f64, Error> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(path, format!("must be a finite number, got {v}")))
        }
    }

    pub(super) fn vec3(&self, path: &str, v: [f64; 3]) -> Result<DVec3, Error> {
        if v.iter().all(|x| x.is_finite()) {
            Ok(DVec3::from_array(v))
        } else {
            Err(self.err(path, format!("must be finite, got {}", fmt3(&v))))
        }
    }

    pub(super) fn positive(&self, path: &str, v: f64) -> Result<f64, Error> {
        let v = self.finite(path, v)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(path, format!("must be positive, got {v}")))
        }
    }

    pub(super) fn unit(&self, path: &str, v: f64) -> Result<f64, Error> {
        let v = self.finite(path, v)?;
        if (0.0..=1.0).contains(&v) {
            Ok(v)
        } else {
            Err(self.err(path, format!("must lie in [0, 1], got {v}")))
        }
    }

    pub(super) fn color(&self, path: &str, v: [f64; 3]) -> Result<[f32; 3], Error> {
        self.vec3(path, v)?;
        if v.iter().all(|c| (0.0..=1.0).contains(c)) {
            Ok(v.map(|c| c as f32))
        } else {
            Err(self.err(
                path,
                format!("colour components must lie in [0, 1], got {}", fmt3(&v)),
            ))
        }
    }

    pub(super) fn int_in(&self, path: &str, v: i64, lo: i64, hi: i64) -> Result<u32, Error> {
        if (lo..=hi).contains(&v) {
            Ok(v as u32)
        } else {
            Err(self.err(path, format!("must be between {lo} and {hi}, got {v}")))
        }
    }

    pub(super) fn square(&self, path: &str, v: i64) -> Result<u32, Error> {
        let n = self.int_in(path, v, 1, 256)?;
        let r = (1..=16).find(|r| r * r >= n).unwrap_or(16);
        if r * r == n {
            Ok(n)
        } else {
            Err(self.err(
                path,
                format!("must be a square number (1, 4, 9, ..., 256), got {v}"),
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_of_paths() {
        let s = segments("csg[2].children[1]");
        assert!(matches!(
            s[..],
            [
                Seg::Key("csg"),
                Seg::Index(2),
                Seg::Key("children"),
                Seg::Index(1)
            ]
        ));
        assert!(segments("").is_empty());
        assert_eq!(segments("a[x].b[").len(), 2);
    }
}

//! "Did you mean ...?" suggestions: the closest known name by edit distance.
//!
//! The distance is the optimal-string-alignment variant of the Damerau–Levenshtein
//! distance: insertions, deletions, substitutions and transpositions of two adjacent
//! characters each cost 1 (so `sine → sin` and `cso → cos` are both at distance 1).

/// The edit distance between `a` and `b` (optimal string alignment: insertions,
/// deletions, substitutions and adjacent transpositions), counted in characters.
///
/// ```
/// use implicit_expr::parse::suggest::distance;
/// assert_eq!(distance("sine", "sin"), 1);
/// assert_eq!(distance("cso", "cos"), 1);
/// assert_eq!(distance("sqrt", "exp"), 4);
/// ```
pub fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    // Three rows of the dynamic-programming table: two back (for transpositions), one
    // back and the current one.
    let mut prev2: Vec<usize> = vec![0; b.len() + 1];
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur: Vec<usize> = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        cur[0] = i;
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut d = (prev[j] + 1).min(cur[j - 1] + 1).min(prev[j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d = d.min(prev2[j - 2] + 1);
            }
            cur[j] = d;
        }
        std::mem::swap(&mut prev2, &mut prev);
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

/// The candidate closest to `name`, if one is close enough to be a plausible typo.
///
/// A candidate that differs only in letter case always qualifies; otherwise the distance
/// must be at most a third of the longer name's length (rounded), so one-letter names get
/// no suggestion (`q` is not a typo of `x`) while `sine` suggests `sin` and `sqrtt`
/// suggests `sqrt`. Ties go to the earlier candidate.
///
/// ```
/// use implicit_expr::parse::suggest::closest;
/// let names = ["sin", "cos", "sqrt"];
/// assert_eq!(closest("sine", names), Some("sin"));
/// assert_eq!(closest("SQRT", names), Some("sqrt"));
/// assert_eq!(closest("foo", names), None);
/// ```
pub fn closest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let len = name.chars().count();
    let mut best: Option<(usize, &'a str)> = None;
    for cand in candidates {
        if cand == name {
            continue;
        }
        if cand.eq_ignore_ascii_case(name) {
            return Some(cand);
        }
        let cand_len = cand.chars().count();
        let limit = (len.max(cand_len) + 1) / 3;
        if len.abs_diff(cand_len) > limit {
            continue; // too far apart to be within the limit: skip the quadratic work
        }
        let d = distance(name, cand);
        if d <= limit && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, cand));
        }
    }
    best.map(|(_, c)| c)
}

/// `Some("did you mean 'NAME'?")` for the [`closest`] candidate, if any.
pub fn did_you_mean<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<String> {
    closest(name, candidates).map(|c| format!("did you mean '{c}'?"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(distance("", ""), 0);
        assert_eq!(distance("", "abc"), 3);
        assert_eq!(distance("abc", ""), 3);
        assert_eq!(distance("kitten", "sitting"), 3);
        assert_eq!(distance("ab", "ba"), 1);
        assert_eq!(distance("atna", "atan"), 1);
        assert_eq!(distance("é", "e"), 1);
    }

    #[test]
    fn suggestions() {
        let funcs = ["sin", "cos", "tan", "sqrt", "ln", "log", "min", "max"];
        assert_eq!(closest("sine", funcs), Some("sin"));
        assert_eq!(closest("sqr t", funcs), Some("sqrt"));
        assert_eq!(closest("Cos", funcs), Some("cos"));
        assert_eq!(closest("q", ["x", "y", "z"]), None);
        assert_eq!(closest("xx", ["x", "y", "z"]), Some("x"));
        let long = "a".repeat(100_000);
        assert_eq!(closest(&long, funcs), None);
    }
}

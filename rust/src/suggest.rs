//! "Did you mean ...?" suggestions for unknown keys and names: the one implementation, used
//! by the scene reader ([`crate::scene::read`]) for every form a scene comes in.
//!
//! [`close_match`] picks the same candidate as Python's
//! `difflib.get_close_matches(word, candidates, n=1, cutoff=0.6)` (the tests compare the
//! two), a choice Python users know. The similarity is difflib's Ratcliff/Obershelp ratio
//! 2·M/T, with M the characters in the matching blocks found by recursively taking the
//! longest common substring (first found wins, as in `SequenceMatcher.find_longest_match`)
//! and T the total length of both strings. difflib's "autojunk" heuristic only applies to
//! strings of 200 characters or more, which keys never are; it is not reproduced.

/// Similarity below which no suggestion is made (difflib's default cutoff).
pub const CUTOFF: f64 = 0.6;

/// Longest common substring of `a[alo..ahi]` and `b[blo..bhi]` as `(i, j, size)`; ties go
/// to the one found first scanning `a`, then `b`, in increasing order (difflib's rule).
fn longest_match(
    a: &[char],
    b: &[char],
    (alo, ahi): (usize, usize),
    (blo, bhi): (usize, usize),
) -> (usize, usize, usize) {
    let (mut besti, mut bestj, mut best) = (alo, blo, 0);
    // run[j + 1 - blo]: length of the common run ending at a[i - 1], b[j].
    let mut run = vec![0usize; bhi - blo + 1];
    let mut next = vec![0usize; bhi - blo + 1];
    for (i, &ca) in a.iter().enumerate().take(ahi).skip(alo) {
        next.iter_mut().for_each(|k| *k = 0);
        for (j, &cb) in b.iter().enumerate().take(bhi).skip(blo) {
            if ca != cb {
                continue;
            }
            let k = run[j - blo] + 1;
            next[j + 1 - blo] = k;
            if k > best {
                besti = i + 1 - k;
                bestj = j + 1 - k;
                best = k;
            }
        }
        std::mem::swap(&mut run, &mut next);
    }
    (besti, bestj, best)
}

/// Characters in the matching blocks of `a[alo..ahi]` and `b[blo..bhi]`.
fn matching_chars(a: &[char], b: &[char], ra: (usize, usize), rb: (usize, usize)) -> usize {
    let (i, j, k) = longest_match(a, b, ra, rb);
    if k == 0 {
        return 0;
    }
    let mut m = k;
    if ra.0 < i && rb.0 < j {
        m += matching_chars(a, b, (ra.0, i), (rb.0, j));
    }
    if i + k < ra.1 && j + k < rb.1 {
        m += matching_chars(a, b, (i + k, ra.1), (j + k, rb.1));
    }
    m
}

/// difflib's `SequenceMatcher(None, a, b).ratio()`: 2·M/T in [0, 1], 1 for identical strings.
pub fn similarity(a: &str, b: &str) -> f64 {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let total = a.len() + b.len();
    if total == 0 {
        return 1.0;
    }
    let m = matching_chars(&a, &b, (0, a.len()), (0, b.len()));
    2.0 * m as f64 / total as f64
}

/// The candidate most similar to `word`, if its similarity is at least [`CUTOFF`]. Ties go
/// to the candidate that sorts last, as `difflib.get_close_matches` (which ranks the
/// pairs (score, candidate) from the largest).
pub fn close_match<'a, I>(word: &str, candidates: I) -> Option<&'a str>
where
    I: IntoIterator<Item = &'a str>,
{
    let mut best: Option<(f64, &'a str)> = None;
    for c in candidates {
        // difflib compares SequenceMatcher(None, candidate, word): candidate is `a`.
        let score = similarity(c, word);
        if score < CUTOFF {
            continue;
        }
        let better = match best {
            None => true,
            Some((s, b)) => score > s || (score == s && c > b),
        };
        if better {
            best = Some((score, c));
        }
    }
    best.map(|(_, c)| c)
}

/// The message for an unknown key: the suggestion (if any) and the keys allowed here.
pub fn unknown_key_rule<'a, I>(key: &str, known: I) -> String
where
    I: IntoIterator<Item = &'a str>,
{
    let mut known: Vec<&str> = known.into_iter().collect();
    known.sort_unstable();
    known.dedup();
    let list = known.join(", ");
    match close_match(key, known.iter().copied()) {
        Some(s) => format!("unknown key, did you mean '{s}'? (known keys here: {list})"),
        None => format!("unknown key (known keys here: {list})"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference ratios are those printed by Python 3.11's
    // difflib.SequenceMatcher(None, a, b).ratio() for the same pairs.
    #[test]
    fn similarity_matches_difflib() {
        let cases = [
            ("radius", "radious", 12.0 / 13.0),
            ("center", "radious", 2.0 / 13.0),
            ("mass", "mas", 6.0 / 7.0),
            ("contact_stiffness", "contact_stifness", 32.0 / 33.0),
            ("contact_damping", "contact_stifness", 20.0 / 31.0),
            ("abce", "abcd", 0.75),
            ("bacd", "abcd", 0.75),
            ("ba", "ab", 0.5),
            ("radius", "xyz", 0.0),
            ("", "", 1.0),
        ];
        for (a, b, want) in cases {
            let got = similarity(a, b);
            assert!(
                (got - want).abs() < 1e-15,
                "similarity({a:?}, {b:?}) = {got}, difflib gives {want}"
            );
        }
    }

    #[test]
    fn picks_what_difflib_picks() {
        let keys = ["center", "radius", "mass", "inertia", "wrap"];
        assert_eq!(close_match("radious", keys), Some("radius"));
        assert_eq!(close_match("mas", ["mass", "name", "wrap"]), Some("mass"));
        assert_eq!(close_match("xyz", ["radius", "mass"]), None);
        // Three candidates tie at 0.75: difflib returns the one that sorts last.
        assert_eq!(close_match("abcd", ["abce", "abdc", "bacd"]), Some("bacd"));
        assert_eq!(close_match("ab", ["ba", "ab "]), Some("ab "));
    }

    #[test]
    fn rule_text() {
        assert_eq!(
            unknown_key_rule("radious", ["radius", "mass"]),
            "unknown key, did you mean 'radius'? (known keys here: mass, radius)"
        );
        assert_eq!(
            unknown_key_rule("zzz", ["radius", "mass"]),
            "unknown key (known keys here: mass, radius)"
        );
    }
}

//! Mutations of a seed input: a few byte-level and token-level edits.

/// Tokens that tend to break parsers and validators.
pub const TOKENS: &[&str] = &[
    "1e300",
    "-1e300",
    "1e-300",
    "0",
    "-0",
    "-1",
    "nan",
    "inf",
    "-inf",
    "4294967296",
    "18446744073709551616",
    "99999999",
    "0.5",
    "\"\"",
    "\"x\"",
    "[]",
    "{}",
    "[[",
    "]]",
    "[",
    "]",
    "{",
    "}",
    "\n",
    "=",
    ",",
    "\"",
    "#",
    ":",
    "true",
    "null",
    "\\u0000",
    "é",
    "\u{202e}",
    "[[hoses]]\n",
    "[[timeline]]\n",
    "[[parts]]\n",
    "action = \"run\"\n",
    "elements = 5000\n",
    "subdivisions = 30",
    "segments = 1000000",
    "mesh = \"/dev/zero\"",
    "mesh = \"../x.obj\"",
    "f 1 2 3\n",
    "v 0 0 0\n",
    "facet normal 0 0 1\n",
    "solid\n",
    "endsolid\n",
    "\"uri\":\"data:;base64,AAAA\"",
    "\"type\":\"step\"",
    "\"n\":100000",
    "\"hand_id\":4294967295",
];

/// One edit, made from three numbers so that proptest can generate and shrink it and a
/// plain random generator can make the same edits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    /// XOR the byte at a position with a value.
    Flip { at: u32, with: u8 },
    /// Insert a token at a position.
    Insert { at: u32, token: u32 },
    /// Delete up to `len` bytes at a position.
    Delete { at: u32, len: u32 },
    /// Repeat the line around a position.
    RepeatLine { at: u32 },
    /// Replace the number after a position by a token.
    Number { at: u32, token: u32 },
    /// Insert a piece of another seed.
    Splice { seed: u32, at: u32, len: u32 },
}

impl Op {
    /// The edit of kind `kind % 6` with parameters `a`, `b`.
    pub fn from_parts(kind: u8, a: u32, b: u32) -> Op {
        match kind % 6 {
            0 => Op::Flip {
                at: a,
                with: (b as u8).max(1),
            },
            1 => Op::Insert { at: a, token: b },
            2 => Op::Delete {
                at: a,
                len: b % 64 + 1,
            },
            3 => Op::RepeatLine { at: a },
            4 => Op::Number { at: a, token: b },
            _ => Op::Splice {
                seed: b,
                at: a,
                len: (b >> 8) % 256 + 1,
            },
        }
    }
}

/// `seed` with `ops` applied in order; `others` are the seeds splices take from.
pub fn apply(seed: &[u8], ops: &[Op], others: &[&[u8]]) -> Vec<u8> {
    let mut s = seed.to_vec();
    for &op in ops {
        let pos = |at: u32, len: usize| if len == 0 { 0 } else { at as usize % (len + 1) };
        let token = |k: u32| TOKENS[k as usize % TOKENS.len()].as_bytes();
        match op {
            Op::Flip { at, with } => {
                if !s.is_empty() {
                    let i = at as usize % s.len();
                    s[i] ^= with;
                }
            }
            Op::Insert { at, token: k } => {
                let i = pos(at, s.len());
                s.splice(i..i, token(k).iter().copied());
            }
            Op::Delete { at, len } => {
                let i = pos(at, s.len());
                let j = (i + len as usize).min(s.len());
                s.drain(i..j);
            }
            Op::RepeatLine { at } => {
                let i = pos(at, s.len());
                let start = s[..i]
                    .iter()
                    .rposition(|&c| c == b'\n')
                    .map_or(0, |p| p + 1);
                let end = s[i..]
                    .iter()
                    .position(|&c| c == b'\n')
                    .map_or(s.len(), |p| i + p + 1);
                let line = s[start..end].to_vec();
                s.splice(end..end, line);
            }
            Op::Number { at, token: k } => {
                let i = pos(at, s.len());
                if let Some(d) = s[i..].iter().position(u8::is_ascii_digit) {
                    let a = i + d;
                    let b = s[a..]
                        .iter()
                        .position(|c| !(c.is_ascii_digit() || matches!(c, b'.' | b'e' | b'-')))
                        .map_or(s.len(), |p| a + p);
                    s.splice(a..b, token(k).iter().copied());
                }
            }
            Op::Splice { seed, at, len } => {
                if let Some(other) = others.get(seed as usize % others.len().max(1)) {
                    let from = pos(at.rotate_left(7), other.len()).min(other.len());
                    let to = (from + len as usize).min(other.len());
                    let i = pos(at, s.len());
                    s.splice(i..i, other[from..to].iter().copied());
                }
            }
        }
    }
    s
}

/// A small, fast, seeded random generator (xorshift64*) for the long run.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.max(1))
    }

    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// One to `max` random edits.
    pub fn ops(&mut self, max: usize) -> Vec<Op> {
        let n = 1 + self.next_u64() as usize % max;
        (0..n)
            .map(|_| {
                let r = self.next_u64();
                Op::from_parts(r as u8, (r >> 8) as u32, self.next_u64() as u32)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edits_do_what_they_say() {
        let s = b"a = 12\nb = 3\n";
        assert_eq!(
            apply(s, &[Op::Number { at: 0, token: 0 }], &[]),
            b"a = 1e300\nb = 3\n"
        );
        assert_eq!(
            apply(s, &[Op::RepeatLine { at: 9 }], &[]),
            b"a = 12\nb = 3\nb = 3\n"
        );
        assert_eq!(
            apply(s, &[Op::Delete { at: 0, len: 4 }], &[]),
            b"12\nb = 3\n"
        );
        assert_eq!(apply(b"", &[Op::Flip { at: 3, with: 1 }], &[]), b"");
        assert_eq!(
            apply(
                b"xy",
                &[Op::Splice {
                    seed: 0,
                    at: 0,
                    len: 2
                }],
                &[b"ab"]
            ),
            b"abxy"
        );
    }
}

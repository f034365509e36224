//! Error messages echo what the user wrote — an unknown key, a name, a value — but never
//! a whole megabyte of it (a 100 000-character key was echoed whole): every
//! word longer than [`MAX_WORD_CHARS`] (paths fit) is cut to its first [`KEEP_CHARS`]
//! characters and "…(N chars)", and a message longer than [`MAX_MESSAGE_CHARS`] to its
//! first [`MAX_MESSAGE_CHARS`] and "…(N chars)".

use std::borrow::Cow;

/// Longest word (a run of characters between whitespace) echoed whole.
pub const MAX_WORD_CHARS: usize = 200;
/// Characters kept of a longer word or message.
pub const KEEP_CHARS: usize = 64;
/// Longest message echoed whole (after its words are clipped).
pub const MAX_MESSAGE_CHARS: usize = 4000;

/// `text` with over-long words and an over-long whole clipped (see the module doc);
/// borrowed when nothing needed clipping.
pub fn clip_words(text: &str) -> Cow<'_, str> {
    let long_word = text
        .split(char::is_whitespace)
        .any(|w| w.len() > MAX_WORD_CHARS && w.chars().count() > MAX_WORD_CHARS);
    if !long_word && text.len() <= MAX_MESSAGE_CHARS {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len().min(4 * MAX_MESSAGE_CHARS));
    let mut rest = text;
    while !rest.is_empty() {
        let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
        out.push_str(&clip(&rest[..end], MAX_WORD_CHARS, KEEP_CHARS));
        let space = rest[end..]
            .find(|c: char| !c.is_whitespace())
            .map_or(rest.len(), |k| end + k);
        out.push_str(&rest[end..space]);
        rest = &rest[space..];
    }
    Cow::Owned(clip(&out, MAX_MESSAGE_CHARS, MAX_MESSAGE_CHARS).into_owned())
}

/// `s` cut to `keep` characters and "…(N chars)" if it has more than `most`.
fn clip(s: &str, most: usize, keep: usize) -> Cow<'_, str> {
    let n = s.chars().count();
    if n <= most {
        return Cow::Borrowed(s);
    }
    let kept: String = s.chars().take(keep).collect();
    Cow::Owned(format!("{kept}…({n} chars)"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_key_is_echoed_as_its_start_and_its_length() {
        let key = "k".repeat(100_000);
        let message = format!("unknown field `{key}`, expected one of `a`, `b`");
        let clipped = clip_words(&message);
        assert!(clipped.len() < 200, "{clipped}");
        // the word is the key with its quotes and comma
        assert!(
            clipped.contains(&format!("`{}…(100003 chars)", "k".repeat(63))),
            "{clipped}"
        );
        assert!(clipped.ends_with(" expected one of `a`, `b`"), "{clipped}");
        assert_eq!(clip_words("short words stay"), "short words stay");
        let many = "word ".repeat(1000);
        let clipped = clip_words(&many);
        assert!(clipped.ends_with("…(5000 chars)"), "{clipped}");
        assert_eq!(
            clipped.chars().count(),
            MAX_MESSAGE_CHARS + "…(5000 chars)".len() - 2
        );
    }
}

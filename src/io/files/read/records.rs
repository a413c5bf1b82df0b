//! Records and fields: the lines of a file that hold data (comments and blank lines skipped) and
//! their numbers, read as C's `strtol` and `strtod` read them, with errors naming file and line.

use super::*;

/// The lines of a file, skipping those without data.
#[derive(Clone, Copy)]
pub(super) struct Lines<'a> {
    file: &'a str,
    text: &'a str,
    position: usize,
    line_number: usize,
}

/// One line with data: the part before `#`, read field by field. Fields are described with
/// `format_args!`, which is formatted only if an error is reported (files have millions of them).
pub(super) struct Record<'a> {
    file: &'a str,
    pub(super) line: usize,
    rest: &'a str,
}

pub(super) fn starts_like_a_number(word: &str) -> bool {
    matches!(
        word.as_bytes().first(),
        Some(b'0'..=b'9' | b'.' | b'+' | b'-')
    )
}

impl<'a> Lines<'a> {
    /// The lines of `text`, without the byte-order mark an editor may write before them (UTF-8's
    /// EF BB BF, U+FEFF): Triangle reads such a file as if it were not there. Every reader, and the
    /// fast path of the vertex section, reads the text from here on.
    pub(super) fn new(file: &'a str, text: &'a str) -> Self {
        Lines {
            file,
            text: text.strip_prefix('\u{feff}').unwrap_or(text),
            position: 0,
            line_number: 0,
        }
    }

    /// Where the next line starts (a byte offset into the text).
    pub(super) fn position(&self) -> usize {
        self.position
    }

    /// The number of the line read last (0 before the first).
    pub(super) fn line_number(&self) -> usize {
        self.line_number
    }

    /// The whole text.
    pub(super) fn text(&self) -> &'a str {
        self.text
    }

    /// These lines as far as byte `end` (a line start): a reader of one part of the text, which
    /// numbers its lines on from here.
    pub(super) fn ending_at(&self, end: usize) -> Lines<'a> {
        Lines {
            text: &self.text[..end],
            ..*self
        }
    }

    /// Moves past `lines` lines that end at byte `position` (a line start), read elsewhere.
    pub(super) fn skip_read_lines(&mut self, position: usize, lines: usize) {
        self.position = position;
        self.line_number += lines;
    }

    pub(super) fn error(&self, line: Option<usize>, message: String) -> FileError {
        FileError {
            file: self.file.to_string(),
            line,
            message,
        }
    }

    /// The next line that holds a number, or `None` at the end of the file.
    pub(super) fn next_record(&mut self) -> Option<Record<'a>> {
        while self.position < self.text.len() {
            let rest = &self.text[self.position..];
            let end = rest.find('\n').unwrap_or(rest.len());
            self.position += (end + 1).min(rest.len());
            self.line_number += 1;
            let line = &rest[..end];
            let data = line.find('#').map_or(line, |hash| &line[..hash]);
            // Most lines start with a number: look at the first word before splitting them all.
            let first = data.bytes().find(|b| !b.is_ascii_whitespace());
            let holds_a_number = match first {
                None => false,
                Some(b'0'..=b'9' | b'.' | b'+' | b'-') => true,
                Some(_) => data.split_ascii_whitespace().any(starts_like_a_number),
            };
            if holds_a_number {
                return Some(Record {
                    file: self.file,
                    line: self.line_number,
                    rest: data,
                });
            }
        }
        None
    }

    /// The next record, which must exist: `what` names what was expected.
    pub(super) fn expect_record(
        &mut self,
        what: fmt::Arguments<'_>,
    ) -> Result<Record<'a>, FileError> {
        self.next_record().ok_or_else(|| {
            self.error(
                Some(self.line_number.max(1)),
                format!("unexpected end of file: expected {what}"),
            )
        })
    }
}

/// Reads the longest prefix of `word` that C's `strtol(word, NULL, 0)` converts.
pub(super) fn parse_c_integer(word: &str) -> Option<Result<i64, ()>> {
    let bytes = word.as_bytes();
    let (negative, mut i) = match bytes.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let radix = if bytes.get(i) == Some(&b'0')
        && matches!(bytes.get(i + 1), Some(b'x' | b'X'))
        && bytes.get(i + 2).is_some_and(|b| b.is_ascii_hexdigit())
    {
        i += 2;
        16
    } else if bytes.get(i) == Some(&b'0') {
        8
    } else {
        10
    };
    let start = i;
    while i < bytes.len() && (bytes[i] as char).is_digit(radix) {
        i += 1;
    }
    if i == start {
        return None;
    }
    let magnitude = match i64::from_str_radix(&word[start..i], radix) {
        Ok(m) => m,
        Err(_) => return Some(Err(())),
    };
    Some(Ok(if negative { -magnitude } else { magnitude }))
}

/// Reads the longest prefix of `word` that C's `strtod` converts as a decimal number.
pub(super) fn parse_c_real(word: &str) -> Option<f64> {
    let bytes = word.as_bytes();
    let mut i = 0;
    if matches!(bytes.first(), Some(b'-' | b'+')) {
        i = 1;
    }
    let mut mantissa_digits = 0;
    while i < bytes.len() && bytes[i].is_ascii_digit() {
        i += 1;
        mantissa_digits += 1;
    }
    if i < bytes.len() && bytes[i] == b'.' {
        i += 1;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            i += 1;
            mantissa_digits += 1;
        }
    }
    if mantissa_digits == 0 {
        return None;
    }
    let mantissa_end = i;
    if i < bytes.len() && matches!(bytes[i], b'e' | b'E') {
        let mut j = i + 1;
        if j < bytes.len() && matches!(bytes[j], b'-' | b'+') {
            j += 1;
        }
        let digits_start = j;
        while j < bytes.len() && bytes[j].is_ascii_digit() {
            j += 1;
        }
        if j > digits_start {
            i = j;
        }
    }
    let text = &word[..i];
    // Rust's parser accepts every form above ("1.", ".5", "+2e3"); only "1.e5"-like forms need
    // the point completed.
    text.parse::<f64>().ok().or_else(|| {
        let mut fixed = word[..mantissa_end].to_string();
        fixed.push('0');
        fixed.push_str(&word[mantissa_end..i]);
        fixed.parse::<f64>().ok()
    })
}

impl<'a> Record<'a> {
    pub(super) fn error(&self, message: String) -> FileError {
        FileError {
            file: self.file.to_string(),
            line: Some(self.line),
            message,
        }
    }

    /// The next word that starts like a number.
    pub(super) fn next_word(&mut self) -> Option<&'a str> {
        // Byte by byte: ASCII whitespace never occurs inside a multi-byte UTF-8 character, so
        // the slices below fall on character boundaries.
        loop {
            let bytes = self.rest.as_bytes();
            let start = bytes
                .iter()
                .position(|b| !b.is_ascii_whitespace())
                .unwrap_or(bytes.len());
            if start == bytes.len() {
                self.rest = "";
                return None;
            }
            let end = bytes[start..]
                .iter()
                .position(|b| b.is_ascii_whitespace())
                .map_or(bytes.len(), |n| start + n);
            let word = &self.rest[start..end];
            self.rest = &self.rest[end..];
            if starts_like_a_number(word) {
                return Some(word);
            }
        }
    }

    /// The next integer field, `None` if the line has no more fields.
    pub(super) fn optional_integer(
        &mut self,
        what: fmt::Arguments<'_>,
    ) -> Result<Option<i64>, FileError> {
        let Some(word) = self.next_word() else {
            return Ok(None);
        };
        match parse_c_integer(word) {
            Some(Ok(value)) => Ok(Some(value)),
            Some(Err(())) => Err(self.error(format!("{what} `{word}` is out of range"))),
            None => Err(self.error(format!("{what} `{word}` is not a number"))),
        }
    }

    pub(super) fn integer(&mut self, what: fmt::Arguments<'_>) -> Result<i64, FileError> {
        self.optional_integer(what)?
            .ok_or_else(|| self.error(format!("{what} is missing")))
    }

    /// The next integer field as an `i32` (an index or a marker).
    pub(super) fn optional_int32(
        &mut self,
        what: fmt::Arguments<'_>,
    ) -> Result<Option<i32>, FileError> {
        match self.optional_integer(what)? {
            None => Ok(None),
            Some(value) => i32::try_from(value)
                .map(Some)
                .map_err(|_| self.error(format!("{what} {value} is out of range"))),
        }
    }

    pub(super) fn int32(&mut self, what: fmt::Arguments<'_>) -> Result<i32, FileError> {
        self.optional_int32(what)?
            .ok_or_else(|| self.error(format!("{what} is missing")))
    }

    /// A count: an integer from 0 to `i32::MAX` (the C interface's limit).
    pub(super) fn optional_count(
        &mut self,
        what: fmt::Arguments<'_>,
    ) -> Result<Option<usize>, FileError> {
        match self.optional_integer(what)? {
            None => Ok(None),
            Some(value) if (0..=i32::MAX as i64).contains(&value) => Ok(Some(value as usize)),
            Some(value) => Err(self.error(format!("{what} {value} is negative or too large"))),
        }
    }

    pub(super) fn count(&mut self, what: fmt::Arguments<'_>) -> Result<usize, FileError> {
        self.optional_count(what)?
            .ok_or_else(|| self.error(format!("{what} is missing")))
    }

    /// The next real field, `None` if the line has no more fields; it must be finite.
    pub(super) fn optional_real(
        &mut self,
        what: fmt::Arguments<'_>,
    ) -> Result<Option<f64>, FileError> {
        let Some(word) = self.next_word() else {
            return Ok(None);
        };
        match parse_c_real(word) {
            Some(value) if value.is_finite() => Ok(Some(value)),
            Some(_) => Err(self.error(format!("{what} `{word}` is not a finite number"))),
            None => Err(self.error(format!("{what} `{word}` is not a number"))),
        }
    }

    pub(super) fn real(&mut self, what: fmt::Arguments<'_>) -> Result<f64, FileError> {
        self.optional_real(what)?
            .ok_or_else(|| self.error(format!("{what} is missing")))
    }
}

/// Capacity to reserve for `count` items announced by a header: bounded, so that a corrupt header
/// cannot make the reader allocate gigabytes before it finds out the file is short. Both the
/// count and the width (corners, attributes per item) come from the header: bound the product.
pub(super) fn reserve(count: usize, width: usize) -> usize {
    count.saturating_mul(width).min(1 << 21)
}

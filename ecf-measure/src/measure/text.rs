//! The text layer of a measurement file: UTF-8, the delimiter, the CSV reader and its header, and the form of every error (file, line, column, reason).

use creep_core::error::{CreepError, Result};

/// An error in a data file: `line` (1-based, header = 1), `column` (a header, a canonical
/// name or "-") and the reason.
pub(crate) fn err(src: &str, line: usize, column: &str, reason: String) -> CreepError {
    CreepError::Data {
        source_name: src.to_string(),
        message: format!("line {line}, column '{}': {reason}", cut(column)),
    }
}

/// A cell or name cut to 40 characters for messages.
pub fn cut(s: &str) -> String {
    let n = s.chars().count();
    if n <= 40 {
        s.to_string()
    } else {
        format!(
            "{}... ({n} characters)",
            s.chars().take(40).collect::<String>()
        )
    }
}

/// The header's names cut for messages, comma separated ("have: ...").
pub(crate) fn names(header: &[String]) -> String {
    header.iter().map(|h| cut(h)).collect::<Vec<_>>().join(", ")
}

/// Text of a data file: UTF-8, else an error naming the line of the first bad byte.
pub fn utf8_text(bytes: &[u8], src: &str) -> Result<String> {
    match std::str::from_utf8(bytes) {
        Ok(t) => Ok(t.trim_start_matches('\u{feff}').to_string()),
        Err(e) => {
            let at = e.valid_up_to();
            let line = bytes[..at].iter().filter(|b| **b == b'\n').count() + 1;
            let col = at
                - bytes[..at]
                    .iter()
                    .rposition(|b| *b == b'\n')
                    .map(|p| p + 1)
                    .unwrap_or(0);
            Err(CreepError::Data {
                source_name: src.into(),
                message: format!(
                    "line {line}: not UTF-8 text (byte 0x{:02X} at character {} of the line); save the file as UTF-8",
                    bytes[at],
                    col + 1
                ),
            })
        }
    }
}

/// Delimiter of a CSV text: the most frequent of `,` `;` tab in the first non-comment line.
pub fn detect_delimiter(text: &str) -> u8 {
    let header = text
        .lines()
        .find(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
        .unwrap_or("");
    let count = |c: char| header.chars().filter(|x| *x == c).count();
    let (comma, semi, tab) = (count(','), count(';'), count('\t'));
    if semi > comma && semi >= tab {
        b';'
    } else if tab > comma && tab > semi {
        b'\t'
    } else {
        b','
    }
}

/// A delimiter as messages name it (`tab`, `,`, `;`).
pub(crate) fn delimiter_name(delim: u8) -> String {
    if delim == b'\t' {
        "tab".to_string()
    } else {
        (delim as char).to_string()
    }
}

/// Opens CSV text (trimmed fields, `#` comments) and checks its header: no empty or duplicate
/// column names, every `required` column present.
pub(crate) fn open_csv<'a>(
    text: &'a str,
    src: &str,
    required: &[&str],
    delim: u8,
) -> Result<(csv::Reader<&'a [u8]>, Vec<String>)> {
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .delimiter(delim)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header: Vec<String> = rdr
        .headers()
        .map_err(|e| err(src, 1, "-", format!("bad header: {}", cut(&e.to_string()))))?
        .iter()
        .map(|s| s.to_string())
        .collect();
    for (i, h) in header.iter().enumerate() {
        if h.is_empty() {
            return Err(err(
                src,
                1,
                &format!("#{}", i + 1),
                "empty column name".into(),
            ));
        }
        if header[..i].contains(h) {
            return Err(err(src, 1, h, "duplicate column".into()));
        }
    }
    for req in required {
        if !header.iter().any(|h| h == req) {
            return Err(err(
                src,
                1,
                req,
                format!("required column missing (have: {})", names(&header)),
            ));
        }
    }
    Ok((rdr, header))
}

/// The line in the file of each record: the csv crate's own line count skips comment lines,
/// so lines are counted from the records' byte offsets, past the comment and empty lines
/// that precede a record.
pub(crate) struct Lines<'a> {
    text: &'a str,
    seen_byte: usize,
    seen_line: usize,
}

impl<'a> Lines<'a> {
    /// Counting in `text`, from its first line.
    pub(crate) fn new(text: &'a str) -> Self {
        Lines {
            text,
            seen_byte: 0,
            seen_line: 1,
        }
    }

    /// Line of the record at `position`; `fallback` where the reader gives no position.
    pub(crate) fn line_of(&mut self, position: Option<&csv::Position>, fallback: usize) -> usize {
        let Some(p) = position else {
            return fallback;
        };
        let bytes = self.text.as_bytes();
        let mut b = (p.byte() as usize).min(bytes.len());
        // the record's position may be that of comment or empty lines before it
        loop {
            let rest = &self.text[b..];
            let first = rest.split('\n').next().unwrap_or("");
            let skip = first.trim_start().starts_with('#') || first.trim().is_empty();
            match rest.find('\n') {
                Some(n) if skip => b += n + 1,
                _ => break,
            }
        }
        if b >= self.seen_byte {
            self.seen_line += bytes[self.seen_byte..b]
                .iter()
                .filter(|c| **c == b'\n')
                .count();
            self.seen_byte = b;
        }
        self.seen_line
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delimiters_and_cuts() {
        assert_eq!(detect_delimiter("# c,c,c\na;b;c\n"), b';');
        assert_eq!(detect_delimiter("a\tb\tc,d\n"), b'\t');
        assert_eq!(detect_delimiter("a,b;c\n"), b',');
        assert_eq!(delimiter_name(b'\t'), "tab");
        assert_eq!(
            cut(&"x".repeat(41)),
            format!("{}... (41 characters)", "x".repeat(40))
        );
        assert_eq!(cut("short"), "short");
    }

    #[test]
    fn lines_pass_over_comments_and_blank_lines() {
        let text = "a,b\n# c\n\n1,2\n3,4\n";
        let (mut rdr, _) = open_csv(text, "t.csv", &[], b',').unwrap();
        let mut lines = Lines::new(text);
        let mut got = Vec::new();
        for rec in rdr.records() {
            let rec = rec.unwrap();
            got.push(lines.line_of(rec.position(), 0));
        }
        assert_eq!(got, vec![4, 5]);
    }

    #[test]
    fn headers_must_be_named_once() {
        let e = open_csv("a,,b\n", "t.csv", &[], b',')
            .unwrap_err()
            .to_string();
        assert!(e.contains("column '#2': empty column name"), "{e}");
        let e = open_csv("a,a\n", "t.csv", &[], b',')
            .unwrap_err()
            .to_string();
        assert!(e.contains("column 'a': duplicate column"), "{e}");
        let e = open_csv("a\n", "t.csv", &["b"], b',')
            .unwrap_err()
            .to_string();
        assert!(e.contains("required column missing (have: a)"), "{e}");
    }
}

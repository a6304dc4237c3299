//! Load errors that name the file, the line and column, and the cause.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A problem with an input file, located as precisely as the input allows.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub struct LoadError {
    /// The file at fault.
    pub file: PathBuf,
    /// 1-based line and column, when the problem has a place in the file.
    pub position: Option<(usize, usize)>,
    /// What is wrong, in one line.
    pub message: String,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.position {
            Some((line, column)) => write!(
                f,
                "{}:{line}:{column}: {}",
                self.file.display(),
                self.message
            ),
            None => write!(f, "{}: {}", self.file.display(), self.message),
        }
    }
}

impl LoadError {
    /// An error about the file as a whole.
    pub fn file(file: &Path, message: impl Into<String>) -> Self {
        Self {
            file: file.to_path_buf(),
            position: None,
            message: message.into(),
        }
    }

    /// An error at a 1-based line (column 1).
    pub fn line(file: &Path, line: usize, message: impl Into<String>) -> Self {
        Self {
            file: file.to_path_buf(),
            position: Some((line, 1)),
            message: message.into(),
        }
    }
}

/// A text file's name and contents, to turn byte offsets into lines and columns.
#[derive(Clone, Copy, Debug)]
pub struct Source<'a> {
    /// The file's path, as the user gave it.
    pub path: &'a Path,
    /// Its text.
    pub text: &'a str,
}

impl Source<'_> {
    /// An error at byte range `span` (no position when the span is empty at offset 0, the mark
    /// of a value that did not come from the file).
    pub fn error(&self, span: Range<usize>, message: impl Into<String>) -> LoadError {
        let position = (span != (0..0)).then(|| line_column(self.text, span.start));
        LoadError {
            file: self.path.to_path_buf(),
            position,
            message: message.into(),
        }
    }
}

/// 1-based line and column (in characters) of byte `offset` in `text`.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut end = offset.min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let before = &text[..end];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_map_to_lines_and_columns() {
        let text = "ab\ncdé\nf";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 1), (1, 2));
        assert_eq!(line_column(text, 3), (2, 1));
        assert_eq!(line_column(text, 8), (3, 1));
        assert_eq!(line_column(text, 6), (2, 3)); // inside é: its first byte
    }

    #[test]
    fn display_names_file_line_and_column() {
        let src = Source {
            path: Path::new("s.toml"),
            text: "a\nbc",
        };
        assert_eq!(src.error(3..4, "bad").to_string(), "s.toml:2:2: bad");
        assert_eq!(src.error(0..0, "bad").to_string(), "s.toml: bad");
    }
}

//! The files a command reads and writes, handled the same way by every subcommand.
//!
//! - [`input`]: open only regular files (a FIFO, a device or a folder is refused without blocking)
//!   and read them under a size cap.
//! - [`output`]: outputs are written atomically (a temporary file in the destination folder,
//!   created before the work starts so that an unwritable folder is reported at once, renamed into
//!   place when complete) and never onto one of the command's inputs, by file identity.
//! - [`shown`]: paths in messages, with control characters escaped.

pub mod input;
pub mod output;

use std::fmt;
use std::path::Path;

/// " (raise it with FLAG)" for a limit's message, or nothing where no flag raises it.
pub fn raise_hint(flag: Option<&str>) -> String {
    match flag {
        Some(flag) => format!(" (raise it with {flag})"),
        None => String::new(),
    }
}

/// A path for messages: as `Path::display`, with control characters (newlines, escape
/// sequences) written as escapes so a hostile file name cannot rewrite the terminal.
pub fn shown(path: &Path) -> Shown<'_> {
    Shown(path)
}

/// See [`shown`].
pub struct Shown<'a>(&'a Path);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = self.0.to_string_lossy();
        if !text.chars().any(char::is_control) {
            return f.write_str(&text);
        }
        for c in text.chars() {
            if c.is_control() {
                write!(f, "{}", c.escape_default())?;
            } else {
                write!(f, "{c}")?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_escaped() {
        assert_eq!(shown(Path::new("a/b c.json")).to_string(), "a/b c.json");
        assert_eq!(
            shown(Path::new("evil\n\u{1b}[2Jname\t.png")).to_string(),
            "evil\\n\\u{1b}[2Jname\\t.png"
        );
        assert_eq!(shown(Path::new("héllo.png")).to_string(), "héllo.png");
    }
}

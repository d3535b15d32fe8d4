//! The summary of a batch: totals, and one row per scene as CSV or JSON.

use std::ffi::OsString;
use std::fmt::Write as _;
use std::path::Path;

use super::run::{SceneRow, Status};

/// Counts of rows by status.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Totals {
    pub scenes: usize,
    pub ok: usize,
    pub failed: usize,
    pub over_threshold: usize,
}

impl Totals {
    /// The counts of `rows`.
    pub fn of(rows: &[SceneRow]) -> Totals {
        let mut t = Totals {
            scenes: rows.len(),
            ..Totals::default()
        };
        for row in rows {
            match row.status {
                Status::Ok => t.ok += 1,
                Status::Failed => t.failed += 1,
                Status::OverThreshold => t.over_threshold += 1,
            }
        }
        t
    }
}

/// The summary's columns; the last four only when comparing.
pub const COLUMNS: [&str; 14] = [
    "scene",
    "output",
    "status",
    "error",
    "width",
    "height",
    "spp",
    "seconds",
    "rays",
    "warnings",
    "reference",
    "mse",
    "flip",
    "pass",
];

/// A summary value.
enum Value {
    Text(Option<String>),
    Number(Option<f64>),
    Count(Option<u64>),
    Bool(Option<bool>),
}

/// A path as the summary writes it (lossy where it is not Unicode).
fn path_text(p: &Path) -> String {
    p.to_string_lossy().into_owned()
}

/// The values of a row, column by column (see [`COLUMNS`]).
fn row_values(row: &SceneRow, comparing: bool) -> Vec<Value> {
    let mut v = vec![
        Value::Text(Some(path_text(&row.scene))),
        Value::Text(row.output.as_deref().map(path_text)),
        Value::Text(Some(row.status.name().to_string())),
        Value::Text(row.error.clone()),
        Value::Count(row.width.map(u64::from)),
        Value::Count(row.height.map(u64::from)),
        Value::Count(row.spp.map(u64::from)),
        Value::Number(row.seconds.map(|s| (s * 1e4).round() / 1e4)),
        Value::Count(row.rays),
        Value::Count(Some(row.warnings.len() as u64)),
    ];
    if comparing {
        let c = row.comparison.clone().unwrap_or_default();
        v.push(Value::Text(c.reference.as_deref().map(path_text)));
        v.push(Value::Number(c.mse));
        v.push(Value::Number(c.flip));
        v.push(Value::Bool(c.pass));
    }
    v
}

/// A number as the CSV writes it: `NaN` for not a number, else as `{x}` formats it.
fn number_text(x: f64) -> String {
    if x.is_nan() {
        "NaN".into()
    } else {
        format!("{x}")
    }
}

/// A text cell of the summary. One that starts with `=`, `+`, `-`, `@`, a tab or a carriage
/// return gets a leading `'`, so that a spreadsheet shows it as text rather than running it as a
/// formula (OWASP, "CSV Injection"): scene names and error messages come from students' files.
fn csv_field(text: &str) -> String {
    let guarded;
    let text = if text.starts_with(['=', '+', '-', '@', '\t', '\r']) {
        guarded = format!("'{text}");
        guarded.as_str()
    } else {
        text
    };
    if text.contains([',', '"', '\n', '\r']) || text.starts_with(' ') || text.ends_with(' ') {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// The summary as CSV (RFC 4180: fields with commas, quotes, line breaks or edge spaces quoted,
/// quotes doubled; CRLF line ends), a header line first. Empty fields for values that do not
/// apply; `NaN` where a metric has no value.
pub fn csv(rows: &[SceneRow], comparing: bool) -> String {
    let n = if comparing { COLUMNS.len() } else { 10 };
    let mut out = COLUMNS[..n].join(",");
    out.push_str("\r\n");
    for row in rows {
        let fields: Vec<String> = row_values(row, comparing)
            .into_iter()
            .map(|v| match v {
                Value::Text(t) => csv_field(t.as_deref().unwrap_or("")),
                Value::Number(x) => x.map(number_text).unwrap_or_default(),
                Value::Count(x) => x.map(|x| x.to_string()).unwrap_or_default(),
                Value::Bool(b) => b.map(|b| b.to_string()).unwrap_or_default(),
            })
            .collect();
        out.push_str(&fields.join(","));
        out.push_str("\r\n");
    }
    out
}

/// `text` as a JSON string literal.
pub fn json_string(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x20 || c == '\u{2028}' || c == '\u{2029}' => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// The summary as JSON: `{"totals": {...}, "scenes": [{column: value, ...}, ...]}` with the
/// columns of [`csv`]; `null` for values that do not apply or are not numbers.
pub fn json(rows: &[SceneRow], comparing: bool) -> String {
    let t = Totals::of(rows);
    let mut out = format!(
        "{{\n  \"totals\": {{\"scenes\": {}, \"ok\": {}, \"failed\": {}, \"over_threshold\": {}}},\n  \"scenes\": [",
        t.scenes, t.ok, t.failed, t.over_threshold
    );
    for (i, row) in rows.iter().enumerate() {
        out.push_str(if i == 0 { "\n    {" } else { ",\n    {" });
        for (j, (column, value)) in COLUMNS.iter().zip(row_values(row, comparing)).enumerate() {
            if j > 0 {
                out.push_str(", ");
            }
            let value = match value {
                Value::Text(t) => t.as_deref().map(json_string),
                Value::Number(x) => x.filter(|x| x.is_finite()).map(|x| format!("{x}")),
                Value::Count(x) => x.map(|x| x.to_string()),
                Value::Bool(b) => b.map(|b| b.to_string()),
            };
            let _ = write!(out, "\"{column}\": {}", value.as_deref().unwrap_or("null"));
        }
        out.push('}');
    }
    out.push_str(if rows.is_empty() {
        "]\n}\n"
    } else {
        "\n  ]\n}\n"
    });
    out
}

/// The summary format for `path`: CSV for `.csv`, JSON for `.json`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SummaryFormat {
    Csv,
    Json,
}

impl SummaryFormat {
    /// The format `path`'s extension names (without regard to case).
    pub fn from_path(path: &Path) -> Option<SummaryFormat> {
        let ext: OsString = path.extension()?.to_ascii_lowercase();
        match ext.to_str()? {
            "csv" => Some(SummaryFormat::Csv),
            "json" => Some(SummaryFormat::Json),
            _ => None,
        }
    }

    /// The summary of `rows` in this format; `comparing` adds the comparison's columns.
    pub fn write(self, rows: &[SceneRow], comparing: bool) -> String {
        match self {
            SummaryFormat::Csv => csv(rows, comparing),
            SummaryFormat::Json => json(rows, comparing),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::run::{Comparison, Images};
    use super::*;
    use std::path::PathBuf;

    fn row(error: Option<&str>) -> SceneRow {
        SceneRow {
            scene: PathBuf::from("dir, with comma/\"q\".json"),
            name: "q".into(),
            output: None,
            status: if error.is_some() {
                Status::Failed
            } else {
                Status::Ok
            },
            error: error.map(String::from),
            width: Some(4),
            height: Some(2),
            spp: None,
            seconds: Some(0.5),
            rays: Some(8),
            warnings: vec![],
            comparison: Some(Comparison {
                reference: None,
                mse: Some(f64::NAN),
                flip: Some(0.25),
                pass: Some(false),
            }),
            images: Images::default(),
        }
    }

    #[test]
    fn csv_text_that_a_spreadsheet_would_run_is_kept_as_text() {
        assert_eq!(csv_field("=HYPERLINK(\"x\")"), "\"'=HYPERLINK(\"\"x\"\")\"");
        assert_eq!(csv_field("@sum"), "'@sum");
        assert_eq!(csv_field("-2+3"), "'-2+3");
        assert_eq!(csv_field("scenes/a=b.json"), "scenes/a=b.json");
    }

    #[test]
    fn csv_quotes_what_needs_quoting() {
        let text = csv(&[row(Some("line 1\nline \"2\""))], true);
        let lines: Vec<&str> = text.split("\r\n").collect();
        assert_eq!(lines[0], COLUMNS.join(","));
        assert_eq!(
            lines[1],
            "\"dir, with comma/\"\"q\"\".json\",,failed,\"line 1\nline \"\"2\"\"\",4,2,,0.5,8,0,,NaN,0.25,false"
        );
        let plain = csv(&[row(None)], false);
        assert!(plain
            .starts_with("scene,output,status,error,width,height,spp,seconds,rays,warnings\r\n"));
    }

    #[test]
    fn json_escapes_strings_and_writes_null_for_missing_values() {
        let text = json(&[row(Some("bad \u{1b} \"x\"\\"))], true);
        assert!(text.contains(r#""error": "bad \u001b \"x\"\\""#), "{text}");
        assert!(
            text.contains(r#""mse": null, "flip": 0.25, "pass": false"#),
            "{text}"
        );
        assert!(
            text.contains(r#""totals": {"scenes": 1, "ok": 0, "failed": 1, "over_threshold": 0}"#)
        );
        assert_eq!(json(&[], false), "{\n  \"totals\": {\"scenes\": 0, \"ok\": 0, \"failed\": 0, \"over_threshold\": 0},\n  \"scenes\": []\n}\n");
    }

    #[test]
    fn error_lines_are_one_line_and_name_the_scene() {
        let mut r = row(Some("first\nsecond"));
        r.scene = PathBuf::from("s.json");
        assert_eq!(r.error_line().unwrap(), "s.json: first; second");
        r.error = Some("s.json:1:2: invalid JSON".into());
        assert_eq!(r.error_line().unwrap(), "s.json:1:2: invalid JSON");
    }
}

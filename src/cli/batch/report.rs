//! The batch's HTML report: one self-contained page (inline CSS, images as `data:` URIs, a few
//! lines of inline script for the full-size view; nothing fetched) with a card per scene, failures
//! first. Every string that comes from a file or a file name is escaped.

use std::fmt::Write as _;
use std::path::Path;

use super::run::{SceneRow, Status};
use super::summary::Totals;

/// What the page says about the batch as a whole.
#[derive(Debug, Clone, Default)]
pub struct ReportInfo {
    /// The reference folder, when comparing.
    pub reference_dir: Option<std::path::PathBuf>,
    pub max_flip: Option<f64>,
    /// The shared render options, in words (e.g. "spp 16, seed 0, tone map linear").
    pub settings: String,
}

/// `text` with `&`, `<`, `>`, `"` and `'` replaced by character references, for HTML text and
/// quoted attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// A path as [`escape`]d text (lossy where it is not Unicode).
fn escape_path(p: &Path) -> String {
    escape(&p.to_string_lossy())
}

/// Standard base64 (RFC 4648, with padding).
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= chunk.len() {
                out.push(ALPHABET[(n >> shift) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// `n` with thin spaces between thousands (1 234 567).
fn grouped(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push('\u{2009}');
        }
        out.push(c);
    }
    out
}

/// The label and CSS class of a row's status.
fn label(row: &SceneRow, judged: bool) -> (&'static str, &'static str) {
    match row.status {
        Status::Failed => ("failed", "failed"),
        Status::OverThreshold => ("over threshold", "over"),
        Status::Ok if judged => ("pass", "ok"),
        Status::Ok => ("ok", "ok"),
    }
}

/// The page's style sheet.
const STYLE: &str = r#"
:root { --bg: #f4f5f7; --card: #fff; --ink: #1d2330; --muted: #5d6675; --line: #dde1e7;
        --ok: #1f7a3d; --ok-bg: #e3f4e8; --over: #8a5300; --over-bg: #fff0d6;
        --failed: #b3261e; --failed-bg: #fde7e5; }
* { box-sizing: border-box; }
body { margin: 0; background: var(--bg); color: var(--ink);
       font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; }
header { padding: 20px 28px 14px; background: var(--card); border-bottom: 1px solid var(--line); }
h1 { margin: 0 0 4px; font-size: 22px; }
.meta { margin: 0; color: var(--muted); }
.totals { margin-top: 12px; display: flex; gap: 10px; align-items: center; flex-wrap: wrap; }
.pill { padding: 3px 12px; border-radius: 999px; font-weight: 600; }
.pill.ok { color: var(--ok); background: var(--ok-bg); }
.pill.over { color: var(--over); background: var(--over-bg); }
.pill.failed { color: var(--failed); background: var(--failed-bg); }
.filter { margin-left: auto; color: var(--muted); user-select: none; }
body:has(#failures-only:checked) .card.ok { display: none; }
main { padding: 18px 28px 40px; display: flex; flex-direction: column; gap: 14px; }
.card { background: var(--card); border: 1px solid var(--line); border-left: 6px solid var(--ok);
        border-radius: 8px; padding: 14px 18px; display: grid;
        grid-template-columns: minmax(260px, 330px) 1fr; gap: 18px; }
.card.over { border-left-color: #e09b2d; }
.card.failed { border-left-color: var(--failed); }
.card h2 { margin: 0; font-size: 16px; overflow-wrap: anywhere; }
.path { color: var(--muted); font-size: 12px; overflow-wrap: anywhere; margin: 2px 0 8px; }
.badge { display: inline-block; font-size: 11px; font-weight: 700; text-transform: uppercase;
         letter-spacing: .04em; padding: 1px 8px; border-radius: 4px; margin-bottom: 6px; }
.ok .badge { color: var(--ok); background: var(--ok-bg); }
.over .badge { color: var(--over); background: var(--over-bg); }
.failed .badge { color: var(--failed); background: var(--failed-bg); }
table { border-collapse: collapse; }
td { padding: 1px 14px 1px 0; vertical-align: top; }
td:first-child { color: var(--muted); }
td.num { font-variant-numeric: tabular-nums; }
.error { margin: 6px 0 0; padding: 6px 10px; border-radius: 4px; background: var(--failed-bg);
         color: var(--failed); font: 12px/1.4 ui-monospace, SFMono-Regular, Menlo, monospace;
         white-space: pre-wrap; overflow-wrap: anywhere; }
.over .error { background: var(--over-bg); color: var(--over); }
details { margin-top: 6px; color: var(--muted); font-size: 12px; }
details ul { margin: 4px 0; padding-left: 18px; overflow-wrap: anywhere; }
.images { display: grid; grid-template-columns: repeat(3, minmax(0, 340px)); gap: 14px;
          align-items: start; }
figure { margin: 0; min-width: 0; }
figure img { width: 100%; height: auto; display: block; background: #000; cursor: zoom-in;
             border: 1px solid var(--line); border-radius: 3px; }
figure img.small { image-rendering: pixelated; }
figcaption { color: var(--muted); font-size: 12px; margin-top: 3px; }
.none { aspect-ratio: 4 / 3; display: flex; align-items: center; justify-content: center;
        border: 1px dashed var(--line); border-radius: 3px; color: var(--muted); font-size: 12px;
        text-align: center; padding: 8px; }
#zoom { position: fixed; inset: 0; background: rgba(10, 12, 16, .88); display: flex;
        align-items: center; justify-content: center; cursor: zoom-out; }
#zoom[hidden] { display: none; }
@media (max-width: 900px) { .card { grid-template-columns: 1fr; } }
#zoom img { width: 92vw; height: 92vh; object-fit: contain; image-rendering: pixelated; }
"#;

/// The page's script: a click on an image shows it full size, a click or Escape closes it.
const SCRIPT: &str = r#"
document.addEventListener('click', function (e) {
  var zoom = document.getElementById('zoom');
  if (e.target.matches('figure img')) {
    zoom.firstElementChild.src = e.target.src;
    zoom.hidden = false;
  } else if (!zoom.hidden) {
    zoom.hidden = true;
  }
});
document.addEventListener('keydown', function (e) {
  if (e.key === 'Escape') document.getElementById('zoom').hidden = true;
});
"#;

/// Images narrower than this are drawn with square pixels when scaled up.
const SMALL: u32 = 340;

/// An image (`png`, inline) with its caption, or a box saying it is `missing`; `width` is the
/// image's, for small images' square pixels.
fn figure(out: &mut String, png: Option<&[u8]>, caption: &str, missing: &str, width: Option<u32>) {
    out.push_str("<figure>");
    match png {
        Some(bytes) => {
            let class = if width.is_some_and(|w| w < SMALL) {
                " class=\"small\""
            } else {
                ""
            };
            let _ = write!(
                out,
                "<img{class} alt=\"{caption}\" title=\"click for full size\" src=\"data:image/png;base64,{}\">",
                base64(bytes)
            );
        }
        None => {
            let _ = write!(out, "<div class=\"none\">{missing}</div>");
        }
    }
    let _ = write!(out, "<figcaption>{caption}</figcaption></figure>");
}

/// A row of a card's table: `name` and its `value`.
fn info_row(out: &mut String, name: &str, value: &str) {
    let _ = write!(
        out,
        "<tr><td>{name}</td><td class=\"num\">{value}</td></tr>"
    );
}

/// A scene's card: its status, name and path, its facts, its error and warnings, and its
/// images.
fn card(out: &mut String, row: &SceneRow, info: &ReportInfo) {
    let judged = info.max_flip.is_some();
    let (text, class) = label(row, judged);
    let _ = write!(
        out,
        "<article class=\"card {class}\"><div class=\"info\"><span class=\"badge\">{text}</span>\
         <h2>{}</h2><div class=\"path\">{}</div><table>",
        escape(&row.name),
        escape_path(&row.scene)
    );
    facts(out, row, info);
    out.push_str("</table>");
    if let Some(error) = &row.error {
        let _ = write!(out, "<p class=\"error\">{}</p>", escape(error));
    }
    if !row.warnings.is_empty() {
        let n = row.warnings.len();
        let s = if n == 1 { "" } else { "s" };
        let _ = write!(out, "<details><summary>{n} warning{s}</summary><ul>");
        for w in &row.warnings {
            let _ = write!(out, "<li>{}</li>", escape(w));
        }
        out.push_str("</ul></details>");
    }
    out.push_str("</div><div class=\"images\">");
    images(out, row);
    out.push_str("</div></article>\n");
}

/// The rows of a card's table: the comparison's metrics, size, samples, time, rays and files.
fn facts(out: &mut String, row: &SceneRow, info: &ReportInfo) {
    if let Some(c) = &row.comparison {
        let number = |x: Option<f64>, f: &dyn Fn(f64) -> String| x.map(f).unwrap_or("–".into());
        info_row(out, "MSE", &number(c.mse, &|m| format!("{m:.3e}")));
        let flip = number(c.flip, &|f| format!("{f:.4}"));
        let flip = match info.max_flip {
            Some(max) => format!("{flip} (max {max})"),
            None => flip,
        };
        info_row(out, "mean FLIP", &flip);
    }
    if let (Some(w), Some(h)) = (row.width, row.height) {
        info_row(out, "size", &format!("{w}×{h}"));
    }
    if let Some(spp) = row.spp {
        info_row(out, "spp", &spp.to_string());
    }
    if let Some(s) = row.seconds {
        info_row(out, "time", &format!("{s:.3} s"));
    }
    if let Some(rays) = row.rays {
        info_row(out, "rays", &grouped(rays));
    }
    if let Some(output) = &row.output {
        info_row(out, "image", &escape_path(output));
    }
    if let Some(Some(reference)) = row.comparison.as_ref().map(|c| c.reference.as_ref()) {
        info_row(out, "reference", &escape_path(reference));
    }
}

/// A card's figures: the render and, when comparing, the reference and the FLIP heat map (or
/// why each is missing).
fn images(out: &mut String, row: &SceneRow) {
    let no_render = if row.status == Status::Failed && row.output.is_none() {
        "not rendered"
    } else {
        "no image"
    };
    figure(
        out,
        row.images.render.as_deref(),
        "render",
        no_render,
        row.width,
    );
    if row.comparison.is_some() {
        let found = row
            .comparison
            .as_ref()
            .is_some_and(|c| c.reference.is_some());
        figure(
            out,
            row.images.reference.as_deref(),
            "reference",
            if found {
                "not compared"
            } else {
                "no reference"
            },
            row.width,
        );
        figure(
            out,
            row.images.heat.as_deref(),
            "FLIP error (black 0, yellow 1)",
            "not compared",
            row.width,
        );
    }
}

/// The order of the cards: failed, then over the threshold (worst first), then the rest, each
/// in batch order.
fn order(rows: &[SceneRow]) -> Vec<&SceneRow> {
    let mut sorted: Vec<&SceneRow> = rows.iter().collect();
    sorted.sort_by(|a, b| {
        a.status.cmp(&b.status).then_with(|| {
            if a.status == Status::OverThreshold {
                let flip = |r: &SceneRow| r.comparison.as_ref().and_then(|c| c.flip).unwrap_or(0.0);
                flip(b).total_cmp(&flip(a))
            } else {
                std::cmp::Ordering::Equal
            }
        })
    });
    sorted
}

/// The report page for `rows`.
pub fn html(rows: &[SceneRow], info: &ReportInfo) -> String {
    let t = Totals::of(rows);
    let judged = info.max_flip.is_some();
    let mut out = String::new();
    let title = format!(
        "Render report: {} scene{}, {} failed",
        t.scenes,
        if t.scenes == 1 { "" } else { "s" },
        t.failed + t.over_threshold
    );
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{title}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<header>\n\
         <h1>Render report</h1>\n"
    );
    let mut meta = Vec::new();
    if let Some(dir) = &info.reference_dir {
        meta.push(format!("compared with {}", escape_path(dir)));
    }
    if let Some(max) = info.max_flip {
        meta.push(format!("pass: mean FLIP ≤ {max}"));
    }
    if !info.settings.is_empty() {
        meta.push(escape(&info.settings));
    }
    let _ = writeln!(out, "<p class=\"meta\">{}</p>", meta.join(" · "));
    let passed = if judged { "passed" } else { "rendered" };
    let _ = write!(
        out,
        "<div class=\"totals\"><strong>{} scene{}</strong>\
         <span class=\"pill ok\">{} {passed}</span>",
        t.scenes,
        if t.scenes == 1 { "" } else { "s" },
        t.ok
    );
    if judged || t.over_threshold > 0 {
        let _ = write!(
            out,
            "<span class=\"pill over\">{} over threshold</span>",
            t.over_threshold
        );
    }
    let _ = write!(
        out,
        "<span class=\"pill failed\">{} failed</span>\
         <label class=\"filter\"><input type=\"checkbox\" id=\"failures-only\"> failures only</label>\
         </div>\n</header>\n<main>\n",
        t.failed
    );
    for row in order(rows) {
        card(&mut out, row, info);
    }
    let _ = write!(
        out,
        "</main>\n<div id=\"zoom\" hidden><img alt=\"full size\"></div>\n<script>{SCRIPT}</script>\n</body>\n</html>\n"
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::batch::run::{Comparison, Images};
    use std::path::PathBuf;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
        assert_eq!(base64(&[0xff, 0xfe, 0xfd]), "//79");
    }

    #[test]
    fn names_and_errors_are_escaped_and_failures_come_first() {
        let row = |name: &str, status: Status, error: Option<&str>| SceneRow {
            scene: PathBuf::from(format!("{name}.json")),
            name: name.into(),
            output: None,
            status,
            error: error.map(String::from),
            width: Some(8),
            height: Some(8),
            spp: Some(1),
            seconds: Some(0.01),
            rays: Some(1234567),
            warnings: vec!["<w>".into()],
            comparison: Some(Comparison {
                reference: None,
                mse: Some(0.0),
                flip: Some(0.0),
                pass: Some(status == Status::Ok),
            }),
            images: Images {
                render: Some(vec![1, 2, 3]),
                ..Images::default()
            },
        };
        let rows = [
            row("good", Status::Ok, None),
            row(
                "<script>alert(1)</script>",
                Status::Failed,
                Some("a & b <i>"),
            ),
        ];
        let info = ReportInfo {
            max_flip: Some(0.1),
            ..ReportInfo::default()
        };
        let page = html(&rows, &info);
        assert!(!page.contains("<script>alert"));
        assert!(page.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
        assert!(page.contains("a &amp; b &lt;i&gt;"));
        assert!(page.contains("&lt;w&gt;"));
        assert!(page.contains("data:image/png;base64,AQID"));
        assert!(page.contains("1\u{2009}234\u{2009}567"));
        let bad = page.find("alert(1)").unwrap();
        assert!(bad < page.find("<h2>good</h2>").unwrap());
        assert!(!page.contains("http://") && !page.contains("https://"));
    }
}

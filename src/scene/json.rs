//! A thin, location-aware view of a parsed JSON document. Parsing is lenient in the ways real
//! scene files need (`//` and `/* */` comments, trailing commas; jsonc-parser does it), and every
//! value keeps its place in the text so errors can name `file:line:column` and the JSON path.

use std::path::{Path, PathBuf};

use jsonc_parser::ast::{ObjectPropName, Value};
use jsonc_parser::common::Ranged;

use super::error::{Location, SceneError};
use crate::math::Vec3;

/// The text of a scene file and where its lines start.
pub struct Source<'t> {
    pub file: PathBuf,
    text: &'t str,
    line_starts: Vec<usize>,
}

impl<'t> Source<'t> {
    pub fn new(file: &Path, text: &'t str) -> Source<'t> {
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        Source {
            file: file.to_path_buf(),
            text,
            line_starts,
        }
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        let line = self.line_starts.partition_point(|&s| s <= offset).max(1);
        let start = self.line_starts[line - 1];
        let end = offset.min(self.text.len());
        let column = self
            .text
            .get(start..end)
            .map_or(end - start, |s| s.chars().count());
        (line, column + 1)
    }

    /// Parses the text into a value tree.
    pub fn parse(&self) -> Result<Value<'t>, SceneError> {
        let options = jsonc_parser::ParseOptions {
            allow_comments: true,
            allow_trailing_commas: true,
            allow_loose_object_property_names: false,
            allow_missing_commas: false,
            allow_single_quoted_strings: false,
            allow_hexadecimal_numbers: false,
            allow_unary_plus_numbers: true,
            allow_bare_decimal_point_numbers: true,
            allow_non_finite_numbers: true,
            allow_extended_string_escapes: false,
        };
        let parsed =
            jsonc_parser::parse_to_ast(self.text, &Default::default(), &options).map_err(|e| {
                let (line, column) = self.line_column(e.range().start);
                SceneError::Syntax {
                    file: self.file.clone(),
                    line,
                    column,
                    message: e.kind().to_string(),
                }
            })?;
        parsed.value.ok_or_else(|| SceneError::Syntax {
            file: self.file.clone(),
            line: 1,
            column: 1,
            message: "the file is empty".into(),
        })
    }
}

/// A value in the document with its JSON path.
#[derive(Clone)]
pub struct Node<'a, 't> {
    pub value: &'a Value<'t>,
    pub path: String,
    src: &'a Source<'t>,
}

impl<'a, 't> Node<'a, 't> {
    pub fn root(value: &'a Value<'t>, src: &'a Source<'t>) -> Node<'a, 't> {
        Node {
            value,
            path: String::new(),
            src,
        }
    }

    /// Where this value is.
    pub fn location(&self) -> Location {
        let (line, column) = self.src.line_column(self.value.start());
        Location {
            file: self.src.file.clone(),
            line,
            column,
            path: if self.path.is_empty() {
                "(root)".into()
            } else {
                self.path.clone()
            },
        }
    }

    /// An error at this value.
    pub fn error(&self, message: impl Into<String>) -> SceneError {
        SceneError::Invalid {
            location: self.location(),
            message: message.into(),
        }
    }

    fn child(&self, value: &'a Value<'t>, segment: String) -> Node<'a, 't> {
        let path = if self.path.is_empty() || segment.starts_with('[') {
            format!("{}{}", self.path, segment)
        } else {
            format!("{}.{}", self.path, segment)
        };
        Node {
            value,
            path,
            src: self.src,
        }
    }

    /// What kind of JSON value this is, for messages.
    pub fn kind(&self) -> &'static str {
        match self.value {
            Value::StringLit(_) => "a string",
            Value::NumberLit(_) => "a number",
            Value::BooleanLit(_) => "a boolean",
            Value::Object(_) => "an object",
            Value::Array(_) => "an array",
            Value::NullKeyword(_) => "null",
        }
    }

    pub fn is_object(&self) -> bool {
        matches!(self.value, Value::Object(_))
    }

    /// The member `key` of an object (exact spelling), or `None` if absent or not an object.
    pub fn get(&self, key: &str) -> Option<Node<'a, 't>> {
        let Value::Object(o) = self.value else {
            return None;
        };
        o.properties
            .iter()
            .find(|p| prop_name(&p.name) == key)
            .map(|p| self.child(&p.value, key.to_string()))
    }

    /// The first present member among `keys` (spellings of the same concept).
    pub fn get_any(&self, keys: &[&str]) -> Option<Node<'a, 't>> {
        keys.iter().find_map(|k| self.get(k))
    }

    /// Whether any of `keys` is present.
    pub fn has_any(&self, keys: &[&str]) -> bool {
        self.get_any(keys).is_some()
    }

    /// The object's members, in file order.
    pub fn members(&self) -> Vec<(String, Node<'a, 't>)> {
        match self.value {
            Value::Object(o) => o
                .properties
                .iter()
                .map(|p| {
                    let k = prop_name(&p.name).to_string();
                    (k.clone(), self.child(&p.value, k))
                })
                .collect(),
            _ => Vec::new(),
        }
    }

    /// The elements of an array.
    pub fn elements(&self) -> Result<Vec<Node<'a, 't>>, SceneError> {
        match self.value {
            Value::Array(a) => Ok(a
                .elements
                .iter()
                .enumerate()
                .map(|(i, v)| self.child(v, format!("[{i}]")))
                .collect()),
            _ => Err(self.error(format!("expected an array, found {}", self.kind()))),
        }
    }

    /// A finite number.
    pub fn f64(&self) -> Result<f64, SceneError> {
        match self.value {
            Value::NumberLit(n) => {
                let v: f64 = n
                    .value
                    .trim_start_matches('+')
                    .parse()
                    .map_err(|_| self.error(format!("'{}' is not a number", n.value)))?;
                if v.is_finite() {
                    Ok(v)
                } else {
                    Err(self.error(format!("{} is not a finite number", n.value)))
                }
            }
            _ => Err(self.error(format!("expected a number, found {}", self.kind()))),
        }
    }

    /// A finite number that also fits an `f32`.
    pub fn f32(&self) -> Result<f32, SceneError> {
        let v = self.f64()?;
        if v.abs() > f32::MAX as f64 {
            return Err(self.error(format!("{v} is too large (the limit is {:e})", f32::MAX)));
        }
        Ok(v as f32)
    }

    /// A whole number in `0..=u32::MAX` (written as an integer or as a float with no fraction).
    pub fn u32(&self) -> Result<u32, SceneError> {
        let v = self.f64()?;
        if v < 0.0 || v.fract() != 0.0 || v > u32::MAX as f64 {
            return Err(self.error(format!("expected a whole number ≥ 0, found {v}")));
        }
        Ok(v as u32)
    }

    /// A boolean (also `0`/`1`, and the strings "true"/"false").
    pub fn bool(&self) -> Result<bool, SceneError> {
        match self.value {
            Value::BooleanLit(b) => Ok(b.value),
            Value::NumberLit(_) => Ok(self.f64()? != 0.0),
            Value::StringLit(s) if s.value.eq_ignore_ascii_case("true") => Ok(true),
            Value::StringLit(s) if s.value.eq_ignore_ascii_case("false") => Ok(false),
            _ => Err(self.error(format!("expected true or false, found {}", self.kind()))),
        }
    }

    pub fn str(&self) -> Result<&'a str, SceneError> {
        match self.value {
            Value::StringLit(s) => Ok(s.value.as_ref()),
            _ => Err(self.error(format!("expected a string, found {}", self.kind()))),
        }
    }

    /// A 3-vector `[x, y, z]`.
    pub fn vec3(&self) -> Result<Vec3, SceneError> {
        let Value::Array(a) = self.value else {
            return Err(self.error(format!(
                "expected an array of 3 numbers, found {}",
                self.kind()
            )));
        };
        if a.elements.len() != 3 {
            return Err(self.error(format!(
                "expected an array of 3 numbers, found {} elements",
                a.elements.len()
            )));
        }
        let e = self.elements()?;
        Ok(Vec3::new(e[0].f32()?, e[1].f32()?, e[2].f32()?))
    }

    /// A colour: `[r, g, b]`, or one number for grey.
    pub fn color(&self) -> Result<Vec3, SceneError> {
        match self.value {
            Value::NumberLit(_) => Ok(Vec3::splat(self.f32()?)),
            _ => self.vec3(),
        }
    }

    /// A list of numbers.
    pub fn numbers(&self) -> Result<Vec<f64>, SceneError> {
        let Value::Array(a) = self.value else {
            return Err(self.error(format!(
                "expected an array of numbers, found {}",
                self.kind()
            )));
        };
        let mut out = Vec::with_capacity(a.elements.len());
        for (i, v) in a.elements.iter().enumerate() {
            match v {
                Value::NumberLit(_) => out.push(self.child(v, format!("[{i}]")).f64()?),
                _ => {
                    return Err(self
                        .child(v, format!("[{i}]"))
                        .f64()
                        .err()
                        .unwrap_or_else(|| self.error("expected a number")))
                }
            }
        }
        Ok(out)
    }
}

fn prop_name<'x>(name: &'x ObjectPropName<'_>) -> &'x str {
    match name {
        ObjectPropName::String(s) => s.value.as_ref(),
        ObjectPropName::Word(w) => w.value,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_line_column_and_path() {
        let text = "{\n  \"camera\": {\n    \"width\": \"wide\"\n  }\n}";
        let src = Source::new(Path::new("s.json"), text);
        let v = src.parse().unwrap();
        let root = Node::root(&v, &src);
        let w = root.get("camera").unwrap().get("width").unwrap();
        let e = w.u32().unwrap_err().to_string();
        assert_eq!(
            e,
            "s.json:3:14: camera.width: expected a number, found a string"
        );
    }

    #[test]
    fn comments_and_trailing_commas_are_accepted() {
        let text = "// a scene\n{ \"a\": [1, 2, 3,], /* note */ \"b\": 2, }";
        let src = Source::new(Path::new("s.json"), text);
        let v = src.parse().unwrap();
        let root = Node::root(&v, &src);
        assert_eq!(
            root.get("a").unwrap().vec3().unwrap(),
            Vec3::new(1.0, 2.0, 3.0)
        );
    }

    #[test]
    fn syntax_errors_have_a_position() {
        let src = Source::new(Path::new("bad.json"), "{\n \"a\": [1, 2\n}");
        match src.parse() {
            Err(SceneError::Syntax { line, .. }) => assert_eq!(line, 3),
            other => panic!("{other:?}"),
        }
        assert!(Source::new(Path::new("e.json"), "").parse().is_err());
    }

    #[test]
    fn non_finite_numbers_are_rejected_with_a_path() {
        let src = Source::new(Path::new("s.json"), "{\"r\": NaN, \"s\": 1e999}");
        let v = src.parse().unwrap();
        let root = Node::root(&v, &src);
        assert!(root
            .get("r")
            .unwrap()
            .f32()
            .unwrap_err()
            .to_string()
            .contains("r: NaN is not a finite"));
        assert!(root.get("s").unwrap().f32().is_err());
    }
}

//! A thin, location-aware view of a parsed JSON document. Parsing is lenient in the ways real
//! scene files need (`//` and `/* */` comments, trailing commas; jsonc-parser does it), and every
//! value keeps its place in the text so errors can name `file:line:column` and the JSON path.
//!
//! Costs stay linear in the size of the file whatever its shape: a member of an object with many
//! members is found through an index built once per object, and a column is counted from the
//! nearest of a fixed set of checkpoints rather than from the start of its line (a file can be one
//! line with a warning every few bytes). [`work_count`] counts the steps both take, so tests can
//! check that growth without timing anything.
//!
//! Every lookup is also recorded: for each object looked into, which of its members a lookup
//! returned and which names it was asked for. After a load, [`Node::unread_members`] lists the
//! members no lookup returned, so that keys the loader does not know can be reported without a
//! second list of every key (`scene::keys`).

use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::path::{Path, PathBuf};
use std::rc::Rc;

use jsonc_parser::ast::{ObjectProp, ObjectPropName, Value};
use jsonc_parser::common::Ranged;

use super::error::{Location, SceneError};
use crate::math::Vec3;

mod names;
pub use names::{folded_key, same_key, NameIndex};

/// Bytes between character-count checkpoints: a column costs at most this many byte reads on top
/// of a binary search over the line starts, and the table takes one `usize` per this many bytes.
const CHECKPOINT_BYTES: usize = 256;

/// Objects with at most this many members are searched member by member; larger ones get an
/// index on their first lookup. Most objects in scene files are this small, and a scan of them
/// costs less than building an index.
const LINEAR_LOOKUP_MAX: usize = 16;

/// Most distinct names recorded as asked of one object: it bounds the cost of each lookup's record
/// and each unread-key suggestion where the loader asks one key per element (`v0`, `v1`, … of a
/// counted mesh). The names asked first (the fixed keys of the object's kind) are kept.
const MOST_NAMES_ASKED: usize = 128;

thread_local! {
    static WORK: Cell<u64> = const { Cell::new(0) };
}

/// Steps taken on this thread so far by [`Source`] and [`Node`] lookups: bytes read to place
/// columns and build their checkpoints, member names compared, hashed or indexed. The count only
/// grows; take the difference around a load to see how its work grows with the input.
pub fn work_count() -> u64 {
    WORK.with(Cell::get)
}

/// Adds `steps` to [`work_count`]: for work done on the document outside this module.
pub(crate) fn work_count_add(steps: usize) {
    count_work(steps);
}

fn count_work(steps: usize) {
    WORK.with(|w| w.set(w.get().wrapping_add(steps as u64)));
}

/// Whether `b` continues a UTF-8 sequence (rather than starting a character).
fn is_continuation(b: u8) -> bool {
    b & 0xC0 == 0x80
}

fn count_chars(bytes: &[u8]) -> usize {
    count_work(bytes.len());
    bytes.iter().filter(|&&b| !is_continuation(b)).count()
}

/// A mixing hasher for keys made here from counters (never from positions or text in the file,
/// which a file could choose to collide; those use the standard library's keyed hash):
/// the SplitMix64 finaliser (Steele, Lea, Flood, "Fast splittable pseudorandom number
/// generators", OOPSLA 2014), which spreads consecutive integers over all bits.
#[derive(Default)]
struct Mix(u64);

impl Hasher for Mix {
    fn finish(&self) -> u64 {
        let mut z = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = self.0.rotate_left(8) ^ u64::from(b);
        }
    }
    fn write_u64(&mut self, n: u64) {
        self.0 ^= n;
    }
    fn write_usize(&mut self, n: usize) {
        self.0 ^= n as u64;
    }
}

type MixMap<K, V> = HashMap<K, V, BuildHasherDefault<Mix>>;

/// Which members of one object lookups returned: a bit per member, the first 64 inline.
struct Returned {
    low: u64,
    rest: Vec<u64>,
}

impl Returned {
    fn new(len: usize) -> Returned {
        Returned {
            low: 0,
            rest: vec![0; len.saturating_sub(64).div_ceil(64)],
        }
    }

    fn set(&mut self, i: usize) {
        match i.checked_sub(64) {
            None => self.low |= 1 << i,
            Some(j) => self.rest[j / 64] |= 1 << (j % 64),
        }
    }

    fn get(&self, i: usize) -> bool {
        match i.checked_sub(64) {
            None => self.low >> i & 1 != 0,
            Some(j) => self.rest[j / 64] >> (j % 64) & 1 != 0,
        }
    }
}

/// What lookups did with one object: the members they returned, and the set of names they
/// asked for (a state of [`AskedSets`]).
struct ObjectReads {
    returned: Returned,
    asked: u32,
}

/// Sets of names asked for, shared between objects: objects of one kind are asked the same names
/// in the same order, so each set is stored once. State 0 is the empty set; every other state is
/// its parent's set plus one name, at most [`MOST_NAMES_ASKED`] deep.
struct AskedSets {
    parent: Vec<u32>,
    name: Vec<u32>,
    depth: Vec<u32>,
    /// `(state << 32) | name` → the state after asking for `name`.
    next: MixMap<u64, u32>,
}

impl AskedSets {
    fn new() -> AskedSets {
        AskedSets {
            parent: vec![0],
            name: vec![u32::MAX],
            depth: vec![0],
            next: MixMap::default(),
        }
    }

    fn full(&self, state: u32) -> bool {
        self.depth[state as usize] as usize >= MOST_NAMES_ASKED
    }

    /// The state after asking `state`'s object for name `id`.
    fn add(&mut self, state: u32, id: u32) -> u32 {
        let key = u64::from(state) << 32 | u64::from(id);
        if let Some(&to) = self.next.get(&key) {
            return to;
        }
        // First time from this state: a name already in the set keeps it (a walk of at most
        // MOST_NAMES_ASKED steps, once per state and name).
        let mut at = state;
        while at != 0 && self.name[at as usize] != id {
            count_work(1);
            at = self.parent[at as usize];
        }
        let to = if at != 0 {
            state
        } else {
            self.parent.push(state);
            self.name.push(id);
            self.depth.push(self.depth[state as usize] + 1);
            self.name.len() as u32 - 1
        };
        self.next.insert(key, to);
        to
    }

    /// The names of `state`, in the order first asked.
    fn names(&self, mut state: u32) -> Vec<u32> {
        let mut out = Vec::new();
        while state != 0 {
            out.push(self.name[state as usize]);
            state = self.parent[state as usize];
        }
        out.reverse();
        out
    }
}

/// Entries in the cache of name positions by address: the keys the loader asks for are mostly
/// string constants, found there without hashing their text.
const NAME_CACHE: usize = 256;

/// The names any object was asked for, each once, and their positions.
struct Names {
    list: Vec<Box<str>>,
    index: NameIndex,
    /// (address, length, position) of recently asked names.
    by_address: Vec<(usize, usize, u32)>,
}

impl Names {
    fn new() -> Names {
        Names {
            list: Vec::new(),
            index: NameIndex::default(),
            by_address: vec![(0, usize::MAX, 0); NAME_CACHE],
        }
    }

    fn id(&mut self, name: &str) -> u32 {
        let address = name.as_ptr() as usize;
        let slot = (address >> 3 ^ name.len()) % NAME_CACHE;
        let (a, len, id) = self.by_address[slot];
        // The text is compared too: a string built at run time may reuse an address.
        if a == address && len == name.len() && *self.list[id as usize] == *name {
            return id;
        }
        let list = &self.list;
        let id = match self.index.find(name, |i| &list[i]) {
            Some(i) => i as u32,
            None => {
                self.index.push(name);
                self.list.push(name.into());
                self.list.len() as u32 - 1
            }
        };
        self.by_address[slot] = (address, name.len(), id);
        id
    }
}

/// A [`Node`]'s object has no [`ObjectReads`] slot yet.
const NO_SLOT: u32 = u32::MAX;

/// The text of a scene file and where its lines start.
pub struct Source<'t> {
    pub file: PathBuf,
    text: &'t str,
    line_starts: Vec<usize>,
    /// `checkpoints[k]`: the number of characters in the first `k × CHECKPOINT_BYTES` bytes.
    checkpoints: Vec<usize>,
    /// Member indexes of the large objects looked into so far, by the object's start offset.
    members: RefCell<HashMap<usize, NameIndex>>,
    /// What lookups did with each object looked into, and its slot there by the object's start
    /// offset.
    reads: RefCell<Vec<ObjectReads>>,
    slots: RefCell<HashMap<usize, u32>>,
    asked: RefCell<AskedSets>,
    names: RefCell<Names>,
}

impl<'t> Source<'t> {
    pub fn new(file: &Path, text: &'t str) -> Source<'t> {
        let line_starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        let mut checkpoints = Vec::with_capacity(text.len() / CHECKPOINT_BYTES + 2);
        let mut chars = 0;
        checkpoints.push(chars);
        for block in text.as_bytes().chunks(CHECKPOINT_BYTES) {
            chars += count_chars(block);
            checkpoints.push(chars);
        }
        Source {
            file: file.to_path_buf(),
            text,
            line_starts,
            checkpoints,
            members: RefCell::new(HashMap::new()),
            reads: RefCell::new(Vec::new()),
            slots: RefCell::new(HashMap::new()),
            asked: RefCell::new(AskedSets::new()),
            names: RefCell::new(Names::new()),
        }
    }

    /// Records a lookup of `key` in the object of `len` members that starts at byte `start`,
    /// and the member it returned; `slot` caches the object's place in the records.
    fn record(
        &self,
        slot: &Cell<u32>,
        start: usize,
        len: usize,
        key: &str,
        returned: Option<usize>,
    ) {
        count_work(1);
        let mut reads = self.reads.borrow_mut();
        let mut at = slot.get();
        if at == NO_SLOT {
            at = *self.slots.borrow_mut().entry(start).or_insert_with(|| {
                reads.push(ObjectReads {
                    returned: Returned::new(len),
                    asked: 0,
                });
                reads.len() as u32 - 1
            });
            slot.set(at);
        }
        let object = &mut reads[at as usize];
        if let Some(i) = returned {
            object.returned.set(i);
        }
        let mut asked = self.asked.borrow_mut();
        if !asked.full(object.asked) {
            let id = self.names.borrow_mut().id(key);
            object.asked = asked.add(object.asked, id);
        }
    }

    /// The number of characters before byte `offset` (at most the text's length).
    fn chars_before(&self, offset: usize) -> usize {
        let block = offset / CHECKPOINT_BYTES;
        let from = block * CHECKPOINT_BYTES;
        self.checkpoints[block] + count_chars(&self.text.as_bytes()[from..offset])
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        let line = self.line_starts.partition_point(|&s| s <= offset).max(1);
        let start = self.line_starts[line - 1];
        let end = offset.min(self.text.len());
        // An offset inside a character (which the parser never gives) counts bytes.
        let column = if self.text.is_char_boundary(end) {
            self.chars_before(end) - self.chars_before(start)
        } else {
            end - start
        };
        (line, column + 1)
    }

    /// The position of the first member spelled as `key` ([`same_key`]) in `props`, the members
    /// of the object that starts at byte `start` of this text.
    fn member_position(&self, start: usize, props: &[ObjectProp], key: &str) -> Option<usize> {
        if props.len() <= LINEAR_LOOKUP_MAX {
            let found = props.iter().position(|p| same_key(prop_name(&p.name), key));
            count_work(found.map_or(props.len(), |i| i + 1));
            return found;
        }
        let mut indexes = self.members.borrow_mut();
        indexes
            .entry(start)
            .or_insert_with(|| NameIndex::keys(props.iter().map(|p| prop_name(&p.name))))
            .find(key, |i| prop_name(&props[i].name))
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

/// A value in the document with its JSON path. Its value must come from its source's
/// [`Source::parse`].
#[derive(Clone)]
pub struct Node<'a, 't> {
    pub value: &'a Value<'t>,
    pub path: String,
    src: &'a Source<'t>,
    /// The object's place in its source's lookup records, once known.
    slot: Cell<u32>,
}

impl<'a, 't> Node<'a, 't> {
    pub fn root(value: &'a Value<'t>, src: &'a Source<'t>) -> Node<'a, 't> {
        Node {
            value,
            path: String::new(),
            src,
            slot: Cell::new(NO_SLOT),
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
        // Built by hand rather than with `format!`: this runs for every value the loader
        // looks at.
        let mut path = String::with_capacity(self.path.len() + 1 + segment.len());
        path.push_str(&self.path);
        if !(self.path.is_empty() || segment.starts_with('[')) {
            path.push('.');
        }
        path.push_str(&segment);
        Node {
            value,
            path,
            src: self.src,
            slot: Cell::new(NO_SLOT),
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

    /// The member `key` of an object, under any spelling of it ([`same_key`]), or `None` if
    /// absent or not an object. The member's path has the key as the file spells it.
    pub fn get(&self, key: &str) -> Option<Node<'a, 't>> {
        let Value::Object(o) = self.value else {
            return None;
        };
        let found = self.src.member_position(o.start(), &o.properties, key);
        self.src
            .record(&self.slot, o.start(), o.properties.len(), key, found);
        let p = &o.properties[found?];
        Some(self.child(&p.value, prop_name(&p.name).to_string()))
    }

    /// The key of this member as the file spells it (the last segment of its path), if it is a
    /// member of an object.
    pub fn key(&self) -> Option<&str> {
        let last = self.path.rsplit('.').next()?;
        (!last.is_empty() && !last.ends_with(']')).then_some(last)
    }

    /// The member `key` like [`Node::get`], but unrecorded: the lookup neither marks the member
    /// as read nor the object as looked into (for a look at an object that may never be used,
    /// like the `name` of a library material).
    pub fn peek(&self, key: &str) -> Option<Node<'a, 't>> {
        let Value::Object(o) = self.value else {
            return None;
        };
        let p = &o.properties[self.src.member_position(o.start(), &o.properties, key)?];
        Some(self.child(&p.value, prop_name(&p.name).to_string()))
    }

    /// The first present member among `keys` (spellings of the same concept). The other
    /// spellings count as asked for, so that a second spelling present beside the first is
    /// reported as such.
    pub fn get_any(&self, keys: &[&str]) -> Option<Node<'a, 't>> {
        let (i, node) = keys
            .iter()
            .enumerate()
            .find_map(|(i, k)| self.get(k).map(|n| (i, n)))?;
        if let Value::Object(o) = self.value {
            for k in &keys[i + 1..] {
                self.src
                    .record(&self.slot, o.start(), o.properties.len(), k, None);
            }
        }
        Some(node)
    }

    /// Marks the members among `keys` as read without reading them: for keys that the loader
    /// reads only in some modes (a texture in `rendermode: binary`), which are known in all.
    pub fn mark_read(&self, keys: &[&str]) {
        for k in keys {
            let _ = self.get(k);
        }
    }

    /// Whether any of `keys` is present, without counting any as read (for choosing between
    /// forms whose keys are then read by the form chosen).
    pub fn contains_any(&self, keys: &[&str]) -> bool {
        keys.iter().any(|k| self.peek(k).is_some())
    }

    /// Whether any of `keys` is present. Every one present counts as read: the loader decides
    /// something from them all.
    pub fn has_any(&self, keys: &[&str]) -> bool {
        let mut any = false;
        for k in keys {
            any |= self.get(k).is_some();
        }
        any
    }

    /// Marks every member read: for an object skipped as a whole, with a warning of its own.
    pub fn mark_all_read(&self) {
        if let Value::Object(o) = self.value {
            for (i, p) in o.properties.iter().enumerate() {
                let key = prop_name(&p.name);
                self.src
                    .record(&self.slot, o.start(), o.properties.len(), key, Some(i));
            }
        }
    }

    /// The object's members, in file order (each counts as read).
    pub fn members(&self) -> Vec<(String, Node<'a, 't>)> {
        match self.value {
            Value::Object(o) => o
                .properties
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let k = prop_name(&p.name).to_string();
                    self.src
                        .record(&self.slot, o.start(), o.properties.len(), &k, Some(i));
                    (k.clone(), self.child(&p.value, k))
                })
                .collect(),
            _ => Vec::new(),
        }
    }

    /// The members no lookup returned ([`Node::peek`] does not count), in file order, of every
    /// object under this value that some lookup looked into; nothing inside an unread member is
    /// searched. Only the unread members' paths are spelled out (each place links to its
    /// parent), so the walk is linear in the document's size however deeply it nests.
    pub fn unread_members(&self) -> Vec<Unread<'a, 't>> {
        #[derive(Clone, Copy)]
        enum Segment<'a> {
            Root,
            Index(usize),
            Key(&'a str),
        }
        let reads = self.src.reads.borrow();
        let slots = self.src.slots.borrow();
        let asked_sets = self.src.asked.borrow();
        let names = self.src.names.borrow();
        // (parent, segment) of each container on the way; `stack` holds positions in it.
        let mut places: Vec<(usize, Segment<'a>)> = vec![(0, Segment::Root)];
        let mut stack: Vec<(&'a Value<'t>, usize)> = vec![(self.value, 0)];
        // (byte offset of the member, place of its object, key, value, names asked of the object)
        type Found<'a, 't> = (usize, usize, &'a str, &'a Value<'t>, Rc<[Box<str>]>);
        let mut found: Vec<Found<'a, 't>> = Vec::new();
        while let Some((value, place)) = stack.pop() {
            count_work(1);
            match value {
                Value::Array(a) => {
                    for (i, v) in a.elements.iter().enumerate().rev() {
                        if matches!(v, Value::Array(_) | Value::Object(_)) {
                            places.push((place, Segment::Index(i)));
                            stack.push((v, places.len() - 1));
                        }
                    }
                }
                Value::Object(o) => {
                    let Some(&at) = slots.get(&o.start()) else {
                        continue;
                    };
                    let r = &reads[at as usize];
                    let mut asked: Option<Rc<[Box<str>]>> = None;
                    for (i, p) in o.properties.iter().enumerate().rev() {
                        count_work(1);
                        let key = prop_name(&p.name);
                        if r.returned.get(i) {
                            if matches!(p.value, Value::Array(_) | Value::Object(_)) {
                                places.push((place, Segment::Key(key)));
                                stack.push((&p.value, places.len() - 1));
                            }
                        } else {
                            let asked = asked
                                .get_or_insert_with(|| {
                                    asked_sets
                                        .names(r.asked)
                                        .iter()
                                        .map(|&id| names.list[id as usize].clone())
                                        .collect()
                                })
                                .clone();
                            found.push((p.start(), place, key, &p.value, asked));
                        }
                    }
                }
                _ => {}
            }
        }
        found.sort_by_key(|f| f.0);
        found
            .into_iter()
            .map(|(_, place, key, value, asked)| {
                let mut segments = vec![Segment::Key(key)];
                let mut at = place;
                while at != 0 {
                    let (parent, segment) = places[at];
                    segments.push(segment);
                    at = parent;
                }
                let mut path = self.path.clone();
                for segment in segments.iter().rev() {
                    match segment {
                        Segment::Root => {}
                        Segment::Index(i) => path.push_str(&format!("[{i}]")),
                        Segment::Key(k) => {
                            if !path.is_empty() {
                                path.push('.');
                            }
                            path.push_str(k);
                        }
                    }
                }
                Unread {
                    key,
                    node: Node {
                        value,
                        path,
                        src: self.src,
                        slot: Cell::new(NO_SLOT),
                    },
                    asked,
                }
            })
            .collect()
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

/// A member that no lookup returned, in an object that some lookup looked into.
pub struct Unread<'a, 't> {
    pub key: &'a str,
    /// The member's value, with the member's path.
    pub node: Node<'a, 't>,
    /// The distinct names lookups asked the member's object for, in the order first asked
    /// (the first `MOST_NAMES_ASKED` of them).
    pub asked: Rc<[Box<str>]>,
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

    /// The column as counted from the start of its line, character by character.
    fn column_by_scanning(text: &str, offset: usize) -> (usize, usize) {
        let before = &text[..offset];
        let line = before.matches('\n').count() + 1;
        let start = before.rfind('\n').map_or(0, |i| i + 1);
        (line, text[start..offset].chars().count() + 1)
    }

    #[test]
    fn columns_from_checkpoints_match_counting_from_the_line_start() {
        // Long lines of one-, two-, three- and four-byte characters, so that lines, characters
        // and checkpoints straddle each other in every way.
        let mut text = String::new();
        for i in 0..2000 {
            text.push(['a', 'é', '€', '𝄞'][i % 4]);
            if i % 333 == 0 {
                text.push('\n');
            }
            if i % 700 == 0 {
                text.push_str("\n\n");
            }
        }
        let src = Source::new(Path::new("s.json"), &text);
        for offset in (0..=text.len()).filter(|&o| text.is_char_boundary(o)) {
            assert_eq!(
                src.line_column(offset),
                column_by_scanning(&text, offset),
                "offset {offset}"
            );
        }
        // Past the end, the column stops at the end of the last line.
        let end = src.line_column(text.len());
        assert_eq!(src.line_column(text.len() + 10), end);
    }

    #[test]
    fn large_objects_find_the_first_of_duplicate_keys() {
        let mut text = String::from("{");
        for i in 0..(3 * LINEAR_LOOKUP_MAX) {
            text.push_str(&format!("\"k{i}\": {i}, "));
        }
        text.push_str("\"k5\": 99, \"last\": 7}");
        let src = Source::new(Path::new("s.json"), &text);
        let v = src.parse().unwrap();
        let root = Node::root(&v, &src);
        assert_eq!(root.get("k5").unwrap().f64().unwrap(), 5.0);
        assert_eq!(root.get("last").unwrap().f64().unwrap(), 7.0);
        assert_eq!(root.get("k47").unwrap().path, "k47");
        assert!(root.get("k48").is_none());
        assert!(root.get("k").is_none());
    }

    #[test]
    fn unread_members_of_large_objects_and_the_names_asked_once_each() {
        let mut text = String::from("{\"inner\": {\"x\": 1, \"y\": 2}, ");
        for i in 0..100 {
            text.push_str(&format!("\"k{i}\": {i}, "));
        }
        text.push_str("\"skipped\": {\"z\": 3}}");
        let src = Source::new(Path::new("s.json"), &text);
        let v = src.parse().unwrap();
        let root = Node::root(&v, &src);
        for key in ["k70", "nope", "k70", "k3", "nope"] {
            let _ = root.get(key);
        }
        let inner = root.get("inner").unwrap();
        assert!(inner.peek("x").is_some());
        assert!(inner.get("y").is_some());
        let unread = root.unread_members();
        let paths: Vec<&str> = unread.iter().map(|u| u.node.path.as_str()).collect();
        // Every k but k3 and k70, in file order, then `skipped` (not searched inside); in
        // `inner`, `x` was only peeked at.
        assert_eq!(paths.len(), 1 + 98 + 1);
        assert_eq!(paths[0], "inner.x");
        assert_eq!(paths[1], "k0");
        assert!(!paths.contains(&"k3") && !paths.contains(&"k70"));
        assert_eq!(paths[99], "skipped");
        let asked: Vec<&str> = unread[1].asked.iter().map(|a| &**a).collect();
        assert_eq!(asked, ["k70", "nope", "k3", "inner"]);
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

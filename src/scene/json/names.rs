//! How member names are matched and found: keys compared without regard to case and
//! separators ([`same_key`]), and an index that finds a name in a long list without scanning it.

use std::collections::HashMap;
use std::hash::{BuildHasher, Hasher, RandomState};

use super::count_work;

/// Names mapped to their first position in a list, for lookups that must not scan it. Only a
/// hash of each name is kept, randomly keyed per process so no file can force collisions; a
/// collision falls back to reading the list in order. An index of keys ([`NameIndex::keys`])
/// matches names as [`same_key`] does, other indexes exactly.
#[derive(Default)]
pub struct NameIndex {
    hasher: RandomState,
    first: HashMap<u64, usize>,
    len: usize,
    fold: bool,
}

/// Whether two member names are spellings of the same key: equal once ASCII letters are
/// lowercased and the separators `_`, `-` and space are dropped (`focalDistance`,
/// `focal_distance`, `focaldistance` and `Focal-Distance` are one key).
pub fn same_key(a: &str, b: &str) -> bool {
    folded(a).eq(folded(b))
}

/// `name` as [`same_key`] compares it: two names are one key when these are equal.
pub fn folded_key(name: &str) -> String {
    // Dropping ASCII bytes and lowercasing ASCII letters leaves valid UTF-8.
    String::from_utf8(folded(name).collect()).unwrap_or_default()
}

/// The bytes of `name` as [`same_key`] compares them.
fn folded(name: &str) -> impl Iterator<Item = u8> + '_ {
    name.bytes()
        .filter(|b| !matches!(b, b'_' | b'-' | b' '))
        .map(|b| b.to_ascii_lowercase())
}

impl NameIndex {
    /// An index of `names`; a name listed twice keeps its first position.
    pub fn new<'n>(names: impl ExactSizeIterator<Item = &'n str>) -> NameIndex {
        let mut index = NameIndex {
            first: HashMap::with_capacity(names.len()),
            ..NameIndex::default()
        };
        for name in names {
            index.push(name);
        }
        index
    }

    /// An index of the member names of an object, matched as [`same_key`] does.
    pub fn keys<'n>(names: impl ExactSizeIterator<Item = &'n str>) -> NameIndex {
        let mut index = NameIndex {
            first: HashMap::with_capacity(names.len()),
            fold: true,
            ..NameIndex::default()
        };
        for name in names {
            index.push(name);
        }
        index
    }

    fn hash(&self, name: &str) -> u64 {
        if self.fold {
            let mut h = self.hasher.build_hasher();
            folded(name).for_each(|b| h.write_u8(b));
            h.finish()
        } else {
            self.hasher.hash_one(name)
        }
    }

    fn matches(&self, a: &str, b: &str) -> bool {
        if self.fold {
            same_key(a, b)
        } else {
            a == b
        }
    }

    /// Adds `name` at the next position.
    pub fn push(&mut self, name: &str) {
        count_work(1);
        let h = self.hash(name);
        self.first.entry(h).or_insert(self.len);
        self.len += 1;
    }

    /// The first position of `name`, in the list whose name at position `i` is `name_at(i)`.
    pub fn find<'n>(&self, name: &str, name_at: impl Fn(usize) -> &'n str) -> Option<usize> {
        count_work(1);
        let i = *self.first.get(&self.hash(name))?;
        if self.matches(name_at(i), name) {
            return Some(i);
        }
        count_work(self.len);
        (0..self.len).find(|&j| self.matches(name_at(j), name))
    }
}

//! The fixed-capacity stack a BVH traversal keeps its deferred subtrees on.
//!
//! A traversal runs for every ray, and most rays push only a few entries, so zeroing a whole
//! `STACK_SIZE` array each time (what `[x; N]` costs) is not free: this stack leaves its slots
//! uninitialised until pushed. (They are built with an inline `const` block, which keeps the
//! compiler from turning the new stack into a memset of the whole struct.) The one `unsafe` read
//! is of a slot below `len`, which `push` wrote: the invariant is local to this type and checked
//! by its tests.

use std::mem::MaybeUninit;

/// A stack of at most `N` `Copy` entries, none of them initialised until pushed.
pub struct Stack<T: Copy, const N: usize> {
    slots: [MaybeUninit<T>; N],
    /// Entries `0..len` of `slots` are initialised.
    len: usize,
}

impl<T: Copy, const N: usize> Stack<T, N> {
    #[inline(always)]
    pub fn new() -> Self {
        Stack {
            slots: [const { MaybeUninit::uninit() }; N],
            len: 0,
        }
    }

    /// Pushes `v`. Panics when the stack holds `N` entries already (the tree builders bound
    /// every tree's depth so that a traversal never does).
    #[inline(always)]
    pub fn push(&mut self, v: T) {
        self.slots[self.len].write(v);
        self.len += 1;
    }

    /// The last entry pushed and not yet popped.
    #[inline(always)]
    pub fn pop(&mut self) -> Option<T> {
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        // SAFETY: `self.len` < the length before this pop, and every slot below that was written
        // by `push` (the only place `len` grows).
        Some(unsafe { self.slots[self.len].assume_init() })
    }

    #[inline(always)]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl<T: Copy, const N: usize> Default for Stack<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pops_in_reverse_order_of_pushes_then_none() {
        let mut s: Stack<(u32, f32), 4> = Stack::new();
        assert!(s.is_empty());
        assert_eq!(s.pop(), None);
        s.push((1, 1.5));
        s.push((2, 2.5));
        assert_eq!(s.pop(), Some((2, 2.5)));
        s.push((3, 3.5));
        s.push((4, 4.5));
        s.push((5, 5.5));
        assert_eq!(s.pop(), Some((5, 5.5)));
        assert_eq!(s.pop(), Some((4, 4.5)));
        assert_eq!(s.pop(), Some((3, 3.5)));
        assert_eq!(s.pop(), Some((1, 1.5)));
        assert_eq!(s.pop(), None);
        assert!(s.is_empty());
    }

    #[test]
    fn holds_exactly_its_capacity() {
        let mut s: Stack<u32, 3> = Stack::new();
        for i in 0..3 {
            s.push(i);
        }
        assert_eq!(s.pop(), Some(2));
        s.push(7);
        let full = std::panic::catch_unwind(move || {
            let mut s = s;
            s.push(8);
        });
        assert!(full.is_err(), "a fourth entry must not fit");
    }
}

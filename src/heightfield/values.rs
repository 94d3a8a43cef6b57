//! Values of a grid read as one slice, held in memory or mapped from a tile store: the walks
//! index either the same way, so a mapped map gives the same answers as one in memory, and a
//! clone shares the values instead of copying them.

use memmap2::Mmap;
use std::ops::Deref;
use std::sync::Arc;

/// A slice of `T` that is either owned or part of a file mapped read-only; cloning shares it.
pub struct Values<T: Copy + 'static> {
    /// The first value (dangling where there are none).
    ptr: *const T,
    len: usize,
    owner: Arc<Owner<T>>,
}

/// What keeps a [`Values`]' memory alive.
enum Owner<T> {
    Heap(Vec<T>),
    /// A mapping of which the values are a part (kept and measured, never read through: the
    /// values point into it).
    Map {
        mapping: Arc<Mmap>,
    },
}

// SAFETY: a `Values` is a shared slice of `T` whose memory its owner keeps alive and never
// moves (a `Vec`'s buffer stays where it is while the `Vec` is not grown; a mapping stays where
// it was mapped), so it is `Send` and `Sync` as `&[T]` is.
unsafe impl<T: Copy + Sync> Send for Values<T> {}
// SAFETY: as for `Send`.
unsafe impl<T: Copy + Sync> Sync for Values<T> {}

impl<T: Copy + 'static> Values<T> {
    /// Values held in memory.
    pub fn owned(values: Vec<T>) -> Self {
        let (ptr, len) = (values.as_ptr(), values.len());
        Values {
            ptr,
            len,
            owner: Arc::new(Owner::Heap(values)),
        }
    }

    /// The `len` values from byte `offset` of `map` on, or `None` where they would reach past
    /// its end or are not aligned for `T`.
    pub fn mapped(map: &Arc<Mmap>, offset: usize, len: usize) -> Option<Self> {
        let bytes = len.checked_mul(size_of::<T>())?;
        let end = offset.checked_add(bytes)?;
        let part = map.get(offset..end)?;
        let ptr = part.as_ptr().cast::<T>();
        if !ptr.is_aligned() {
            return None;
        }
        Some(Values {
            ptr,
            len,
            owner: Arc::new(Owner::Map {
                mapping: Arc::clone(map),
            }),
        })
    }

    /// The values, to change: this one's own where they are held in memory and not shared,
    /// else a copy made its own first.
    pub fn make_mut(&mut self) -> &mut [T] {
        if !matches!(Arc::get_mut(&mut self.owner), Some(Owner::Heap(_))) {
            *self = Values::owned(self.to_vec());
        }
        match Arc::get_mut(&mut self.owner) {
            Some(Owner::Heap(values)) => values.as_mut_slice(),
            // (Just made owned and unshared.)
            _ => &mut [],
        }
    }

    /// Whether the values are part of a mapped file rather than held in memory.
    pub fn is_mapped(&self) -> bool {
        matches!(*self.owner, Owner::Map { .. })
    }

    /// The length in bytes of the whole mapped file the values are part of, if they are.
    pub fn mapping_len(&self) -> Option<u64> {
        match &*self.owner {
            Owner::Map { mapping } => Some(mapping.len() as u64),
            Owner::Heap(_) => None,
        }
    }
}

impl<T: Copy + 'static> Deref for Values<T> {
    type Target = [T];
    #[inline(always)]
    fn deref(&self) -> &[T] {
        // SAFETY: `ptr` and `len` describe values the owner holds, alive while `self` is, and
        // aligned (see `owned`, `mapped`); they are only written through `make_mut`, which
        // takes `&mut self`. A mapped file is opened read-only and, as the tile store says, is
        // not to be changed while a map is open.
        unsafe { std::slice::from_raw_parts(self.ptr, self.len) }
    }
}

impl<T: Copy + 'static> Clone for Values<T> {
    fn clone(&self) -> Self {
        Values {
            ptr: self.ptr,
            len: self.len,
            owner: Arc::clone(&self.owner),
        }
    }
}

impl<T: Copy + std::fmt::Debug + 'static> std::fmt::Debug for Values<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self.owner {
            Owner::Heap(_) => write!(f, "Values({} in memory)", self.len),
            Owner::Map { .. } => write!(f, "Values({} mapped)", self.len),
        }
    }
}

impl<T: Copy + PartialEq + 'static> PartialEq for Values<T> {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl<T: Copy + Eq + 'static> Eq for Values<T> {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clone_shares_and_a_change_copies() {
        let mut a = Values::owned(vec![1u16, 2, 3]);
        let b = a.clone();
        assert_eq!(a.as_ptr(), b.as_ptr(), "shared");
        a.make_mut()[0] = 9;
        assert_eq!(*a, [9, 2, 3]);
        assert_eq!(*b, [1, 2, 3], "the clone keeps its values");
        let before = a.as_ptr();
        a.make_mut()[1] = 8;
        assert_eq!(a.as_ptr(), before, "an unshared change is in place");
        assert_eq!(*a, [9, 8, 3]);
    }

    #[test]
    fn mapped_values_are_read_from_the_file_and_checked() {
        let path = std::env::temp_dir().join(format!("values-{}.bin", std::process::id()));
        let bytes: Vec<u8> = [0u16, 7, 65535, 3]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        std::fs::write(&path, &bytes).unwrap();
        let file = std::fs::File::open(&path).unwrap();
        // SAFETY: the test's own file, not changed while mapped.
        let map = Arc::new(unsafe { Mmap::map(&file) }.unwrap());
        let values = Values::<u16>::mapped(&map, 2, 3).unwrap();
        assert!(values.is_mapped());
        assert_eq!(*values, [7, 65535, 3]);
        assert!(Values::<u16>::mapped(&map, 2, 4).is_none(), "past the end");
        assert!(Values::<u16>::mapped(&map, 1, 1).is_none(), "misaligned");
        let mut copy = values.clone();
        copy.make_mut()[0] = 1;
        assert_eq!(*copy, [1, 65535, 3]);
        assert_eq!(*values, [7, 65535, 3], "the file's values stay");
        std::fs::remove_file(&path).unwrap();
    }
}

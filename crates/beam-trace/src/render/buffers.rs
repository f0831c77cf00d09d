//! The large per-pixel buffers of a render, backed by huge pages where the system offers
//! them.
//!
//! A render writes tens of bytes of fresh records per pixel (box classes, samples, colours,
//! coverage, costs): about a hundred megabytes at 1024 × 1024, mostly in allocations the
//! allocator maps afresh, as it does every large one. The first write to each 4 KiB page of
//! them costs a page fault; on the machine measured that is about 0.45 ns per byte (15 ms
//! for 32 MiB), and a 2 MiB page costs a sixth of that for the same bytes (2.4 ms). On
//! Linux, where transparent huge pages are given on request (`madvise`, the usual default)
//! or always, [`with_room`] asks for them on the whole 2 MiB pages inside a large buffer;
//! elsewhere, or where they are off, it is `Vec::with_capacity` (where free memory is
//! fragmented, the kernel compacts it or gives small pages, as its `defrag` setting says).
//! A first render of a process maps all of these afresh: 1024 × 1024 renders of the CSG
//! models with two threads took 7 to 16 % less time (`docs/expr-benchmarks.md`); renders
//! that find memory freed by earlier ones in the allocator take the same time.

use rayon::prelude::*;

/// Buffers smaller than this are left as the allocator makes them (a huge page is 2 MiB).
const LARGE: usize = 4 << 20;

/// Buffers of [`filled`] from this size on are written in parallel.
const PARALLEL_FILL: usize = 256 << 10;

/// The size of a huge page where the system has them (x86-64; most ARM64 kernels).
#[cfg(target_os = "linux")]
const HUGE_PAGE: usize = 2 << 20;

/// An empty vector with room for `n` items; where that is large and the system offers
/// huge pages, its memory is backed by them (the vector is as `Vec::with_capacity` makes
/// it: only how its pages are mapped differs).
pub(super) fn with_room<T>(n: usize) -> Vec<T> {
    let v: Vec<T> = Vec::with_capacity(n);
    let bytes = v.capacity().saturating_mul(size_of::<T>());
    if bytes >= LARGE {
        advise_huge(v.as_ptr().cast(), bytes);
    }
    v
}

/// `n` copies of `value`, in a vector made by [`with_room`]; a large one is written in
/// parallel (its fresh pages are faulted in by every thread, not one).
pub(super) fn filled<T: Clone + Send + Sync>(n: usize, value: T) -> Vec<T> {
    let mut v = with_room(n);
    if n.saturating_mul(size_of::<T>()) >= PARALLEL_FILL {
        v.par_extend(rayon::iter::repeat_n(value, n));
    } else {
        v.resize(n, value);
    }
    v
}

/// Asks for huge pages on the whole huge pages inside the `len` bytes from `start`.
#[cfg(target_os = "linux")]
fn advise_huge(start: *const u8, len: usize) {
    let begin = (start as usize).next_multiple_of(HUGE_PAGE);
    let end = (start as usize).saturating_add(len) / HUGE_PAGE * HUGE_PAGE;
    if end > begin {
        // SAFETY: the range lies inside an allocation this process owns (the vector's
        // buffer, not yet written), and `MADV_HUGEPAGE` changes only how its pages are
        // backed, never their contents; where the kernel refuses (no transparent huge
        // pages), nothing changes.
        unsafe {
            libc::madvise(begin as *mut libc::c_void, end - begin, libc::MADV_HUGEPAGE);
        }
    }
}

/// Elsewhere the memory is left as the allocator maps it.
#[cfg(not(target_os = "linux"))]
fn advise_huge(_start: *const u8, _len: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    /// Small and large buffers have the room asked for and hold what is put in them, as
    /// plain vectors do.
    #[test]
    fn buffers_are_plain_vectors() {
        for n in [0, 10, 1 << 20, 3 << 20] {
            let mut v: Vec<u64> = with_room(n);
            assert!(v.is_empty() && v.capacity() >= n);
            v.extend((0..n as u64).map(|i| i * 3));
            assert!(v.iter().enumerate().all(|(i, &x)| x == 3 * i as u64));
            let w = filled(n, 7u32);
            assert!(w.len() == n && w.iter().all(|&x| x == 7));
        }
    }
}

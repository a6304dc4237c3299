//! Large buffers in huge pages. A first touch of a fresh 4 KiB page costs a page fault, which
//! on the machines measured here (virtual ones) took microseconds: a 2400×1800 film, a large
//! mesh's build buffers, were tens of thousands of faults, a tenth of a render's time. Asked
//! for before their first touch, the kernel backs them with 2 MiB pages where it can (Linux
//! transparent huge pages in `madvise` or `always` mode; elsewhere this is a no-op).

/// Huge pages: their size, and the smallest buffer worth advising.
const HUGE_PAGE: usize = 2 << 20;
const WORTH_ADVISING: usize = 2 * HUGE_PAGE;

/// A vector of `n` zeros (`T::default()` of a number type, or an array of them) in memory
/// advised as huge pages and not yet touched: the standard library asks the allocator for
/// zeroed memory (`calloc`), which for a large block is fresh from the kernel and not written,
/// so its pages are faulted in by whichever threads first write them (a film's tiles, an
/// image's rows), in parallel, instead of all at once by the thread that made it.
pub fn zeroed_vec<T: Clone + Default>(n: usize) -> Vec<T> {
    let v = vec![T::default(); n];
    advise_huge_pages(&v);
    v
}

/// Advises the kernel to back `v`'s allocated capacity (written or not) with huge pages: called
/// before the capacity is first written.
fn advise_huge_pages<T>(v: &Vec<T>) {
    let bytes = v.capacity() * size_of::<T>();
    if bytes < WORTH_ADVISING {
        return;
    }
    let start = v.as_ptr() as usize;
    // Only whole huge pages inside the allocation.
    let (first, end) = (
        start.next_multiple_of(HUGE_PAGE),
        (start + bytes) / HUGE_PAGE * HUGE_PAGE,
    );
    if end > first {
        advise(first, end - first);
    }
}

#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn advise(address: usize, len: usize) {
    // SAFETY: the range lies inside one live allocation of ours, and `MADV_HUGEPAGE` only
    // changes how the kernel backs it, never its contents. A kernel without transparent huge
    // pages refuses the advice, which changes nothing: the result is ignored.
    unsafe {
        libc::madvise(address as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
    }
}

#[cfg(not(target_os = "linux"))]
fn advise(_: usize, _: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zeroed_vector_holds_zeros_large_or_small() {
        for n in [0, 1, 3 * HUGE_PAGE / 4 + 17] {
            let v: Vec<[f32; 3]> = zeroed_vec(n);
            assert_eq!(v.len(), n);
            assert!(v.iter().all(|x| *x == [0.0; 3]));
        }
        let mut v: Vec<u64> = Vec::with_capacity(WORTH_ADVISING);
        advise_huge_pages(&v);
        v.extend(0..1000);
        assert_eq!(v[999], 999);
    }
}

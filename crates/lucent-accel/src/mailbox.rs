//! Mailboxes (Amanatides & Woo 1987): in a structure where one primitive sits in several
//! cells, a ray remembers which primitives it has tested so that each is tested once.
//!
//! A mailbox is an array of "last ray" stamps, one per primitive, and a per-query stamp. The
//! structures are shared between threads and queried through `&self`, so the arrays live in a
//! per-thread pool: a query takes one out, and puts it back when done (a query nested inside
//! another's leaf test, as with instancing, takes a second one).

use std::cell::RefCell;

/// Stamps of one thread's queries.
#[derive(Default)]
pub struct Mailbox {
    stamps: Vec<u32>,
    stamp: u32,
}

thread_local! {
    static POOL: RefCell<Vec<Mailbox>> = const { RefCell::new(Vec::new()) };
}

impl Mailbox {
    /// Runs `f` with a fresh mailbox for `primitives` primitives.
    pub fn with<R>(primitives: usize, f: impl FnOnce(&mut Mailbox) -> R) -> R {
        let mut mailbox = POOL.with(|p| p.borrow_mut().pop()).unwrap_or_default();
        mailbox.begin(primitives);
        let result = f(&mut mailbox);
        POOL.with(|p| p.borrow_mut().push(mailbox));
        result
    }

    fn begin(&mut self, primitives: usize) {
        if self.stamps.len() < primitives {
            self.stamps.resize(primitives, 0);
        }
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            // The stamps wrapped around: forget every old one.
            self.stamps.fill(0);
            self.stamp = 1;
        }
    }

    /// True the first time primitive `i` is seen by this query.
    #[inline]
    pub fn first_visit(&mut self, i: u32) -> bool {
        let slot = &mut self.stamps[i as usize];
        let first = *slot != self.stamp;
        *slot = self.stamp;
        first
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_primitive_is_new_once_per_query_and_queries_nest() {
        Mailbox::with(4, |m| {
            assert!(m.first_visit(2));
            assert!(!m.first_visit(2));
            Mailbox::with(4, |inner| assert!(inner.first_visit(2)));
            assert!(!m.first_visit(2));
        });
        Mailbox::with(4, |m| assert!(m.first_visit(2)));
    }
}

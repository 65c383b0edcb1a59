//! Work buffers of products that may run on several threads at once (the contact solves of an
//! envelope's cases share one body and one operator).

use std::sync::{Mutex, PoisonError};

/// The spare sets of work buffers of type `T` of a body or operator shared by threads: a
/// product takes a spare set, or makes one when every set is in use, and gives it back, so
/// that products never wait for each other, and one used by one thread keeps one set (its
/// hot loop allocates nothing). As many sets as products ran at once, at most.
#[derive(Debug)]
pub struct Spares<T> {
    spare: Mutex<Vec<T>>,
}

impl<T> Default for Spares<T> {
    /// No spare set: the first product makes one.
    fn default() -> Self {
        Self {
            spare: Mutex::new(vec![]),
        }
    }
}

impl<T> Spares<T> {
    /// One spare set.
    pub fn new(work: T) -> Self {
        Self {
            spare: Mutex::new(vec![work]),
        }
    }

    /// Runs `product` on a spare set (made by `make` when none is left) and keeps the set.
    /// The lock is held only to take and to give back, never during the product.
    pub fn with<R>(&self, make: impl FnOnce() -> T, product: impl FnOnce(&mut T) -> R) -> R {
        let taken = self.lock().pop();
        let mut work = taken.unwrap_or_else(make);
        let result = product(&mut work);
        self.lock().push(work);
        result
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<T>> {
        self.spare.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Products at once get a set each; afterwards the sets are kept, none is made again.
    #[test]
    fn products_at_once_get_a_set_each() {
        let spares = Spares::new(vec![0u8; 4]);
        let made = std::sync::atomic::AtomicUsize::new(0);
        let barrier = std::sync::Barrier::new(3);
        std::thread::scope(|s| {
            for _ in 0..3 {
                s.spawn(|| {
                    spares.with(
                        || {
                            made.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                            vec![0u8; 4]
                        },
                        |_| barrier.wait(),
                    );
                });
            }
        });
        assert_eq!(made.load(std::sync::atomic::Ordering::SeqCst), 2);
        assert_eq!(spares.lock().len(), 3);
        spares.with(|| unreachable!("a set is spare"), |w| w[0] = 1);
    }
}

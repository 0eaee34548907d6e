//! Parallel searches that produce lists: each fixed chunk of the items searched fills a
//! buffer of its own, kept from call to call, and the buffers are joined in chunk order,
//! so the list is the same for any number of threads and nothing is allocated once the
//! buffers have grown to what the cloth needs.

use crate::parallelism::Parallelism;
use rayon::prelude::*;

/// Items searched per chunk.
const ITEMS_PER_CHUNK: usize = 16;

#[derive(Debug, Clone)]
pub(crate) struct ChunkedSearch<T> {
    buffers: Vec<Vec<T>>,
}

impl<T> Default for ChunkedSearch<T> {
    fn default() -> Self {
        Self { buffers: Vec::new() }
    }
}

impl<T: Send + Copy> ChunkedSearch<T> {
    /// Calls `search(item, found)` for every item in `items`, on rayon's pool when `par` says so,
    /// and writes what they found, in item order, into `out` (cleared first).
    pub fn run<I: Copy + Sync>(
        &mut self,
        items: &[I],
        par: Parallelism,
        out: &mut Vec<T>,
        search: impl Fn(I, &mut Vec<T>) + Sync,
    ) {
        let chunks = items.len().div_ceil(ITEMS_PER_CHUNK);
        if self.buffers.len() < chunks {
            self.buffers.resize_with(chunks, Vec::new);
        }
        let run = |(chunk, buffer): (&[I], &mut Vec<T>)| {
            buffer.clear();
            for &i in chunk {
                search(i, buffer);
            }
        };
        let buffers = &mut self.buffers[..chunks];
        if par.is_rayon() {
            items
                .par_chunks(ITEMS_PER_CHUNK)
                .zip(buffers.par_iter_mut())
                .for_each(run);
        } else {
            items
                .chunks(ITEMS_PER_CHUNK)
                .zip(buffers.iter_mut())
                .for_each(run);
        }
        out.clear();
        for b in buffers.iter() {
            out.extend_from_slice(b);
        }
    }
}

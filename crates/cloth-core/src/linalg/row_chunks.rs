//! Parallel work over the rows of a vector or of a compressed-row array. Each row is
//! written by one task only, so results do not depend on the number of threads.

use crate::parallelism::Parallelism;

/// Rows per parallel task.
const ROWS_PER_TASK: usize = 512;

/// `f(i, &mut out[i])` for every row, on rayon's pool when `par` says so.
pub(crate) fn for_each_entry<T: Send>(out: &mut [T], par: Parallelism, f: impl Fn(usize, &mut T) + Sync) {
    let run = |(task, chunk): (usize, &mut [T])| {
        let first = task * ROWS_PER_TASK;
        for (k, entry) in chunk.iter_mut().enumerate() {
            f(first + k, entry);
        }
    };
    if par.is_rayon() {
        use rayon::prelude::*;
        out.par_chunks_mut(ROWS_PER_TASK).enumerate().for_each(run);
    } else {
        run((0, out));
    }
}

/// `f(r, first, values)` for every row `r` of `data` laid out by `row_ptr` (which starts at
/// 0), `values` being the row's part, the first of them at index `first`; on rayon's pool when
/// `par` says so. Rows have different lengths, so the split is by halves through
/// `rayon::join`, which keeps its jobs on the stack: nothing is allocated.
pub(crate) fn for_each_row<T: Send>(
    row_ptr: &[usize],
    data: &mut [T],
    par: Parallelism,
    f: impl Fn(usize, usize, &mut [T]) + Sync,
) {
    let n = row_ptr.len() - 1;
    let data = &mut data[..row_ptr[n]];
    if par.is_rayon() {
        split(row_ptr, 0, n, data, &f);
    } else {
        rows(row_ptr, 0, n, data, &f);
    }
}

fn split<T: Send>(
    row_ptr: &[usize],
    start: usize,
    end: usize,
    data: &mut [T],
    f: &(impl Fn(usize, usize, &mut [T]) + Sync),
) {
    if end - start <= ROWS_PER_TASK {
        return rows(row_ptr, start, end, data, f);
    }
    let mid = start + (end - start) / 2;
    let (left, right) = data.split_at_mut(row_ptr[mid] - row_ptr[start]);
    rayon::join(
        || split(row_ptr, start, mid, left, f),
        || split(row_ptr, mid, end, right, f),
    );
}

/// Rows `start..end`, whose values are `data`.
fn rows<T>(row_ptr: &[usize], start: usize, end: usize, data: &mut [T], f: &impl Fn(usize, usize, &mut [T])) {
    let base = row_ptr[start];
    for r in start..end {
        let (first, last) = (row_ptr[r], row_ptr[r + 1]);
        f(r, first, &mut data[first - base..last - base]);
    }
}

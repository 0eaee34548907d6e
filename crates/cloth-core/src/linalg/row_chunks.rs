//! Parallel work over rows of a compressed-row array whose rows have different lengths.

use std::ops::Range;

/// Calls `f(rows, values)` on groups of at most `rows_per_task` consecutive rows, `values`
/// being those rows' part of `data` (laid out by `row_ptr`, which starts at 0); the groups
/// run in parallel when `parallel`. Each group writes only its own rows, so the result
/// does not depend on the number of threads. The split is by `rayon::join`, which keeps
/// its jobs on the stack: nothing is allocated.
pub(crate) fn for_each_row_chunk<T: Send>(
    row_ptr: &[usize],
    data: &mut [T],
    rows_per_task: usize,
    parallel: bool,
    f: impl Fn(Range<usize>, &mut [T]) + Sync,
) {
    let n = row_ptr.len() - 1;
    let data = &mut data[..row_ptr[n]];
    if parallel {
        split(row_ptr, 0..n, data, rows_per_task.max(1), &f);
    } else {
        f(0..n, data);
    }
}

fn split<T: Send>(
    row_ptr: &[usize],
    rows: Range<usize>,
    data: &mut [T],
    rows_per_task: usize,
    f: &(impl Fn(Range<usize>, &mut [T]) + Sync),
) {
    if rows.len() <= rows_per_task {
        f(rows, data);
        return;
    }
    let mid = rows.start + rows.len() / 2;
    let (left, right) = data.split_at_mut(row_ptr[mid] - row_ptr[rows.start]);
    rayon::join(
        || split(row_ptr, rows.start..mid, left, rows_per_task, f),
        || split(row_ptr, mid..rows.end, right, rows_per_task, f),
    );
}

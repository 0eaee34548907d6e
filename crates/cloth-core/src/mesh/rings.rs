//! What lies within a few edges of a set of vertices.

/// `seeds` and all that lies within `rings` steps of them, a step going from an item to
/// those `neighbours` gives for it; sorted, each once.
pub fn within_rings<T, I>(mut seeds: Vec<T>, rings: usize, neighbours: impl Fn(T) -> I) -> Vec<T>
where
    T: Copy + Ord,
    I: IntoIterator<Item = T>,
{
    seeds.sort_unstable();
    seeds.dedup();
    let mut frontier = seeds.clone();
    for _ in 0..rings {
        let mut next: Vec<T> = frontier
            .iter()
            .flat_map(|&i| neighbours(i))
            .filter(|i| seeds.binary_search(i).is_err())
            .collect();
        if next.is_empty() {
            break;
        }
        next.sort_unstable();
        next.dedup();
        seeds.extend_from_slice(&next);
        seeds.sort_unstable();
        frontier = next;
    }
    seeds
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rings_along_a_path_reach_as_many_steps_each_way() {
        // A path 0 - 1 - ... - 9.
        let neighbours = |i: usize| [i.checked_sub(1), (i < 9).then_some(i + 1)].into_iter().flatten();
        assert_eq!(within_rings(vec![5], 0, neighbours), vec![5]);
        assert_eq!(within_rings(vec![5], 2, neighbours), vec![3, 4, 5, 6, 7]);
        assert_eq!(within_rings(vec![0, 9, 0], 1, neighbours), vec![0, 1, 8, 9]);
        assert_eq!(within_rings(vec![4], 20, neighbours), (0..10).collect::<Vec<_>>());
    }
}

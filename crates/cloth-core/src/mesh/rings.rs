//! What lies within a few edges of a set of vertices, and what is joined to what.

use super::ClothMesh;

/// Each vertex's neighbours along a mesh's edges, in compressed rows.
#[derive(Debug, Clone)]
pub struct Neighbours {
    start: Vec<usize>,
    list: Vec<usize>,
}

impl Neighbours {
    pub fn of(mesh: &ClothMesh) -> Self {
        let n = mesh.vertex_count();
        let mut start = vec![0; n + 1];
        for e in mesh.edges() {
            start[e[0] + 1] += 1;
            start[e[1] + 1] += 1;
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut cursor = start.clone();
        let mut list = vec![0; start[n]];
        for &[a, b] in mesh.edges() {
            list[cursor[a]] = b;
            cursor[a] += 1;
            list[cursor[b]] = a;
            cursor[b] += 1;
        }
        Self { start, list }
    }

    /// The vertices joined to vertex `i` by an edge.
    pub fn of_vertex(&self, i: usize) -> &[usize] {
        &self.list[self.start[i]..self.start[i + 1]]
    }

    /// `vertices` and those within `rings` edges of them, sorted, each once.
    pub fn around(&self, vertices: Vec<usize>, rings: usize) -> Vec<usize> {
        within_rings(vertices, rings, |i| self.of_vertex(i).iter().copied())
    }
}

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

/// Labels the items `0..n` by the connected part of the graph whose steps `neighbours`
/// gives, parts numbered from 0 in order of their first item.
pub fn components<I>(n: usize, neighbours: impl Fn(usize) -> I) -> Vec<usize>
where
    I: IntoIterator<Item = usize>,
{
    let mut label = vec![usize::MAX; n];
    let mut count = 0;
    let mut stack = Vec::new();
    for seed in 0..n {
        if label[seed] != usize::MAX {
            continue;
        }
        label[seed] = count;
        stack.push(seed);
        while let Some(i) = stack.pop() {
            for j in neighbours(i) {
                if label[j] == usize::MAX {
                    label[j] = count;
                    stack.push(j);
                }
            }
        }
        count += 1;
    }
    label
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

    #[test]
    fn parts_are_labelled_in_order_of_their_first_item() {
        // 0-2, 1-3-4, and 5 alone.
        let links: [&[usize]; 6] = [&[2], &[3], &[0], &[1, 4], &[3], &[]];
        assert_eq!(
            components(6, |i| links[i].iter().copied()),
            vec![0, 1, 0, 1, 1, 2]
        );
        assert!(components(0, |_| std::iter::empty()).is_empty());
    }

    #[test]
    fn a_grid_vertex_has_its_edge_neighbours_and_two_rings_reach_two_cells() {
        // 4 x 3 grid, diagonals one way: vertex 5 (second row, second column).
        let mesh = crate::GridBuilder::new(4, 3).size(0.3, 0.2).build().unwrap();
        let neighbours = Neighbours::of(&mesh);
        for i in 0..mesh.vertex_count() {
            let mut expected: Vec<usize> = mesh
                .edges()
                .iter()
                .filter_map(|e| (e[0] == i).then_some(e[1]).or((e[1] == i).then_some(e[0])))
                .collect();
            expected.sort_unstable();
            let mut got = neighbours.of_vertex(i).to_vec();
            got.sort_unstable();
            assert_eq!(got, expected, "vertex {i}");
        }
        assert_eq!(neighbours.around(vec![0], 0), vec![0]);
        assert_eq!(neighbours.around(vec![0, 0], 20), (0..12).collect::<Vec<_>>());
        let two = neighbours.around(vec![0], 2);
        assert!(
            two.contains(&2) && two.contains(&8) && !two.contains(&3),
            "{two:?}"
        );
    }
}

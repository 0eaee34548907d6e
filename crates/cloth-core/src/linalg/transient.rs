//! Couplings of a [`super::BlockSparse`] outside its fixed pattern, set anew each step: the
//! cloth's contacts with itself join particles the mesh does not. Each coupling is a
//! symmetric 3x3 `K` acting on a combination of a few nodes, `sum_k G_k x_{i_k}`, so it
//! adds `G_a^T K G_b` at every pair of its nodes `(i_a, i_b)`, gathered into compressed
//! rows (sorted by row and column, duplicates summed) for the products and for folding
//! into a pattern that holds them (see `linalg::multigrid::folded`). Every buffer is reused.

use crate::math::{Mat3, Vec3};

#[derive(Debug, Clone, Default)]
pub(super) struct Transient {
    stiffness: Vec<Mat3>,
    /// Coupling `c`'s terms are `terms[term_start[c]..term_start[c + 1]]`.
    term_start: Vec<usize>,
    terms: Vec<(u32, Mat3)>,
    /// The gathered blocks: row starts (`n + 1` of them, none before gathering), columns,
    /// values.
    row_ptr: Vec<usize>,
    cols: Vec<u32>,
    blocks: Vec<Mat3>,
    staged: Vec<(u32, u32, Mat3)>,
    /// Per row, a block bounding the couplings from above by the row's own (see
    /// [`Transient::smoother_block`]); `bounded` lists the rows that have one.
    bound: Vec<Mat3>,
    bounded: Vec<u32>,
    n: usize,
}

impl Transient {
    pub fn new(n: usize) -> Self {
        Self {
            n,
            term_start: vec![0],
            ..Self::default()
        }
    }

    /// Rows of the matrix.
    pub fn size(&self) -> usize {
        self.n
    }

    pub fn clear(&mut self) {
        for &r in &self.bounded {
            self.bound[r as usize] = Mat3::zeros();
        }
        self.bounded.clear();
        self.stiffness.clear();
        self.term_start.clear();
        self.term_start.push(0);
        self.terms.clear();
        self.row_ptr.clear();
    }

    pub fn is_empty(&self) -> bool {
        self.stiffness.is_empty()
    }

    pub fn add(&mut self, stiffness: Mat3, terms: impl IntoIterator<Item = (usize, Mat3)>) {
        for (i, g) in terms {
            debug_assert!(i < self.n);
            self.terms.push((i as u32, g));
        }
        self.term_start.push(self.terms.len());
        self.stiffness.push(stiffness);
    }

    /// Gathers the couplings into rows.
    pub fn finish(&mut self) {
        self.row_ptr.clear();
        if self.is_empty() {
            return;
        }
        self.staged.clear();
        if self.bound.len() != self.n {
            self.bound = vec![Mat3::zeros(); self.n];
        }
        for c in 0..self.stiffness.len() {
            let (k, terms) = (
                &self.stiffness[c],
                &self.terms[self.term_start[c]..self.term_start[c + 1]],
            );
            let total: f64 = terms.iter().map(|(_, g)| g.norm()).sum();
            for (a, ga) in terms {
                let gk = ga.transpose() * k;
                for (b, gb) in terms {
                    self.staged.push((*a, *b, gk * gb));
                }
                // (sum_a G_a y_a)^T K (sum_a G_a y_a) <= sum_a (S / |G_a|) y_a^T G_a^T K G_a y_a,
                // S = sum_b |G_b| (Cauchy-Schwarz with weights |G_a|).
                let norm = ga.norm();
                if norm > 0.0 {
                    let r = *a as usize;
                    if self.bound[r] == Mat3::zeros() {
                        self.bounded.push(*a);
                    }
                    self.bound[r] += (total / norm) * (gk * ga);
                }
            }
        }
        // By row and column (the blocks of coarse levels pile up on few rows), then with
        // duplicates summed.
        self.staged.sort_unstable_by_key(|&(r, c, _)| (r, c));
        let n = self.n;
        self.row_ptr.resize(n + 1, 0);
        self.cols.clear();
        self.blocks.clear();
        let mut last = None;
        for &(r, c, b) in &self.staged {
            if last == Some((r, c)) {
                *self.blocks.last_mut().expect("a block before") += b;
            } else {
                self.cols.push(c);
                self.blocks.push(b);
                self.row_ptr[r as usize + 1] += 1;
                last = Some((r, c));
            }
        }
        for r in 0..n {
            self.row_ptr[r + 1] += self.row_ptr[r];
        }
    }

    fn row(&self, r: usize) -> std::ops::Range<usize> {
        debug_assert!(
            self.is_empty() || !self.row_ptr.is_empty(),
            "couplings added but not gathered (finish)"
        );
        match self.row_ptr.get(r..r + 2) {
            Some(&[a, b]) => a..b,
            _ => 0..0,
        }
    }

    /// Row `r`'s gathered columns, sorted.
    pub fn row_columns(&self, r: usize) -> impl Iterator<Item = u32> + '_ {
        self.cols[self.row(r)].iter().copied()
    }

    /// Row `r`'s gathered blocks with their columns.
    pub fn row_blocks(&self, r: usize) -> impl Iterator<Item = (u32, &Mat3)> + '_ {
        let range = self.row(r);
        self.cols[range.clone()].iter().copied().zip(&self.blocks[range])
    }

    pub fn row_product(&self, r: usize, x: &[Vec3]) -> Vec3 {
        let mut s = Vec3::zeros();
        for k in self.row(r) {
            s += self.blocks[k] * x[self.cols[k] as usize];
        }
        s
    }

    /// Row `r`'s block of a block diagonal that bounds the couplings from above (in the
    /// positive semi-definite order): each coupling's own diagonal blocks scaled up by its
    /// spread over its terms. A Jacobi smoother on it damps every row, where the plain
    /// diagonal does poorly: a particle joined to a triangle near one of its corners puts
    /// only a small weight, squared, on the far corners' diagonal but that weight, not
    /// squared, off it, and `D^-1 A` then has a spectral radius far above two.
    pub fn smoother_block(&self, r: usize) -> Mat3 {
        self.bound.get(r).copied().unwrap_or_else(Mat3::zeros)
    }

    /// (row, column, block) of every gathered block, by row and column.
    pub fn blocks(&self) -> impl Iterator<Item = (usize, usize, &Mat3)> + '_ {
        (0..self.row_ptr.len().saturating_sub(1)).flat_map(move |r| {
            self.row(r)
                .map(move |k| (r, self.cols[k] as usize, &self.blocks[k]))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn couplings_are_gathered_into_sorted_rows_with_duplicates_summed() {
        let mut t = Transient::new(4);
        let i = Mat3::identity();
        let k = Mat3::from_diagonal_element(2.0);
        // A spring between nodes 2 and 0 and one between 2 and 3.
        t.add(k, [(2, i), (0, -i)]);
        t.add(k, [(2, i), (3, -i)]);
        t.finish();
        let got: Vec<_> = t.blocks().map(|(r, c, m)| (r, c, m[(0, 0)])).collect();
        assert_eq!(
            got,
            vec![
                (0, 0, 2.0),
                (0, 2, -2.0),
                (2, 0, -2.0),
                (2, 2, 4.0),
                (2, 3, -2.0),
                (3, 2, -2.0),
                (3, 3, 2.0)
            ]
        );
        // Each spring on two terms of weight one bounds its rows by twice its diagonal.
        assert_eq!(t.smoother_block(2), Mat3::from_diagonal_element(8.0));
        assert_eq!(t.smoother_block(0), Mat3::from_diagonal_element(4.0));
        assert_eq!(t.smoother_block(1), Mat3::zeros());
        let x = [Vec3::new(1.0, 0.0, 0.0); 4];
        assert_eq!(t.row_product(2, &x), Vec3::zeros());
        assert_eq!(t.stiffness.len(), 2);
        t.clear();
        t.finish();
        assert!(t.is_empty());
        assert_eq!(t.row_product(2, &x), Vec3::zeros());
    }
}

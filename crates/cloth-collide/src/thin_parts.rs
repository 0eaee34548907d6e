//! Which of a body's surface lies over its thin parts: the hands and forearms of a body in
//! an A pose, which GarmentCode's skirts are placed round and which cloth may pass (see
//! `cloth_core::PassThrough`).

use cloth_core::math::union_find::find;
use cloth_core::math::Vec3;

/// Where the body is thinner than this under its surface (along the inward normal), m,
/// it may be a thin part: a hand, a forearm, an ear, under a hand's width. The trunk, the
/// head, the thighs and the neck are thicker.
pub const THIN_PART: f64 = 0.1;

/// Per triangle, whether it lies over a thin part, given the body's chord under each
/// (see [`THIN_PART`]). A connected run of thin triangles is a thin part only if it
/// reaches above the middle of the thick parts' height along `up` (in the body's frame): limbs
/// hanging from the shoulders, ears. The shins and feet under a standing body are as thin
/// as a forearm, but they carry what dresses the legs: trousers resting on a foot must not
/// pass it (GarmentCode's simulator likewise lets skirts pass only the arms).
pub(crate) fn thin_triangles(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    chords: &[f64],
    up: &Vec3,
) -> Vec<bool> {
    let height = |v: u32| vertices[v as usize].dot(up);
    let narrow: Vec<bool> = chords.iter().map(|&c| c < THIN_PART).collect();
    let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
    for (t, _) in triangles.iter().zip(&narrow).filter(|(_, &n)| !n) {
        for &v in t {
            low = low.min(height(v));
            high = high.max(height(v));
        }
    }
    if low > high {
        // Thin all over (a plate, a lone hand): all of it is.
        return narrow;
    }
    let middle = 0.5 * (low + high);
    // Runs of thin triangles, joined through shared corners.
    let mut parent: Vec<u32> = (0..vertices.len() as u32).collect();
    for (t, _) in triangles.iter().zip(&narrow).filter(|(_, &n)| n) {
        let r = find(&mut parent, t[0]);
        for &v in &t[1..] {
            let s = find(&mut parent, v);
            parent[s as usize] = r;
        }
    }
    let mut top = vec![f64::NEG_INFINITY; vertices.len()];
    for (t, _) in triangles.iter().zip(&narrow).filter(|(_, &n)| n) {
        let r = find(&mut parent, t[0]) as usize;
        for &v in t {
            top[r] = top[r].max(height(v));
        }
    }
    triangles
        .iter()
        .zip(&narrow)
        .map(|(t, &n)| n && top[find(&mut parent, t[0]) as usize] > middle)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thin_runs_count_only_when_they_reach_above_the_middle() {
        // Three triangles apart: a thick one from z 0 to 2, a thin one up at 1.5 (an arm),
        // a thin one down at 0.2 (a foot).
        let vertices: Vec<Vec3> = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 2.0],
            [5.0, 0.0, 1.0],
            [6.0, 0.0, 1.0],
            [5.0, 0.0, 1.5],
            [5.0, 0.0, 0.0],
            [6.0, 0.0, 0.0],
            [5.0, 0.0, 0.2],
        ]
        .iter()
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect();
        let triangles = [[0, 1, 2], [3, 4, 5], [6, 7, 8]];
        let thin = thin_triangles(&vertices, &triangles, &[0.5, 0.05, 0.05], &Vec3::z());
        assert_eq!(thin, vec![false, true, false]);
        // With nothing thick, everything narrow is thin.
        let thin = thin_triangles(&vertices, &triangles, &[0.05, 0.05, 0.5], &Vec3::z());
        assert_eq!(thin, vec![true, true, false]);
        // A foot joined to the arm through a shared corner is part of it.
        let triangles = [[0, 1, 2], [3, 4, 5], [6, 7, 3]];
        let thin = thin_triangles(&vertices, &triangles, &[0.5, 0.05, 0.05], &Vec3::z());
        assert_eq!(thin, vec![false, true, true]);
        // Upside down, the foot is up and the arm down.
        let triangles = [[0, 1, 2], [3, 4, 5], [6, 7, 8]];
        let thin = thin_triangles(&vertices, &triangles, &[0.5, 0.05, 0.05], &-Vec3::z());
        assert_eq!(thin, vec![false, false, true]);
    }
}

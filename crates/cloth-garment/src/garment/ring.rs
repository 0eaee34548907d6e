//! The ring a seam closes. A seam held open with nothing between its sides is held by the
//! cloth round them: the sides of a sleeve's underarm seam are joined the other way round
//! the arm, through the sleeve and its top seam, and closing it asks that way round to
//! reach round the arm. That way, the shortest from one side of the open pair to the other
//! through the cloth and over the other seams' pairs (never over its own seam) that goes
//! round the body, is its ring: at rest as long as the cloth along it is cut, and now as
//! long as the cloth lies, plus the gaps of the pairs it crosses and the pair's own. Their
//! ratio is the stretch closing every seam asks of the ring, near enough: the cloth round a
//! limb lies near the shortest way round it. An open pair on the way costs its gap, as the
//! cloth that would have to span it. Where seams meet at a corner (a sleeve's underarm
//! seam, its cuff's and the cuff's own side seam), the shortest way turns round the corner
//! without going round the arm: such a way is passed over, and the next sought without the
//! seams it crossed.

use super::Garment;
use cloth_core::math::Vec3;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The ring through an open pair (see the module's note).
#[derive(Debug, Clone, PartialEq)]
pub struct Ring {
    /// Its length in the flat cloth, m.
    pub rest: f64,
    /// Its length as the cloth lies, plus the pair's gap, m.
    pub now: f64,
    /// The panels it runs through, each once, from the pair's first side.
    pub panels: Vec<String>,
    /// Its particles, from the pair's first side to the other.
    pub particles: Vec<usize>,
    /// The seams it crosses, each once.
    pub seams: Vec<usize>,
}

impl Ring {
    /// The strain closing the pair asks of the ring: its length now over its rest length,
    /// less one (negative for a ring with slack).
    pub fn closing_strain(&self) -> f64 {
        self.now / self.rest - 1.0
    }
}

/// A ring's closing strain (see [`Ring::closing_strain`]) as the end of a sentence about
/// the ring: the stretch closing asks of it, or the slack it keeps.
pub fn closing_said(strain: f64) -> String {
    if strain > 0.0 {
        format!("which closing stretches {:.0} %", 100.0 * strain)
    } else {
        format!("with {:.0} % to spare when closed", -100.0 * strain)
    }
}

/// A cost compared in a heap: finite and non-negative, so ordered by its bits.
fn key(d: f64) -> Reverse<u64> {
    Reverse(d.to_bits())
}

/// How many ways are tried for one going round the body.
const TRIES: usize = 4;

impl Garment {
    /// The ring through `pair` of seam `seam` at `x` (see [`Ring`]): the shortest way from
    /// one side to the other that `round` says goes round the body (given its points, from
    /// one side to the other), over the cloth's edges (by rest length) and the other
    /// seams' pairs (by their gap), each way tried without the seams the ones before it
    /// crossed; `None` where none of the first few ways goes round.
    pub fn ring_through(
        &self,
        x: &[Vec3],
        seam: usize,
        pair: [usize; 2],
        round: impl Fn(&[Vec3]) -> bool,
    ) -> Option<Ring> {
        let ways = Ways::new(self, x);
        let mut without = vec![seam];
        for _ in 0..TRIES {
            let way = ways.shortest(self, x, &without, pair)?;
            let points: Vec<Vec3> = way.particles.iter().map(|&i| x[i]).collect();
            // A way over seams' pairs alone (a corner where the pair's sides meet other
            // seams) has no cloth to stretch: no ring.
            if way.rest > 0.0 && round(&points) {
                return Some(way);
            }
            if way.seams.is_empty() {
                return None;
            }
            without.extend_from_slice(&way.seams);
        }
        None
    }
}

/// The cloth's edges and the seams' pairs as a graph, made once for every way tried.
struct Ways {
    /// Each particle's neighbours, the cost of the step to each (rest length, or a pair's
    /// gap) and the seam of a pair.
    links: Vec<Vec<(usize, f64, Option<usize>)>>,
    /// The panel of each particle.
    panel: Vec<usize>,
}

impl Ways {
    fn new(garment: &Garment, x: &[Vec3]) -> Self {
        let uv = garment.mesh.uv();
        let mut links: Vec<Vec<(usize, f64, Option<usize>)>> = vec![Vec::new(); garment.mesh.vertex_count()];
        for &[i, j] in garment.mesh.edges() {
            let rest = (uv[i] - uv[j]).norm();
            links[i].push((j, rest, None));
            links[j].push((i, rest, None));
        }
        for (s, seam) in garment.seams.iter().enumerate() {
            for &[i, j] in &seam.pairs {
                let gap = (x[i] - x[j]).norm();
                links[i].push((j, gap, Some(s)));
                links[j].push((i, gap, Some(s)));
            }
        }
        Self {
            links,
            panel: garment.particle_panels(),
        }
    }

    /// The shortest way from one side of `pair` to the other at `x`, over the cloth and
    /// the pairs of the seams not in `without` (see [`Garment::ring_through`]).
    fn shortest(&self, garment: &Garment, x: &[Vec3], without: &[usize], pair: [usize; 2]) -> Option<Ring> {
        let n = self.links.len();
        let [from, to] = pair;
        let mut cost = vec![f64::INFINITY; n];
        let mut prev = vec![(usize::MAX, None); n];
        let mut heap = BinaryHeap::new();
        cost[from] = 0.0;
        heap.push((key(0.0), from));
        while let Some((Reverse(bits), i)) = heap.pop() {
            let c = f64::from_bits(bits);
            if c > cost[i] {
                continue;
            }
            if i == to {
                break;
            }
            for &(j, step, by) in &self.links[i] {
                if by.is_some_and(|s| without.contains(&s)) {
                    continue;
                }
                let e = c + step;
                if e < cost[j] {
                    cost[j] = e;
                    prev[j] = (i, by);
                    heap.push((key(e), j));
                }
            }
        }
        if !cost[to].is_finite() {
            return None;
        }
        let uv = garment.mesh.uv();
        let (mut rest, mut now) = (0.0, (x[from] - x[to]).norm());
        let (mut particles, mut seams) = (vec![to], Vec::new());
        let mut i = to;
        while i != from {
            let (p, by) = prev[i];
            match by {
                None => rest += (uv[i] - uv[p]).norm(),
                Some(s) if !seams.contains(&s) => seams.push(s),
                Some(_) => {}
            }
            now += (x[i] - x[p]).norm();
            particles.push(p);
            i = p;
        }
        particles.reverse();
        let mut panels: Vec<String> = Vec::new();
        for &i in &particles {
            let name = &garment.panel_names[self.panel[i]];
            if !panels.contains(name) {
                panels.push(name.clone());
            }
        }
        Some(Ring {
            rest,
            now,
            panels,
            particles,
            seams,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::garment::GarmentBuilder;
    use crate::pattern::Pattern;
    use cloth_core::math::Vec3;

    /// Two 10 x 20 cm panels, the front at z = +r and the back at z = -r (m), both from x
    /// = -5 to 5 cm and y = 0 to 20 cm: seam 0 joins their sides at x = -5 cm, seam 1 at
    /// x = +5 cm, seam 2 their tops.
    fn tube(r: f64) -> crate::garment::Garment {
        let text = format!(
            r#"
units = "cm"
[[panels]]
name = "front"
outline = [{{ start = [-5, 0] }}, {{ start = [5, 0] }}, {{ start = [5, 20] }}, {{ start = [-5, 20] }}]
placement = {{ rotation = [0, 0, 0], translation = [0, 0, {r}] }}
[[panels]]
name = "back"
outline = [{{ start = [-5, 0] }}, {{ start = [5, 0] }}, {{ start = [5, 20] }}, {{ start = [-5, 20] }}]
placement = {{ rotation = [0, 0, 0], translation = [0, 0, -{r}] }}
[[seams]]
a = {{ panel = "front", edge = 3 }}
b = {{ panel = "back", edge = 3 }}
orientation = "same"
[[seams]]
a = {{ panel = "front", edge = 1 }}
b = {{ panel = "back", edge = 1 }}
orientation = "same"
[[seams]]
a = {{ panel = "front", edge = 2 }}
b = {{ panel = "back", edge = 2 }}
orientation = "same"
"#,
            r = 100.0 * r
        );
        let pattern = Pattern::from_toml_str(&text, "tube.toml").unwrap();
        GarmentBuilder::new(pattern).edge_length(0.02).build().unwrap()
    }

    /// Whether a way's points lie on average left of x = 2 cm: round the tube through
    /// seam 0, not round its corner at the top of seam 1.
    fn round(points: &[Vec3]) -> bool {
        points.iter().map(|p| p.x).sum::<f64>() / (points.len() as f64) < 0.02
    }

    #[test]
    fn the_ring_through_an_open_side_runs_round_through_the_closed_one() {
        let r = 0.01;
        let mut garment = tube(r);
        let x = garment.mesh.positions().to_vec();
        // The pair of seam 1 next to the top: the shortest way from one side to the other
        // turns over seam 2 at the corner, and is passed over; the next, without seam 2,
        // runs across the front (10 cm), over seam 0's pair (2 r), back across the back.
        // Seam 1's own pairs, as near, are no way (else the way would be the pair itself).
        let n = garment.seams[1].pairs.len();
        let pair = garment.seams[1].pairs[n - 2];
        assert!((x[pair[0]].y - 0.18).abs() < 1e-9);
        let ring = garment.ring_through(&x, 1, pair, round).expect("a ring");
        assert_eq!(ring.seams, [0]);
        assert_eq!(ring.particles.first(), Some(&pair[0]));
        assert_eq!(ring.particles.last(), Some(&pair[1]));
        // Along the mesh's edges, so no shorter than the 20 cm straight across and, the
        // triangles near equilateral, not much longer.
        assert!(ring.rest >= 0.2 - 1e-12 && ring.rest < 0.22, "rest {}", ring.rest);
        // The panels lie flat, unstretched, so the way round is as long as at rest, but
        // for the 2 r over seam 0 and the open pair's 2 r.
        assert!(
            (ring.now - (ring.rest + 4.0 * r)).abs() < 1e-12,
            "now {}",
            ring.now
        );
        assert!((ring.closing_strain() - 4.0 * r / ring.rest).abs() < 1e-12);
        assert_eq!(ring.panels, ["front", "back"]);
        // Any way is a ring where any goes round: the corner's, over seam 2.
        let corner = garment.ring_through(&x, 1, pair, |_| true).expect("a way");
        assert_eq!(corner.seams, [2]);
        assert!(corner.rest < 0.1, "{}", corner.rest);
        // None where no way goes round, nor where nothing but their own seam joins the
        // sides.
        assert_eq!(garment.ring_through(&x, 1, pair, |_| false), None);
        garment.seams[0].pairs.clear();
        assert_eq!(garment.ring_through(&x, 1, pair, round), None);
    }
}

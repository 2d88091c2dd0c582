//! A second, much cheaper reference for one cell, fast enough for a million cells: the
//! trilinear function is linear along every `x` line, so on each line of an `n × n` lattice of
//! `(y, z)` the inside set `{g ≥ 0}` and the outside set `{g < 0}` are one interval each. The
//! sets are approximated by those intervals joined between neighbouring lines where they
//! overlap (and across a lattice square where all four overlap); the components come from a
//! union–find over the lines and the Euler characteristic from counting, as for any cubical
//! complex of convex pieces: lines − overlapping neighbours + overlapping squares.

/// Surface pieces and Euler characteristic of the level set in the cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Counts {
    /// Components of the surface: `inside + outside − 1` components of the two sets.
    pub pieces: usize,
    /// `χ(inside) + χ(outside) − χ(cube)`.
    pub euler: i64,
}

/// Reused storage for [`counts`].
#[derive(Default)]
pub struct Lines {
    /// Per line and set (inside 0, outside 1): the interval `[lo, hi]`, empty when `lo > hi`.
    spans: Vec<[(f64, f64); 2]>,
    parent: Vec<u32>,
}

fn root(parent: &mut [u32], n: usize) -> usize {
    let mut n = n;
    while parent[n] as usize != n {
        let up = parent[n] as usize;
        parent[n] = parent[up];
        n = up;
    }
    n
}

fn overlap(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0.max(b.0), a.1.min(b.1))
}

fn filled(s: (f64, f64)) -> bool {
    s.0 <= s.1
}

impl Lines {
    /// The counts for corner values `g` on an `n × n` lattice of lines.
    pub fn counts(&mut self, g: &[f64; 8], n: usize) -> Counts {
        let m = n + 1;
        self.spans.clear();
        for k in 0..m {
            for j in 0..m {
                let (y, z) = (j as f64 / n as f64, k as f64 / n as f64);
                let w = [(1.0 - y) * (1.0 - z), y * (1.0 - z), (1.0 - y) * z, y * z];
                let a = g[0] * w[0] + g[2] * w[1] + g[4] * w[2] + g[6] * w[3];
                let b = g[1] * w[0] + g[3] * w[1] + g[5] * w[2] + g[7] * w[3];
                // g(x) = a + (b − a) x: the inside set is one end of [0, 1], the outside the other.
                let spans = match (a >= 0.0, b >= 0.0) {
                    (true, true) => [(0.0, 1.0), (1.0, 0.0)],
                    (false, false) => [(1.0, 0.0), (0.0, 1.0)],
                    (true, false) => {
                        let t = a / (a - b);
                        [(0.0, t), (t, 1.0)]
                    }
                    (false, true) => {
                        let t = a / (a - b);
                        [(t, 1.0), (0.0, t)]
                    }
                };
                self.spans.push(spans);
            }
        }
        self.parent.clear();
        self.parent.extend(0..(2 * m * m) as u32);
        let mut euler = [0i64; 2];
        let mut components = [0usize; 2];
        for set in 0..2 {
            for line in 0..m * m {
                euler[set] += i64::from(filled(self.spans[line][set]));
            }
            for k in 0..m {
                for j in 0..m {
                    let here = k * m + j;
                    let s = self.spans[here][set];
                    let right = (j + 1 < m).then(|| here + 1);
                    let up = (k + 1 < m).then(|| here + m);
                    for other in [right, up].into_iter().flatten() {
                        if filled(overlap(s, self.spans[other][set])) {
                            euler[set] -= 1;
                            let (ra, rb) =
                                (root(&mut self.parent, 2 * here + set), root(&mut self.parent, 2 * other + set));
                            self.parent[ra.max(rb)] = ra.min(rb) as u32;
                        }
                    }
                    if let (Some(r), Some(u)) = (right, up) {
                        let four = overlap(
                            overlap(s, self.spans[r][set]),
                            overlap(self.spans[u][set], self.spans[u + 1][set]),
                        );
                        euler[set] += i64::from(filled(four));
                    }
                }
            }
            for line in 0..m * m {
                let node = 2 * line + set;
                if filled(self.spans[line][set]) && root(&mut self.parent, node) == node {
                    components[set] += 1;
                }
            }
        }
        Counts { pieces: (components[0] + components[1]).saturating_sub(1), euler: euler[0] + euler[1] - 1 }
    }
}

#[test]
fn the_line_reference_agrees_with_the_lattice_reference() {
    use super::Rng;
    use super::reference::topology;
    let mut lines = Lines::default();
    let mut rng = Rng::new(5);
    let mut compared = 0;
    for _ in 0..300 {
        let g: [f64; 8] = std::array::from_fn(|_| 2.0 * rng.next() - 1.0);
        if super::reference::saddle_values(&g).iter().any(|s| s.abs() < 1e-2) {
            continue;
        }
        let lattice = topology(&g, 30);
        let got = lines.counts(&g, 30);
        assert_eq!((got.pieces, got.euler), (lattice.surface, lattice.euler), "g {g:?}");
        compared += 1;
    }
    assert!(compared > 200);
    // A tunnel (two opposite corners joined through the middle): one tube, χ = 0.
    let mut g = [-0.2; 8];
    g[0] = 1.0;
    g[7] = 1.0;
    assert_eq!(lines.counts(&g, 40), Counts { pieces: 1, euler: 0 });
    // Two corners cut off, the middle low: two disks.
    let mut g = [-0.5; 8];
    g[0] = 1.0;
    g[7] = 1.0;
    assert_eq!(lines.counts(&g, 40), Counts { pieces: 2, euler: 2 });
}

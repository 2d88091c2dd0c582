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

/// Reused storage for [`counts`]. Written as plain loops over flat arrays: the million-cell
/// test runs it in debug builds, where iterator adaptors and small calls cost several times the
/// arithmetic.
#[derive(Default)]
pub struct Lines {
    /// Per set (inside 0, outside 1), per line: the interval's ends `lo` and `hi`, empty when
    /// `lo > hi`.
    lo: [Vec<f64>; 2],
    hi: [Vec<f64>; 2],
    /// Union–find over the lines of one set.
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

fn join(parent: &mut [u32], a: usize, b: usize) {
    let (ra, rb) = (root(parent, a), root(parent, b));
    if ra < rb {
        parent[rb] = ra as u32;
    } else {
        parent[ra] = rb as u32;
    }
}

impl Lines {
    /// The counts for corner values `g` on an `n × n` lattice of lines.
    pub fn counts(&mut self, g: &[f64; 8], n: usize) -> Counts {
        let m = n + 1;
        let lines = m * m;
        for set in 0..2 {
            self.lo[set].clear();
            self.lo[set].resize(lines, 0.0);
            self.hi[set].clear();
            self.hi[set].resize(lines, 0.0);
        }
        for k in 0..m {
            for j in 0..m {
                let (y, z) = (j as f64 / n as f64, k as f64 / n as f64);
                let w = [(1.0 - y) * (1.0 - z), y * (1.0 - z), (1.0 - y) * z, y * z];
                let a = g[0] * w[0] + g[2] * w[1] + g[4] * w[2] + g[6] * w[3];
                let b = g[1] * w[0] + g[3] * w[1] + g[5] * w[2] + g[7] * w[3];
                // g(x) = a + (b − a) x: the inside set is one end of [0, 1], the outside the other.
                let (inside, outside) = if a >= 0.0 && b >= 0.0 {
                    ((0.0, 1.0), (1.0, 0.0))
                } else if a < 0.0 && b < 0.0 {
                    ((1.0, 0.0), (0.0, 1.0))
                } else {
                    let t = a / (a - b);
                    if a >= 0.0 { ((0.0, t), (t, 1.0)) } else { ((t, 1.0), (0.0, t)) }
                };
                let line = k * m + j;
                (self.lo[0][line], self.hi[0][line]) = inside;
                (self.lo[1][line], self.hi[1][line]) = outside;
            }
        }
        let mut euler = 0i64;
        let mut components = 0usize;
        for set in 0..2 {
            let (lo, hi) = (&self.lo[set], &self.hi[set]);
            let parent = &mut self.parent;
            parent.clear();
            parent.extend(0..lines as u32);
            for k in 0..m {
                for j in 0..m {
                    let here = k * m + j;
                    let (l, h) = (lo[here], hi[here]);
                    if l > h {
                        continue;
                    }
                    euler += 1;
                    // Overlaps with the next line along y and along z, and the square's four.
                    let (mut l4, mut h4) = (l, h);
                    if j + 1 < m {
                        let r = here + 1;
                        let (lr, hr) = (if l > lo[r] { l } else { lo[r] }, if h < hi[r] { h } else { hi[r] });
                        if lr <= hr {
                            euler -= 1;
                            join(parent, here, r);
                        }
                        (l4, h4) = (lr, hr);
                    }
                    if k + 1 < m {
                        let u = here + m;
                        let (lu, hu) = (if l > lo[u] { l } else { lo[u] }, if h < hi[u] { h } else { hi[u] });
                        if lu <= hu {
                            euler -= 1;
                            join(parent, here, u);
                        }
                        if j + 1 < m && l4 <= h4 {
                            let d = u + 1;
                            let lo4 = if l4 > lo[u] { l4 } else { lo[u] };
                            let lo4 = if lo4 > lo[d] { lo4 } else { lo[d] };
                            let hi4 = if h4 < hi[u] { h4 } else { hi[u] };
                            let hi4 = if hi4 < hi[d] { hi4 } else { hi[d] };
                            euler += i64::from(lo4 <= hi4);
                        }
                    }
                }
            }
            for line in 0..lines {
                if lo[line] <= hi[line] && root(parent, line) == line {
                    components += 1;
                }
            }
        }
        Counts { pieces: components.saturating_sub(1), euler: euler - 1 }
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

//! A brute-force reference for one cell: the trilinear function sampled on a fine lattice, and
//! the components and Euler characteristics of `{g ≥ 0}` and `{g < 0}` found by flood fill and
//! by counting the cubical complex — nothing shared with the code under test.

/// The trilinear function with corner values `g` (corner `x | y << 1 | z << 2`).
pub fn trilinear(g: &[f64; 8], p: [f64; 3]) -> f64 {
    let mut sum = 0.0;
    for (c, v) in g.iter().enumerate() {
        let w: f64 = (0..3).map(|a| if c >> a & 1 == 1 { p[a] } else { 1.0 - p[a] }).product();
        sum += w * v;
    }
    sum
}

/// What the fine lattice says about one cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Topology {
    /// Components of `{g ≥ 0}` in the cell.
    pub inside: usize,
    /// Components of `{g < 0}` in the cell.
    pub outside: usize,
    /// Components of the surface in the cell: `inside + outside − 1` (the cell, a ball, cut by
    /// a properly embedded surface of `c` pieces falls into `c + 1` regions).
    pub surface: usize,
    /// Boundary loops of the surface: the pieces of the cube's surface minus one.
    pub loops: usize,
    /// The Euler characteristic of the surface, `χ(in) + χ(out) − χ(ball)`.
    pub euler: i64,
}

/// Components of each class of lattice points (6-connected, within one class), counted as
/// `[outside, inside]`; with `surface`, only points on the cube's surface and paths along it.
fn flood(n: usize, inside: &[bool], surface: bool) -> [usize; 2] {
    let m = n + 1;
    let on_surface = |p: usize| {
        let (i, j, k) = (p % m, p / m % m, p / (m * m));
        i == 0 || i == n || j == 0 || j == n || k == 0 || k == n
    };
    let mut seen = vec![false; inside.len()];
    let mut count = [0usize; 2];
    let mut stack: Vec<usize> = Vec::new();
    for start in 0..inside.len() {
        if seen[start] || (surface && !on_surface(start)) {
            continue;
        }
        let class = inside[start];
        count[usize::from(class)] += 1;
        seen[start] = true;
        stack.push(start);
        while let Some(p) = stack.pop() {
            let (i, j, k) = (p % m, p / m % m, p / (m * m));
            let mut next = [usize::MAX; 6];
            if i > 0 {
                next[0] = p - 1;
            }
            if i < n {
                next[1] = p + 1;
            }
            if j > 0 {
                next[2] = p - m;
            }
            if j < n {
                next[3] = p + m;
            }
            if k > 0 {
                next[4] = p - m * m;
            }
            if k < n {
                next[5] = p + m * m;
            }
            for q in next {
                if q != usize::MAX && !seen[q] && inside[q] == class && (!surface || on_surface(q)) {
                    seen[q] = true;
                    stack.push(q);
                }
            }
        }
    }
    count
}

/// The Euler characteristics `[outside, inside]` of the cubical complexes whose vertices are
/// the lattice points of each class (an edge, square or cube is in a complex when all its
/// corners are).
fn euler(n: usize, inside: &[bool]) -> [i64; 2] {
    let m = n + 1;
    let mut chi = [0i64; 2];
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                let p = (k * m + j) * m + i;
                let class = inside[p];
                let c = usize::from(class);
                chi[c] += 1;
                let same = |q: usize| inside[q] == class;
                let (x, y, z) = (i < n, j < n, k < n);
                let (dx, dy, dz) = (1, m, m * m);
                if x && same(p + dx) {
                    chi[c] -= 1;
                }
                if y && same(p + dy) {
                    chi[c] -= 1;
                }
                if z && same(p + dz) {
                    chi[c] -= 1;
                }
                if x && y && same(p + dx) && same(p + dy) && same(p + dx + dy) {
                    chi[c] += 1;
                }
                if x && z && same(p + dx) && same(p + dz) && same(p + dx + dz) {
                    chi[c] += 1;
                }
                if y && z && same(p + dy) && same(p + dz) && same(p + dy + dz) {
                    chi[c] += 1;
                }
                if x && y && z && [dx, dy, dz, dx + dy, dx + dz, dy + dz, dx + dy + dz].iter().all(|&d| same(p + d)) {
                    chi[c] -= 1;
                }
            }
        }
    }
    chi
}

/// The topology of the cell with corner values `g` (level 0) on an `n`-step lattice.
pub fn topology(g: &[f64; 8], n: usize) -> Topology {
    let m = n + 1;
    let mut inside = Vec::with_capacity(m * m * m);
    for k in 0..m {
        let z = k as f64 / n as f64;
        for j in 0..m {
            let y = j as f64 / n as f64;
            let w = [(1.0 - y) * (1.0 - z), y * (1.0 - z), (1.0 - y) * z, y * z];
            let a = g[0] * w[0] + g[2] * w[1] + g[4] * w[2] + g[6] * w[3];
            let b = g[1] * w[0] + g[3] * w[1] + g[5] * w[2] + g[7] * w[3];
            for i in 0..m {
                let x = i as f64 / n as f64;
                inside.push(a * (1.0 - x) + b * x >= 0.0);
            }
        }
    }
    let [cout, cin] = flood(n, &inside, false);
    let [pout, pin] = flood(n, &inside, true);
    let [eout, ein] = euler(n, &inside);
    Topology {
        inside: cin,
        outside: cout,
        surface: (cin + cout).saturating_sub(1),
        loops: (pin + pout).saturating_sub(1),
        euler: ein + eout - 1,
    }
}

/// Values of the critical points of the trilinear function inside the cell (faces' saddles,
/// which matter for the face decisions, and the body's saddles, for the interior).
pub fn saddle_values(g: &[f64; 8]) -> Vec<f64> {
    let mut out = Vec::new();
    // Faces: bilinear g00 + (g10 − g00)u + (g01 − g00)v + D uv.
    for axis in 0..3 {
        let (u, v) = (1 << ((axis + 1) % 3), 1 << ((axis + 2) % 3));
        for side in 0..2 {
            let base = side << axis;
            let (g00, g10, g01, g11) = (g[base], g[base | u], g[base | v], g[base | u | v]);
            let d = g00 - g10 - g01 + g11;
            if d != 0.0 {
                let (su, sv) = ((g00 - g01) / d, (g00 - g10) / d);
                if su > 0.0 && su < 1.0 && sv > 0.0 && sv < 1.0 {
                    out.push((g00 * g11 - g10 * g01) / d);
                }
            }
        }
    }
    // Body: g = a + bx + cy + dz + e xy + f yz + h xz + k xyz.
    let b = g[1] - g[0];
    let c = g[2] - g[0];
    let d = g[4] - g[0];
    let e = g[3] - g[2] - g[1] + g[0];
    let f = g[6] - g[4] - g[2] + g[0];
    let h = g[5] - g[4] - g[1] + g[0];
    let k = g[7] - g[6] - g[5] - g[3] + g[4] + g[2] + g[1] - g[0];
    if k.abs() > 1e-12 {
        // g = k(x+α)(y+β)(z+γ) + p(x+α) + q(y+β) + r(z+γ) + s.
        let (alpha, beta, gamma) = (f / k, h / k, e / k);
        let (p, q, r) = (b - k * beta * gamma, c - k * alpha * gamma, d - k * alpha * beta);
        let s = trilinear(g, [-alpha, -beta, -gamma]);
        let w2 = -p * q * r / k;
        if w2 > 0.0 && p != 0.0 && q != 0.0 && r != 0.0 {
            for w in [w2.sqrt(), -w2.sqrt()] {
                let x = [-w / p - alpha, -w / q - beta, -w / r - gamma];
                if x.iter().all(|&t| t > 0.0 && t < 1.0) {
                    out.push(s - 2.0 * w);
                }
            }
        }
    }
    out
}

#[test]
fn the_reference_knows_a_tunnel_and_a_ball() {
    // One corner in: a quarter ball, disk surface.
    let mut g = [-1.0; 8];
    g[0] = 1.0;
    let t = topology(&g, 20);
    assert_eq!(t, Topology { inside: 1, outside: 1, surface: 1, loops: 1, euler: 1 });
    // Corners 0 and 7 in with a high centre: a tube, χ = 0.
    let mut g = [-0.2; 8];
    g[0] = 1.0;
    g[7] = 1.0;
    let t = topology(&g, 40);
    assert_eq!(t, Topology { inside: 1, outside: 1, surface: 1, loops: 2, euler: 0 });
    // The body saddles of that function: the value at the saddles is above 0 (the tube is
    // open) and the same by symmetry.
    let s = saddle_values(&g);
    assert!(s.iter().all(|v| *v > 0.0), "{s:?}");
}

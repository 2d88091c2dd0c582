//! A plane through a volume with 2-D coordinates of its own, so a slice can be drawn as an image
//! with axes.
//!
//! The plane's axes follow the conventions of medical viewers, whatever its tilt: `u` runs toward
//! the world's +x (toward +y when the normal is mostly along x) and `v` toward +z (toward +y
//! when the normal is mostly along z), both turned into the plane. So an axial plane (normal z)
//! shows x across and y up, a coronal one (normal y) x across and z up, a sagittal one (normal x)
//! y across and z up. A point's coordinates are its distances from the plane's origin along `u`
//! and `v`: for a plane through `at · e` along a world axis `e` these are the world coordinates
//! of the other two axes.

/// A plane with an origin and orthonormal axes `u` and `v` in it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    origin: [f64; 3],
    normal: [f64; 3],
    u: [f64; 3],
    v: [f64; 3],
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn scaled(a: [f64; 3], s: f64) -> [f64; 3] {
    a.map(|x| x * s)
}

fn minus(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn unit(a: [f64; 3]) -> Option<[f64; 3]> {
    let n = dot(a, a).sqrt();
    (n.is_finite() && n > 1e-12).then(|| scaled(a, 1.0 / n))
}

/// `a` with its parts along the unit vectors `along` removed, made unit length.
fn orthogonal(a: [f64; 3], along: &[[f64; 3]]) -> Option<[f64; 3]> {
    let rest = along.iter().fold(a, |r, e| minus(r, scaled(*e, dot(r, *e))));
    unit(rest)
}

impl Plane {
    /// The plane through `point` with `normal` (any length), or why there is none (a normal of
    /// zero length or a value that is not a finite number).
    pub fn new(point: [f64; 3], normal: [f64; 3]) -> Result<Plane, String> {
        if point.iter().chain(&normal).any(|x| !x.is_finite()) {
            return Err(format!("the plane through {point:?} with normal {normal:?} has a value that is not a number"));
        }
        let normal =
            unit(normal).ok_or_else(|| format!("the normal {normal:?} has no direction; give a non-zero vector"))?;
        let mostly = (0..3).max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs())).unwrap_or(2);
        let (right, up) = match mostly {
            0 => ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            1 => ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            _ => ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        };
        // `right` is never parallel to the normal (the normal is mostly along another axis).
        let u = orthogonal(right, &[normal]).ok_or("the plane's axes cannot be chosen")?;
        let v = orthogonal(up, &[normal, u]).ok_or("the plane's axes cannot be chosen")?;
        Ok(Plane { origin: point, normal, u, v })
    }

    /// The plane `world[axis] = at` (axis 0, 1, 2 for x, y, z), whose coordinates are the world
    /// coordinates of the other two axes.
    pub fn along_axis(axis: usize, at: f64) -> Plane {
        let mut point = [0.0; 3];
        let mut normal = [0.0; 3];
        point[axis.min(2)] = at;
        normal[axis.min(2)] = 1.0;
        let origin = point;
        Plane::new(point, normal).unwrap_or(Plane { origin, normal, u: [1.0, 0.0, 0.0], v: [0.0, 1.0, 0.0] })
    }

    /// The unit normal.
    pub fn normal(&self) -> [f64; 3] {
        self.normal
    }

    /// The point the plane was given.
    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }

    /// The unit vectors of the plane's `u` (across) and `v` (up) axes.
    pub fn axes(&self) -> ([f64; 3], [f64; 3]) {
        (self.u, self.v)
    }

    /// The world point at plane coordinates `(u, v)`.
    pub fn world(&self, u: f64, v: f64) -> [f64; 3] {
        [0, 1, 2].map(|a| self.origin[a] + u * self.u[a] + v * self.v[a])
    }

    /// The plane coordinates of world point `w` projected onto the plane.
    pub fn coords(&self, w: [f64; 3]) -> (f64, f64) {
        let d = minus(w, self.origin);
        (dot(d, self.u), dot(d, self.v))
    }

    /// Signed distance of `w` from the plane, along the normal.
    pub fn distance(&self, w: [f64; 3]) -> f64 {
        dot(minus(w, self.origin), self.normal)
    }

    /// Where the plane cuts the parallelepiped with `corners` (bit 0 of the index picks one
    /// edge direction, bit 1 the second, bit 2 the third): the convex polygon's vertices in
    /// plane coordinates, counter-clockwise; empty when the plane misses it or only touches an
    /// edge or a corner.
    pub fn cut(&self, corners: &[[f64; 3]; 8]) -> Vec<(f64, f64)> {
        let d = corners.map(|c| self.distance(c));
        let size = corners.iter().flat_map(|c| c.iter()).fold(0.0f64, |m, x| m.max(x.abs())).max(1.0);
        let touch = 1e-12 * size;
        let mut points: Vec<(f64, f64)> = Vec::new();
        for a in 0..8usize {
            for bit in [1usize, 2, 4] {
                let b = a | bit;
                if b == a {
                    continue;
                }
                let (da, db) = (d[a], d[b]);
                let hit = if da.abs() <= touch {
                    Some(corners[a])
                } else if db.abs() <= touch {
                    Some(corners[b])
                } else if (da < 0.0) != (db < 0.0) {
                    let t = da / (da - db);
                    Some([0, 1, 2].map(|k| corners[a][k] + t * (corners[b][k] - corners[a][k])))
                } else {
                    None
                };
                if let Some(w) = hit {
                    let p = self.coords(w);
                    if !points.iter().any(|q| (q.0 - p.0).abs() <= touch && (q.1 - p.1).abs() <= touch) {
                        points.push(p);
                    }
                }
            }
        }
        if points.len() < 3 {
            return Vec::new();
        }
        let n = points.len() as f64;
        let c = points.iter().fold((0.0, 0.0), |s, p| (s.0 + p.0 / n, s.1 + p.1 / n));
        points.sort_by(|p, q| (p.1 - c.1).atan2(p.0 - c.0).total_cmp(&(q.1 - c.1).atan2(q.0 - c.0)));
        if area(&points) <= touch * touch {
            return Vec::new();
        }
        points
    }
}

/// The area of a simple polygon given counter-clockwise (negative when clockwise).
pub fn area(points: &[(f64, f64)]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<f64>()
        / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> [[f64; 3]; 8] {
        std::array::from_fn(|c| [0, 1, 2].map(|a| (c >> a & 1) as f64))
    }

    #[test]
    fn axis_planes_use_the_viewer_conventions_and_world_coordinates() {
        let axial = Plane::along_axis(2, 4.0);
        assert_eq!(axial.axes(), ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
        assert_eq!(axial.coords([3.0, -2.0, 9.0]), (3.0, -2.0));
        assert_eq!(axial.world(3.0, -2.0), [3.0, -2.0, 4.0]);
        assert_eq!(Plane::along_axis(1, 0.0).axes(), ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]));
        assert_eq!(Plane::along_axis(0, 0.0).axes(), ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]));
        // A tilted plane keeps orthonormal axes, v as near +z as the plane allows.
        let p = Plane::new([0.0; 3], [0.0, 2.0, 1.0]).expect("plane");
        let (u, v) = p.axes();
        assert!((dot(u, v)).abs() < 1e-12 && (dot(u, p.normal())).abs() < 1e-12 && (dot(v, p.normal())).abs() < 1e-12);
        assert!((dot(v, v) - 1.0).abs() < 1e-12 && v[2] > 0.89, "{v:?}");
        assert!(Plane::new([0.0; 3], [0.0; 3]).is_err());
        assert!(Plane::new([f64::NAN, 0.0, 0.0], [0.0, 0.0, 1.0]).is_err());
    }

    #[test]
    fn cuts_through_a_cube_have_the_known_shapes_and_areas() {
        // Square at z = 0.5: area 1.
        let square = Plane::along_axis(2, 0.5).cut(&cube());
        assert_eq!(square.len(), 4);
        assert!((area(&square) - 1.0).abs() < 1e-12);
        // Through the centre perpendicular to the diagonal: a regular hexagon of side √2/2,
        // area 3√3/4.
        let hexagon = Plane::new([0.5; 3], [1.0, 1.0, 1.0]).expect("plane").cut(&cube());
        assert_eq!(hexagon.len(), 6);
        assert!((area(&hexagon) - 3.0 * 3f64.sqrt() / 4.0).abs() < 1e-12, "{}", area(&hexagon));
        // Through the diagonal edge pair x = y: a rectangle 1 × √2.
        let diagonal = Plane::new([0.0; 3], [1.0, -1.0, 0.0]).expect("plane").cut(&cube());
        assert_eq!(diagonal.len(), 4);
        assert!((area(&diagonal) - 2f64.sqrt()).abs() < 1e-12);
        // Near a corner: a triangle with legs 0.3, area (√3/2)(0.3√2)²/2.
        let corner = Plane::new([0.1; 3], [1.0, 1.0, 1.0]).expect("plane").cut(&cube());
        assert_eq!(corner.len(), 3);
        assert!((area(&corner) - 3f64.sqrt() / 4.0 * 0.18).abs() < 1e-12);
        // Missing, or touching a face's plane only at a corner.
        assert!(Plane::along_axis(2, 1.5).cut(&cube()).is_empty());
        assert!(Plane::new([0.0; 3], [1.0, 1.0, 1.0]).expect("plane").cut(&cube()).is_empty());
        // A face of the cube itself is a cut (the slice at the first voxel plane).
        assert!((area(&Plane::along_axis(2, 0.0).cut(&cube())) - 1.0).abs() < 1e-12);
    }
}

//! The flat geometry that pictures of the die share: the outline a convex body's projection
//! covers, and whether a point lies inside it. The explorer's die view and the animation
//! frames both draw with it.

/// A point on a picture's plane: across and up (cm on the explorer's view plane, pixels in
/// an animation frame).
pub type Flat = (f64, f64);

/// Twice the signed area of the triangle `o`, `a`, `b`: positive when `b` lies left of
/// `o`→`a`.
fn cross(o: Flat, a: Flat, b: Flat) -> f64 {
    (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain): the outline a
/// convex body's projection covers.
pub fn convex_hull(points: &[Flat]) -> Vec<Flat> {
    let mut p: Vec<Flat> = points
        .iter()
        .copied()
        .filter(|q| q.0.is_finite() && q.1.is_finite())
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<Flat> = Vec::with_capacity(2 * p.len());
    // The lower chain left to right, then the upper chain right to left.
    let order: Vec<Flat> = p.iter().chain(p.iter().rev()).copied().collect();
    for (k, chain) in order.chunks(p.len()).enumerate() {
        let start = hull.len();
        for &q in chain {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0 {
                hull.pop();
            }
            hull.push(q);
        }
        if k < 2 {
            hull.pop();
        }
    }
    hull
}

/// Whether `p` lies inside the counter-clockwise convex polygon `hull` (or on its outline).
pub fn inside(hull: &[Flat], p: Flat) -> bool {
    hull.len() >= 3 && (0..hull.len()).all(|i| cross(hull[i], hull[(i + 1) % hull.len()], p) >= 0.0)
}

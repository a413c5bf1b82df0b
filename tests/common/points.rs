//! Point-set generators for the property and differential tests. Each is deterministic in its seed.

use super::rng::SplitMix64;

pub type Point = [f64; 2];

/// Uniform in the unit square: general position with probability 1.
pub fn uniform(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    (0..n).map(|_| [rng.next_f64(), rng.next_f64()]).collect()
}

/// Tight clusters (spread 1e-4) around random centres, about 50 points per cluster.
pub fn clustered(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    let centres: Vec<Point> = (0..n.div_ceil(50))
        .map(|_| [rng.next_f64(), rng.next_f64()])
        .collect();
    (0..n)
        .map(|_| {
            let c = centres[rng.below(centres.len())];
            [
                c[0] + 1e-4 * (rng.next_f64() - 0.5),
                c[1] + 1e-4 * (rng.next_f64() - 0.5),
            ]
        })
        .collect()
}

/// An integer grid, `side` × `side` points, shuffled: every cell's corners are cocircular.
pub fn grid(side: usize, seed: u64) -> Vec<Point> {
    let mut points: Vec<Point> = (0..side * side)
        .map(|k| [(k % side) as f64, (k / side) as f64])
        .collect();
    SplitMix64::new(seed).shuffle(&mut points);
    points
}

/// `n` points on one line (exactly representable, shuffled): no triangle exists.
pub fn collinear(n: usize, seed: u64) -> Vec<Point> {
    let mut points: Vec<Point> = (0..n)
        .map(|i| [i as f64 * 0.25, 1.0 + i as f64 * 0.5])
        .collect();
    SplitMix64::new(seed).shuffle(&mut points);
    points
}

/// `n - 2` points on a line plus one on each side: a thin fan of triangles, collinear points
/// everywhere on the way.
pub fn nearly_collinear(n: usize, seed: u64) -> Vec<Point> {
    let mut points = collinear(n.saturating_sub(2), seed);
    points.push([0.3, 40.0]);
    points.push([5.1, -3.0]);
    SplitMix64::new(seed ^ 1).shuffle(&mut points);
    points
}

/// Uniform points of which about a third appear two or three times (exact duplicates).
pub fn duplicated(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    let distinct = uniform(n - n / 3, seed ^ 0xD0D0);
    let mut points = distinct.clone();
    while points.len() < n {
        points.push(distinct[rng.below(distinct.len())]);
    }
    rng.shuffle(&mut points);
    points
}

/// Uniform points scaled to a 1e-12 square (tests that nothing uses an absolute tolerance).
pub fn tiny(n: usize, seed: u64) -> Vec<Point> {
    uniform(n, seed)
        .into_iter()
        .map(|[x, y]| [x * 1e-12, y * 1e-12])
        .collect()
}

/// Uniform points in a unit square offset by 1e12: coordinates keep only ~12 bits of the
/// offset-free part, so many points are cocircular or collinear.
pub fn offset(n: usize, seed: u64) -> Vec<Point> {
    uniform(n, seed)
        .into_iter()
        .map(|[x, y]| [1e12 + x, 1e12 + y])
        .collect()
}

/// A generator: (point count, seed) → points.
pub type Generator = fn(usize, u64) -> Vec<Point>;

/// Every generator by name, for property tests that loop over all of them.
pub fn all_generators() -> Vec<(&'static str, Generator)> {
    vec![
        ("uniform", uniform),
        ("clustered", clustered),
        ("grid", |n, seed| {
            grid((n as f64).sqrt().ceil() as usize, seed)
        }),
        ("collinear", collinear),
        ("nearly_collinear", nearly_collinear),
        ("duplicated", duplicated),
        ("tiny", tiny),
        ("offset", offset),
    ]
}

/// The points as spade's (for the benchmarks that race it).
pub fn spade_points(points: &[Point]) -> Vec<spade::Point2<f64>> {
    points
        .iter()
        .map(|p| spade::Point2::new(p[0], p[1]))
        .collect()
}

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

/// Normal (Gaussian) points, standard deviation 1 in each coordinate (Box–Muller).
pub fn normal(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    (0..n).map(|_| gaussian_pair(&mut rng)).collect()
}

/// Two independent standard normal numbers (Box–Muller).
fn gaussian_pair(rng: &mut SplitMix64) -> Point {
    let radius = (-2.0 * (1.0 - rng.next_f64()).ln()).sqrt();
    let angle = std::f64::consts::TAU * rng.next_f64();
    [radius * angle.cos(), radius * angle.sin()]
}

/// Kuzmin's distribution (Su and Drysdale 1997): uniform angle, radius `r` with
/// P(radius ≤ r) = 1 − 1/√(1 + r²). Half the points lie within √3 of the origin, the farthest
/// of `n` some `n` away: a density that spans many orders of magnitude.
pub fn kuzmin(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| {
            // 1 − u in (0, 1]: r = √(1/(1 − u)² − 1).
            let w = 1.0 - rng.next_f64();
            let r = (1.0 / (w * w) - 1.0).max(0.0).sqrt();
            let angle = std::f64::consts::TAU * rng.next_f64();
            [r * angle.cos(), r * angle.sin()]
        })
        .collect()
}

/// A line singularity (Su and Drysdale 1997): y uniform in [0, 1), x = b/(b + (1 − b)·u) with
/// u uniform and b = 0.001, a density ∝ 1/x² on (b, 1] that crowds the points towards the
/// line x = b.
pub fn line_singularity(n: usize, seed: u64) -> Vec<Point> {
    const B: f64 = 0.001;
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| {
            let u = rng.next_f64();
            [B / (B + (1.0 - B) * u), rng.next_f64()]
        })
        .collect()
}

/// Ten normal clusters of standard deviation 0.01 around centres uniform in the unit square
/// (Su and Drysdale 1997).
pub fn ten_clusters(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    let centres: Vec<Point> = (0..10).map(|_| [rng.next_f64(), rng.next_f64()]).collect();
    (0..n)
        .map(|_| {
            let c = centres[rng.below(centres.len())];
            let g = gaussian_pair(&mut rng);
            [c[0] + 0.01 * g[0], c[1] + 0.01 * g[1]]
        })
        .collect()
}

/// Points on an arc of the unit circle (angles uniform in [0, π)): points in convex position,
/// nearly cocircular four by four, so the in-circle decisions mostly need exact arithmetic.
pub fn circle_arc(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| {
            let angle = std::f64::consts::PI * rng.next_f64();
            [angle.cos(), angle.sin()]
        })
        .collect()
}

/// A square grid of ⌈√n⌉² nodes, the first `n` of them in a shuffled order, each moved by up
/// to 1 % of the spacing in each coordinate.
pub fn jittered_grid(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    let side = (n as f64).sqrt().ceil() as usize;
    let mut nodes: Vec<usize> = (0..side * side).collect();
    rng.shuffle(&mut nodes);
    nodes
        .into_iter()
        .take(n)
        .map(|k| {
            let (i, j) = ((k % side) as f64, (k / side) as f64);
            [
                i + 0.01 * (rng.next_f64() - 0.5),
                j + 0.01 * (rng.next_f64() - 0.5),
            ]
        })
        .collect()
}

/// Forty normal clusters in a 1000-wide square, their standard deviations log-uniform from
/// 10^-3 to 30, the same number of points in each.
pub fn mixed_clusters(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    let clusters: Vec<(Point, f64)> = (0..40)
        .map(|_| {
            let centre = [1000.0 * rng.next_f64(), 1000.0 * rng.next_f64()];
            (
                centre,
                10f64.powf(-3.0 + (30f64.log10() + 3.0) * rng.next_f64()),
            )
        })
        .collect();
    (0..n)
        .map(|i| {
            let (c, spread) = clusters[i % clusters.len()];
            let g = gaussian_pair(&mut rng);
            [c[0] + spread * g[0], c[1] + spread * g[1]]
        })
        .collect()
}

/// Half the points uniform in the unit square, the other half uniform in a 10^-6-wide square
/// patch inside it.
pub fn dense_patch(n: usize, seed: u64) -> Vec<Point> {
    let mut rng = SplitMix64::new(seed);
    let corner = [0.2 + 0.6 * rng.next_f64(), 0.2 + 0.6 * rng.next_f64()];
    (0..n)
        .map(|i| {
            let (u, v) = (rng.next_f64(), rng.next_f64());
            if i % 2 == 0 {
                [u, v]
            } else {
                [corner[0] + 1e-6 * u, corner[1] + 1e-6 * v]
            }
        })
        .collect()
}

/// The distributions of Su and Drysdale's comparison of Delaunay algorithms (1997) — uniform,
/// normal, Kuzmin, line singularity, clusters, points on a circle's arc, a jittered grid — and
/// clusters of mixed spreads and a dense patch in a uniform square: the benchmark's rows and
/// the differential tests' inputs (issue 38).
pub fn distributions() -> Vec<(&'static str, Generator)> {
    vec![
        ("uniform", uniform),
        ("normal", normal),
        ("kuzmin", kuzmin),
        ("line singularity", line_singularity),
        ("ten clusters", ten_clusters),
        ("circle arc", circle_arc),
        ("jittered grid", jittered_grid),
        ("mixed clusters", mixed_clusters),
        ("dense patch", dense_patch),
    ]
}

/// The points as spade's (for the benchmarks that race it).
pub fn spade_points(points: &[Point]) -> Vec<spade::Point2<f64>> {
    points
        .iter()
        .map(|p| spade::Point2::new(p[0], p[1]))
        .collect()
}

//! Geometric predicates and constructions.
//!
//! Predicates are exact by default (Shewchuk's adaptive-precision `orient2d` and `incircle`, from
//! the `robust` crate, which evaluates a floating-point filter first and goes exact only when it is
//! inconclusive). The `X` switch selects plain floating point ([`Inexact`]). Algorithms are generic
//! over [`Predicates`] so that each choice is monomorphized into the hot loops.

pub type Point = [f64; 2];

/// Orientation and in-circle tests.
pub trait Predicates: Copy + Send + Sync + 'static {
    /// Positive if `a`, `b`, `c` are in counter-clockwise order, negative if clockwise, zero if
    /// collinear. (Twice the signed area of the triangle.)
    fn orient2d(a: Point, b: Point, c: Point) -> f64;
    /// Positive if `d` lies inside the circle through the counter-clockwise `a`, `b`, `c`,
    /// negative if outside, zero if on it.
    fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64;

    /// Whether `incircle(a, b, c, d) > 0.0`: the test as Lawson's flips ask it, which lets the
    /// filter answer from one comparison on each side of its error bound.
    #[inline(always)]
    fn incircle_positive(a: Point, b: Point, c: Point, d: Point) -> bool {
        Self::incircle(a, b, c, d) > 0.0
    }

    /// The index of the candidate (of a non-empty list) chosen as the apex over base `u → w`:
    /// the first candidate, replaced by each later one that lies strictly inside the circle
    /// through `u`, `w` and the current choice. When all candidates lie left of `u → w`, whose
    /// circles through `u` and `w` are nested on that side, this is the first one whose circle
    /// contains no other candidate.
    #[inline]
    fn smallest_circle(u: Point, w: Point, candidates: &[Point]) -> usize {
        let mut best = 0;
        for (i, &p) in candidates.iter().enumerate().skip(1) {
            if Self::incircle(u, w, candidates[best], p) > 0.0 {
                best = i;
            }
        }
        best
    }

    /// [`Predicates::smallest_circle`] and whether its choice `c` lies strictly left of
    /// `u → w` (`orient2d(u, w, c) > 0`).
    #[inline]
    fn smallest_circle_left(u: Point, w: Point, candidates: &[Point]) -> (usize, bool) {
        let best = Self::smallest_circle(u, w, candidates);
        (best, Self::orient2d(u, w, candidates[best]) > 0.0)
    }
}

/// Exact predicates (the default).
#[derive(Clone, Copy, Debug, Default)]
pub struct Exact;

/// Floating-point predicates (`X`): faster, but may produce invalid meshes on hard inputs.
#[derive(Clone, Copy, Debug, Default)]
pub struct Inexact;

#[inline(always)]
fn coord(p: Point) -> robust::Coord<f64> {
    robust::Coord { x: p[0], y: p[1] }
}

/// Shewchuk's machine epsilon for round-to-nearest doubles, 2^-53.
const EPSILON: f64 = f64::EPSILON * 0.5;
/// Error bounds of the first (floating-point) stage of Shewchuk's adaptive predicates
/// ("Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates", 1997).
const CCW_ERRBOUND_A: f64 = (3.0 + 16.0 * EPSILON) * EPSILON;
const ICC_ERRBOUND_A: f64 = (10.0 + 96.0 * EPSILON) * EPSILON;
/// Error bound of the in-circle determinant as [`PencilFrame`] evaluates it (linear in the tested
/// point). Following Shewchuk's analysis for that evaluation order gives 11ε + O(ε²) times the
/// permanent; 16ε leaves a margin.
const PENCIL_ERRBOUND: f64 = (16.0 + 128.0 * EPSILON) * EPSILON;

/// The in-circle test of many points `p` against one circle through `u`, `w` and `c`, with
/// everything that does not depend on `p` computed once. With the origin at `u` (`a = w − u`,
/// `b = c − u`, `d = p − u`, lifts `|·|²`), Shewchuk's determinant for `incircle(w, c, p, u)`,
/// which is `−incircle(u, w, c, p)` (a cyclic shift of four rows is an odd permutation), is
/// `dx·A + dy·B + dlift·C` with `A = blift·ay − alift·by`, `B = alift·bx − blift·ax`,
/// `C = ax·by − bx·ay`: five products per point instead of a full determinant.
///
/// The error bound is `PENCIL_ERRBOUND` times the permanent `|dx|·pA + |dy|·pB + dlift·pC` (the
/// `p*` being the sums of absolute values of the coefficients' products), itself bounded by a
/// quadratic in `dlift` so that a test costs one product and one sum for its bound: with
/// `m = pA + pB` (at least both) and any scale `s > 0`, `|dx| + |dy| ≤ √(2·dlift) ≤ dlift/(2s) + s` (the
/// arithmetic–geometric mean inequality), so the permanent is at most
/// `dlift·(pC + m/(2s)) + m·s`. The scale is half the base's L1 length, which keeps the bound
/// within a small factor of the permanent for points about as far from `u` as `w` is (the chain
/// between the base's ends); a looser bound only sends more tests to the exact stages.
struct PencilFrame {
    u: Point,
    w: Point,
    c: Point,
    /// A, B, C.
    coefficients: [f64; 3],
    /// The error bound at `p` is `dlift·bound_quadratic + bound_constant`.
    bound_quadratic: f64,
    bound_constant: f64,
    /// Shewchuk's orientation filter for `orient2d(w, c, u)`, which is `orient2d(u, w, c)`:
    /// `C`, whose sign is exact when it exceeds this bound.
    orientation_bound: f64,
}

/// What the pencil frames over one base `u → w` share: `a = w − u`, its lift, and the scale of
/// the error bound (see [`PencilFrame`]): `s = (|ax| + |ay|)/2` and `1/(2s)`.
struct PencilBase {
    u: Point,
    w: Point,
    a: Point,
    alift: f64,
    scale: f64,
    inverse_double_scale: f64,
}

impl PencilBase {
    #[inline(always)]
    fn new(u: Point, w: Point) -> PencilBase {
        let a = [w[0] - u[0], w[1] - u[1]];
        let l1 = a[0].abs() + a[1].abs();
        PencilBase {
            u,
            w,
            a,
            alift: a[0] * a[0] + a[1] * a[1],
            scale: 0.5 * l1,
            // An infinite or NaN bound (a base below the subnormal range) fails every filter
            // test, and the exact stages decide: still correct.
            inverse_double_scale: 1.0 / l1,
        }
    }

    /// The frame of the circle through `u`, `w` and `c`.
    #[inline(always)]
    fn frame(&self, c: Point) -> PencilFrame {
        let [ax, ay] = self.a;
        let alift = self.alift;
        let (bx, by) = (c[0] - self.u[0], c[1] - self.u[1]);
        let blift = bx * bx + by * by;
        let (a1, a2) = (blift * ay, alift * by);
        let (b1, b2) = (alift * bx, blift * ax);
        let (c1, c2) = (ax * by, bx * ay);
        let linear = (a1.abs() + a2.abs()) + (b1.abs() + b2.abs());
        let orientation_permanent = c1.abs() + c2.abs();
        let quadratic = orientation_permanent + linear * self.inverse_double_scale;
        PencilFrame {
            u: self.u,
            w: self.w,
            c,
            coefficients: [a1 - a2, b1 - b2, c1 - c2],
            bound_quadratic: PENCIL_ERRBOUND * quadratic,
            bound_constant: PENCIL_ERRBOUND * (linear * self.scale),
            orientation_bound: CCW_ERRBOUND_A * orientation_permanent,
        }
    }
}

impl PencilFrame {
    #[cfg(test)]
    fn new(u: Point, w: Point, c: Point) -> PencilFrame {
        PencilBase::new(u, w).frame(c)
    }

    /// Whether `c` lies strictly left of `u → w`: `C` is Shewchuk's floating-point
    /// `orient2d(w, c, u)` (`(w − u) × (c − u)`, the same evaluation), exact in sign beyond his
    /// bound; otherwise the adaptive test decides.
    #[inline(always)]
    fn apex_strictly_left(&self) -> bool {
        if self.coefficients[2] > self.orientation_bound {
            return true;
        }
        Exact::orient2d(self.u, self.w, self.c) > 0.0
    }

    /// Whether `p` lies strictly inside the circle through `u`, `w`, `c` (counter-clockwise):
    /// exactly, with the adaptive exact test when the filter cannot decide.
    #[inline(always)]
    fn strictly_inside(&self, p: Point) -> bool {
        let (dx, dy) = (p[0] - self.u[0], p[1] - self.u[1]);
        let dlift = dx * dx + dy * dy;
        let [a, b, c] = self.coefficients;
        let det = dx * a + dy * b + dlift * c;
        let errbound = dlift * self.bound_quadratic + self.bound_constant;
        // Outside is the common answer (one replacement in several tests): tested first.
        if det > errbound {
            return false;
        }
        if det < -errbound {
            return true;
        }
        robust::incircle(coord(self.u), coord(self.w), coord(self.c), coord(p)) > 0.0
    }
}

impl Predicates for Exact {
    /// The floating-point filter is evaluated here, inline; only when it cannot decide the sign
    /// does `robust` run the adaptive exact stages. The filter decides nearly every test.
    #[inline(always)]
    fn orient2d(a: Point, b: Point, c: Point) -> f64 {
        let detleft = (a[0] - c[0]) * (b[1] - c[1]);
        let detright = (a[1] - c[1]) * (b[0] - c[0]);
        let det = detleft - detright;
        // Shewchuk's bound on |detleft| + |detright| without his sign branches: when the two
        // terms differ in sign (or one is zero), |det| is their whole sum and passes anyway.
        let errbound = CCW_ERRBOUND_A * (detleft.abs() + detright.abs());
        if det.abs() >= errbound {
            return det;
        }
        robust::orient2d(coord(a), coord(b), coord(c))
    }

    #[inline(always)]
    fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64 {
        let (det, errbound) = incircle_filter(a, b, c, d);
        if det > errbound || -det > errbound {
            return det;
        }
        robust::incircle(coord(a), coord(b), coord(c), coord(d))
    }

    #[inline(always)]
    fn incircle_positive(a: Point, b: Point, c: Point, d: Point) -> bool {
        let (det, errbound) = incircle_filter(a, b, c, d);
        if det > errbound {
            return true;
        }
        if -det > errbound {
            return false;
        }
        robust::incircle(coord(a), coord(b), coord(c), coord(d)) > 0.0
    }

    /// The same choice as the default, with the circle's terms computed once per candidate
    /// circle instead of once per test ([`PencilFrame`]); exact like every test here.
    #[inline]
    fn smallest_circle(u: Point, w: Point, candidates: &[Point]) -> usize {
        Self::smallest_circle_left(u, w, candidates).0
    }

    /// The choice of [`Exact::smallest_circle`]; the orientation of the chosen apex comes with
    /// its frame (its `C` term is the orientation determinant).
    #[inline]
    fn smallest_circle_left(u: Point, w: Point, candidates: &[Point]) -> (usize, bool) {
        let base = PencilBase::new(u, w);
        let mut best = 0;
        let mut frame = base.frame(candidates[0]);
        for (i, &p) in candidates.iter().enumerate().skip(1) {
            if frame.strictly_inside(p) {
                best = i;
                frame = base.frame(p);
            }
        }
        (best, frame.apex_strictly_left())
    }
}

/// Shewchuk's in-circle determinant in floating point (rows `a`, `b`, `c` relative to `d`) and
/// the bound on its error (his `ICC_ERRBOUND_A` times the permanent): when `|det|` exceeds the
/// bound, its sign is the exact one.
#[inline(always)]
fn incircle_filter(a: Point, b: Point, c: Point, d: Point) -> (f64, f64) {
    let (adx, ady) = (a[0] - d[0], a[1] - d[1]);
    let (bdx, bdy) = (b[0] - d[0], b[1] - d[1]);
    let (cdx, cdy) = (c[0] - d[0], c[1] - d[1]);
    let (bdxcdy, cdxbdy) = (bdx * cdy, cdx * bdy);
    let (cdxady, adxcdy) = (cdx * ady, adx * cdy);
    let (adxbdy, bdxady) = (adx * bdy, bdx * ady);
    let alift = adx * adx + ady * ady;
    let blift = bdx * bdx + bdy * bdy;
    let clift = cdx * cdx + cdy * cdy;
    let det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * alift
        + (cdxady.abs() + adxcdy.abs()) * blift
        + (adxbdy.abs() + bdxady.abs()) * clift;
    let errbound = ICC_ERRBOUND_A * permanent;
    (det, errbound)
}

impl Predicates for Inexact {
    #[inline(always)]
    fn orient2d(a: Point, b: Point, c: Point) -> f64 {
        (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0])
    }
    #[inline(always)]
    fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64 {
        let (adx, ady) = (a[0] - d[0], a[1] - d[1]);
        let (bdx, bdy) = (b[0] - d[0], b[1] - d[1]);
        let (cdx, cdy) = (c[0] - d[0], c[1] - d[1]);
        let alift = adx * adx + ady * ady;
        let blift = bdx * bdx + bdy * bdy;
        let clift = cdx * cdx + cdy * cdy;
        alift * (bdx * cdy - cdx * bdy)
            + blift * (cdx * ady - adx * cdy)
            + clift * (adx * bdy - bdx * ady)
    }
}

/// The points a caller's coordinates can hold, in the engine's frame (a translated frame is finer
/// than the caller's doubles: see `crate::scaling`). Vertices given back to the caller are put
/// on it so that the caller receives exactly the mesh the engine checked.
pub trait Grid: Sync {
    /// The grid point nearest to `p`.
    fn round(&self, p: Point) -> Point;
}

/// The coordinates `(xi, eta)` of `p` in the affine frame of triangle `(a, b, c)`:
/// `p = a + xi·(b − a) + eta·(c − a)`; they interpolate vertex attributes linearly at `p`.
pub fn frame_coordinates([a, b, c]: [Point; 3], p: Point) -> (f64, f64) {
    let det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    let (dx, dy) = (p[0] - a[0], p[1] - a[1]);
    let xi = (dx * (c[1] - a[1]) - dy * (c[0] - a[0])) / det;
    let eta = ((b[0] - a[0]) * dy - (b[1] - a[1]) * dx) / det;
    (xi, eta)
}

/// The circumcentre of triangle `(org, dest, apex)`, with its coordinates `(xi, eta)` in the
/// affine frame of the triangle: `centre = org + xi·(dest − org) + eta·(apex − org)`. The frame
/// coordinates interpolate (or extrapolate) vertex attributes linearly at the centre.
pub fn circumcenter(org: Point, dest: Point, apex: Point) -> (Point, f64, f64) {
    let (xdo, ydo) = (dest[0] - org[0], dest[1] - org[1]);
    let (xao, yao) = (apex[0] - org[0], apex[1] - org[1]);
    let dodist = xdo * xdo + ydo * ydo;
    let aodist = xao * xao + yao * yao;
    // Twice the signed area, computed exactly so that the sign is right for thin triangles.
    let det = Exact::orient2d(org, dest, apex);
    let denominator = 0.5 / det;
    let dx = (yao * dodist - ydo * aodist) * denominator;
    let dy = (xdo * aodist - xao * dodist) * denominator;
    let xi = (yao * dx - xao * dy) * (2.0 * denominator);
    let eta = (xdo * dy - ydo * dx) * (2.0 * denominator);
    ([org[0] + dx, org[1] + dy], xi, eta)
}

/// The squared sine of the smallest angle of triangle (a, b, c), which grows with that angle
/// (at most 60°): twice the area over the product of the two longest edges is the sine of the
/// angle between them, the one opposite the shortest edge.
pub fn min_angle_sin2([a, b, c]: [Point; 3]) -> f64 {
    let sq = |p: Point, q: Point| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
    let (ab, bc, ca) = (sq(a, b), sq(b, c), sq(c, a));
    let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    let longest_two = ab * bc * ca / ab.min(bc).min(ca);
    if longest_two > 0.0 {
        cross * cross / longest_two
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_and_incircle_signs() {
        let (a, b, c) = ([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]);
        assert!(Exact::orient2d(a, b, c) > 0.0);
        assert!(Exact::orient2d(a, c, b) < 0.0);
        assert_eq!(Exact::orient2d(a, b, [2.0, 0.0]), 0.0);
        assert!(Exact::incircle(a, b, c, [0.5, 0.5]) > 0.0);
        assert!(Exact::incircle(a, b, c, [2.0, 2.0]) < 0.0);
        assert_eq!(Exact::incircle(a, b, c, [1.0, 1.0]), 0.0);
        assert!(Inexact::incircle(a, b, c, [0.5, 0.5]) > 0.0);
    }

    /// The pencil frame's test agrees with the adaptive in-circle test, on random points and on
    /// nearly cocircular ones (where the filter must defer to the exact stages).
    #[test]
    fn pencil_frame_matches_incircle() {
        let mut s = 11u64;
        let mut rand =
            || crate::algorithms::delaunay::order::splitmix64(&mut s) as f64 / u64::MAX as f64;
        for round in 0..40_000 {
            // Scales and offsets around the base (the error bound's scale is the base's length),
            // and tested points far beyond it.
            let (scale, offset) = [(1.0, 0.0), (1e-7, 3.0), (1e6, -1e7), (1.0, 1e4)][round % 4];
            let mut point = || [offset + scale * rand(), offset + scale * rand()];
            let (u, w, c) = (point(), point(), point());
            let p = if round % 2 == 0 {
                let far = if round % 8 == 0 { 1e3 } else { 1.0 };
                let q = point();
                [u[0] + far * (q[0] - u[0]), u[1] + far * (q[1] - u[1])]
            } else {
                // Nearly on the circle through u, w, c: the circumcentre plus the radius, rounded.
                let (centre, _, _) = circumcenter(u, w, c);
                let r = ((u[0] - centre[0]).powi(2) + (u[1] - centre[1]).powi(2)).sqrt();
                let angle = rand() * std::f64::consts::TAU;
                [centre[0] + r * angle.cos(), centre[1] + r * angle.sin()]
            };
            let (w, c) = if Exact::orient2d(u, w, c) > 0.0 {
                (w, c)
            } else {
                (c, w)
            };
            let expected = Exact::incircle(u, w, c, p) > 0.0;
            assert_eq!(
                PencilFrame::new(u, w, c).strictly_inside(p),
                expected,
                "round {round}"
            );
        }
        // Exactly cocircular: never strictly inside.
        let (u, w, c) = ([0.0, 0.0], [4.0, 0.0], [4.0, 4.0]);
        assert!(!PencilFrame::new(u, w, c).strictly_inside([0.0, 4.0]));
        assert!(PencilFrame::new(u, w, c).strictly_inside([1.0, 1.0]));
        // The fast and the default choice agree.
        let candidates: Vec<Point> = (0..50)
            .map(|i| [i as f64 * 0.1, 1.0 + ((i * 7) % 11) as f64 * 0.3])
            .collect();
        let (u, w) = ([0.0, 0.0], [5.0, 0.0]);
        let by_default = (1..candidates.len()).fold(0, |best, i| {
            if Exact::incircle(u, w, candidates[best], candidates[i]) > 0.0 {
                i
            } else {
                best
            }
        });
        assert_eq!(Exact::smallest_circle(u, w, &candidates), by_default);
        // The orientation that comes with the choice is the apex's, also for lists with points
        // right of the base, on its line, or nearly so.
        for round in 0..2_000 {
            let n = 1 + round % 7;
            let candidates: Vec<Point> = (0..n)
                .map(|i| match (round + i) % 5 {
                    0 => [rand() * 5.0, 0.0],
                    1 => [rand() * 5.0, -rand()],
                    2 => [rand() * 5.0, 1e-17 * rand()],
                    _ => [rand() * 5.0, rand()],
                })
                .collect();
            let (best, left) = Exact::smallest_circle_left(u, w, &candidates);
            assert_eq!(best, Exact::smallest_circle(u, w, &candidates));
            let by_default = (1..n).fold(0, |best, i| {
                if Exact::incircle(u, w, candidates[best], candidates[i]) > 0.0 {
                    i
                } else {
                    best
                }
            });
            assert_eq!(best, by_default, "round {round}");
            assert_eq!(left, Exact::orient2d(u, w, candidates[best]) > 0.0);
        }
    }

    #[test]
    fn circumcenter_frame_reproduces_centre() {
        let (o, d, a) = ([0.0, 0.0], [2.0, 0.0], [0.5, 1.5]);
        let (c, xi, eta) = circumcenter(o, d, a);
        let r = |p: Point| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).sqrt();
        assert!((r(o) - r(d)).abs() < 1e-12 && (r(o) - r(a)).abs() < 1e-12);
        let back = [
            o[0] + xi * (d[0] - o[0]) + eta * (a[0] - o[0]),
            o[1] + xi * (d[1] - o[1]) + eta * (a[1] - o[1]),
        ];
        assert!((back[0] - c[0]).abs() < 1e-12 && (back[1] - c[1]).abs() < 1e-12);
    }
}

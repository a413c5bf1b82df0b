//! Geometric predicates and constructions.
//!
//! Predicates are exact by default (Shewchuk's adaptive-precision `orient2d` and `incircle`, from
//! the `robust` crate, which evaluates a floating-point filter first and goes exact only when it is
//! inconclusive). The `X` switch selects plain floating point ([`Inexact`]). Algorithms are generic
//! over [`Predicates`] so that each choice is monomorphized into the hot loops.

mod expansion;

pub type Point = [f64; 2];

/// Orientation and in-circle tests.
pub trait Predicates: Copy + Send + Sync + 'static {
    /// Positive if `a`, `b`, `c` are in counter-clockwise order, negative if clockwise, zero if
    /// collinear. (Twice the signed area of the triangle.)
    fn orient2d(a: Point, b: Point, c: Point) -> f64;
    /// Positive if `d` lies inside the circle through the counter-clockwise `a`, `b`, `c`,
    /// negative if outside, zero if on it.
    fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64;

    /// Whether `d` lies inside the circle through the counter-clockwise `a`, `b`, `c` after the
    /// symbolic perturbation ([`perturbed_incircle_positive`]): `incircle(a, b, c, d) > 0.0`
    /// where the determinant is not zero, the tie rule where it is. Every in-circle decision of
    /// the Delaunay build asks this (the flips, the merge's zip, the scan), so the triangulation
    /// of cocircular points depends on the points alone, not on the insertion order. Asked as
    /// a yes-or-no question, it lets the filter answer from one comparison on each side of its
    /// error bound.
    #[inline(always)]
    fn incircle_positive(a: Point, b: Point, c: Point, d: Point) -> bool {
        let det = Self::incircle(a, b, c, d);
        if det != 0.0 {
            return det > 0.0;
        }
        perturbed_incircle_positive::<Self>(a, b, c, d)
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

    /// A number of the sign of [`Self::orient2d`]`(p, a, b)`, for a caller that computes
    /// `(a − p) × (b − p)` itself: exact predicates compute `orient2d(a, b, p)`, whose exact
    /// sign is the same (a cyclic shift of the points) and whose filter's determinant is that
    /// product with the same operations, so the compiler computes it once; plain floating point
    /// computes `orient2d(p, a, b)` itself, whose rounding may differ.
    #[inline(always)]
    fn orient2d_sign_from(p: Point, a: Point, b: Point) -> f64 {
        Self::orient2d(p, a, b)
    }

    /// [`Predicates::smallest_circle`] and whether its choice `c` lies strictly left of
    /// `u → w` (`orient2d(u, w, c) > 0`).
    #[inline]
    fn smallest_circle_left(u: Point, w: Point, candidates: &[Point]) -> (usize, bool) {
        let best = Self::smallest_circle(u, w, candidates);
        (best, Self::orient2d(u, w, candidates[best]) > 0.0)
    }
}

/// Whether `p` comes after `q` in the points' rank: lexicographic order of the coordinates
/// (`x`, then `y`), which depends on the points alone — not on their numbering, their insertion
/// order or the other points (a subset ranks its points as the whole set does), and not on a
/// power-of-two scaling.
#[inline(always)]
fn ranks_above(p: Point, q: Point) -> bool {
    p[0] > q[0] || (p[0] == q[0] && p[1] > q[1])
}

/// The tie rule of [`Predicates::incircle_positive`], for an in-circle determinant that is
/// exactly zero (`d` on the circle through `a`, `b`, `c`): the sign of the determinant after
/// symbolic perturbation of the lifted points (Edelsbrunner and Mücke 1990, "Simulation of
/// Simplicity"). Each point's lift `x² + y²` is raised by `ε^(n − rank)`, its rank in
/// lexicographic order ([`ranks_above`]), for an infinitesimal `ε > 0`: a higher-ranked point's
/// raise dominates any combination of lower-ranked ones.
///
/// The in-circle determinant is the orientation of the four lifted points, linear in the lifts:
/// raising them by `δa, δb, δc, δd` adds
/// `δa·orient2d(b, c, d) − δb·orient2d(a, c, d) + δc·orient2d(a, b, d) − δd·orient2d(a, b, c)`.
/// So the sign is that of the term of the highest-ranked of the four points whose orientation
/// is not zero — of four distinct cocircular points, the highest-ranked one's (no three points
/// of a circle are collinear). When `d` ranks highest, raising it moves it outside the circle
/// (its term is `−δd·orient2d(a, b, c) < 0`): not inside.
///
/// The perturbed points are in general position for the in-circle test, so the Delaunay
/// triangulation of the perturbed points is unique, and it is a Delaunay triangulation of the
/// points (every exact in-circle determinant ≤ 0 across its edges). The plane's coordinates are
/// not perturbed: orientations, and so the hull with its collinear points and the ghost
/// triangles' tests (a half-plane beyond a hull edge), are the exact ones. Four points of
/// which all orientations are zero (collinear) stay a tie: not inside.
#[cold]
#[inline(never)]
pub fn perturbed_incircle_positive<P: Predicates>(a: Point, b: Point, c: Point, d: Point) -> bool {
    // The four points by decreasing rank (insertion sort of four).
    let mut order = [0usize, 1, 2, 3];
    let points = [a, b, c, d];
    for i in 1..4 {
        let mut j = i;
        while j > 0 && ranks_above(points[order[j]], points[order[j - 1]]) {
            order.swap(j, j - 1);
            j -= 1;
        }
    }
    for k in order {
        let term = match k {
            0 => P::orient2d(b, c, d),
            1 => -P::orient2d(a, c, d),
            2 => P::orient2d(a, b, d),
            _ => -P::orient2d(a, b, c),
        };
        if term != 0.0 {
            return term > 0.0;
        }
    }
    false
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
    #[inline(always)]
    fn orient2d_sign_from(p: Point, a: Point, b: Point) -> f64 {
        Self::orient2d(a, b, p)
    }

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
        exact_incircle(coord(a), coord(b), coord(c), coord(d))
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
        exact_incircle_positive(coord(a), coord(b), coord(c), coord(d))
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

/// [`Exact::incircle_positive`] where the filter cannot decide: the adaptive exact stages, then
/// the tie rule. One call out of the flips' loop, whose arguments (`Coord`s, a pair of scalars
/// each: eight floating-point registers, as for `robust::incircle`; arrays would be passed in
/// general registers, which the loop needs) are those the exact stages take anyway, so that the
/// loop keeps nothing alive across it for the tie rule. Measured (callgrind, 3·10^5 uniform
/// points, one core): 528 M instructions before the tie rule, 518 M so, 541 M with arrays as
/// arguments, 555 M with the tie rule after a call of `robust::incircle` in the loop.
#[cold]
#[inline(never)]
fn exact_incircle_positive(
    a: robust::Coord<f64>,
    b: robust::Coord<f64>,
    c: robust::Coord<f64>,
    d: robust::Coord<f64>,
) -> bool {
    let det = exact_incircle(a, b, c, d);
    if det != 0.0 {
        return det > 0.0;
    }
    let point = |p: robust::Coord<f64>| [p.x, p.y];
    perturbed_incircle_positive::<Exact>(point(a), point(b), point(c), point(d))
}

/// The exact in-circle determinant's sign (as a double of that sign, or its value): in 128-bit
/// integers where the four points have small integer coordinates (grids, the corners of unit
/// squares: the cocircular inputs whose ties reach this stage most often), else in
/// double-double arithmetic where that decides (near ties: rounded points on a curve), else in
/// short expansions where the coordinate differences are exact ([`expansion`]: nearby points, as
/// ties are), else by `robust`'s adaptive stages, which zero some 20 KiB of expansions per
/// call — some microseconds, more than a whole small triangulation.
#[inline]
fn exact_incircle(
    a: robust::Coord<f64>,
    b: robust::Coord<f64>,
    c: robust::Coord<f64>,
    d: robust::Coord<f64>,
) -> f64 {
    // Below 2^24 the differences are below 2^25, the lifts below 2^51, the 2×2 minors below
    // 2^51 and the determinant below 2^104: exact in i128.
    const SMALL: f64 = (1u32 << 24) as f64;
    let small = |v: f64| v.trunc() == v && v.abs() < SMALL;
    if [a, b, c, d].iter().all(|p| small(p.x) && small(p.y)) {
        let row = |p: robust::Coord<f64>| {
            let (x, y) = ((p.x - d.x) as i128, (p.y - d.y) as i128);
            (x, y, x * x + y * y)
        };
        let ((ax, ay, al), (bx, by, bl), (cx, cy, cl)) = (row(a), row(b), row(c));
        let det = al * (bx * cy - cx * by) + bl * (cx * ay - ax * cy) + cl * (ax * by - bx * ay);
        return det.signum() as f64;
    }
    let point = |p: robust::Coord<f64>| [p.x, p.y];
    expansion::incircle(point(a), point(b), point(c), point(d))
        .unwrap_or_else(|| robust::incircle(a, b, c, d))
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

/// The sign of `(u − w)·(v − w)`, exactly: negative where `w` lies strictly inside the circle
/// with diameter `u`–`v` (the angle at `w` is obtuse), zero on it, positive outside. Conforming
/// Delaunay (`D`) decides encroachment by it: a vertex a few units in the last place inside a
/// hull subsegment's diametral circle puts a Voronoi vertex outside the triangulation, so the
/// decision cannot be left to rounding. A floating-point filter first (each difference, product
/// and the sum round once: 4ε of the terms' magnitudes, doubled for safety); else the exact
/// sum of the eight error-free products of the differences' two-term expansions.
pub fn diametral_dot(u: Point, v: Point, w: Point) -> f64 {
    let (ax, ay, bx, by) = (u[0] - w[0], u[1] - w[1], v[0] - w[0], v[1] - w[1]);
    let (px, py) = (ax * bx, ay * by);
    let dot = px + py;
    if dot.abs() > 8.0 * f64::EPSILON * (px.abs() + py.abs()) {
        return dot;
    }
    let two_diff = |a: f64, b: f64| {
        let x = a - b;
        let bv = a - x;
        (x, (a - (x + bv)) + (bv - b))
    };
    let (ax, ay) = (two_diff(u[0], w[0]), two_diff(u[1], w[1]));
    let (bx, by) = (two_diff(v[0], w[0]), two_diff(v[1], w[1]));
    // Exactly a·b + c·d... as the sum of 16 doubles (each product split by an fma).
    let mut terms = [0.0; 16];
    let mut n = 0;
    for (a, b) in [(ax, bx), (ay, by)] {
        for x in [a.0, a.1] {
            for y in [b.0, b.1] {
                let p = x * y;
                terms[n] = p;
                terms[n + 1] = x.mul_add(y, -p);
                n += 2;
            }
        }
    }
    exact_sum_sign(&terms)
}

/// The exact sum's sign of `terms` (as a double of that sign): grown term by term into a
/// nonoverlapping expansion (Shewchuk 1997, Grow-Expansion), whose largest nonzero component
/// carries the sign.
fn exact_sum_sign(terms: &[f64]) -> f64 {
    let mut expansion = [0.0f64; 17];
    let mut len = 0;
    for &t in terms {
        let mut q = t;
        for e in expansion.iter_mut().take(len) {
            let sum = q + *e;
            let bv = sum - q;
            let low = (q - (sum - bv)) + (*e - bv);
            *e = low;
            q = sum;
        }
        expansion[len] = q;
        len += 1;
    }
    expansion[..len]
        .iter()
        .rev()
        .copied()
        .find(|&c| c != 0.0)
        .unwrap_or(0.0)
}

/// The squared sine of the smallest angle of triangle (a, b, c), which grows with that angle
/// (at most 60°): twice the area over the product of the two longest edges is the sine of the
/// angle between them, the one opposite the shortest edge.
#[inline]
pub fn min_angle_sin2([a, b, c]: [Point; 3]) -> f64 {
    min_angle_sin2_given_bc([a, b, c], squared_distance(b, c))
}

/// The squared distance between `p` and `q`.
#[inline(always)]
pub fn squared_distance(p: Point, q: Point) -> f64 {
    (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)
}

/// [`min_angle_sin2`] of triangle (a, b, c) with `bc`, [`squared_distance`] of `b` and `c`,
/// given: the same operations, so the same value, for a caller that tries many `a` against one
/// edge.
#[inline(always)]
pub fn min_angle_sin2_given_bc([a, b, c]: [Point; 3], bc: f64) -> f64 {
    let sq = squared_distance;
    let (ab, ca) = (sq(a, b), sq(c, a));
    let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    // The shortest by plain comparisons, not `f64::min`'s NaN handling: where one is NaN, so
    // is the product, and the value is 0 either way (sums of squares are never -0).
    let shortest = if ab < bc { ab } else { bc };
    let shortest = if shortest < ca { shortest } else { ca };
    let longest_two = ab * bc * ca / shortest;
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
    fn small_integer_incircle_agrees_with_the_adaptive_one() {
        let mut state = 7u64;
        let mut next = |range: u64| {
            (crate::algorithms::delaunay::order::splitmix64(&mut state) % range) as f64
        };
        for case in 0..20_000 {
            // Small grids (many cocircular quadruples) and coordinates near the 2^24 limit.
            let (range, offset) = if case % 2 == 0 {
                (5, 0.0)
            } else {
                (40, 16_777_000.0)
            };
            let mut p = || robust::Coord {
                x: next(range) + offset,
                y: next(range) - offset,
            };
            let (a, b, c, d) = (p(), p(), p(), p());
            let adaptive = robust::incircle(a, b, c, d);
            let sign = |v: f64| (v > 0.0) as i8 - (v < 0.0) as i8;
            assert_eq!(
                sign(exact_incircle(a, b, c, d)),
                sign(adaptive),
                "{a:?} {b:?} {c:?} {d:?}"
            );
        }
    }

    #[test]
    fn diametral_dot_is_exact_where_rounding_says_on_the_circle() {
        // (0.6, 0.3) lies on the circle with diameter (0.375, 0)–(1, 0) in the reals; the doubles
        // 0.6 and 0.3 (just below) put it a few 10^-18 inside: rounding says 0.
        let (u, v, w) = ([0.375, 0.0], [1.0, 0.0], [0.6, 0.3]);
        let rounded = (u[0] - w[0]) * (v[0] - w[0]) + (u[1] - w[1]) * (v[1] - w[1]);
        assert!(rounded >= 0.0, "the doubles round to {rounded}");
        assert!(diametral_dot(u, v, w) < 0.0);
        assert!(diametral_dot(u, v, [0.6875, 0.3125]) == 0.0);
        assert!(diametral_dot(u, v, [0.6875, 0.3125f64.next_up()]) > 0.0);
        assert!(diametral_dot(u, v, [0.6875, 0.3125f64.next_down()]) < 0.0);
        assert!(diametral_dot(u, v, [2.0, 0.0]) > 0.0);
    }

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

    /// The tie rule is the sign of the in-circle determinant of explicitly perturbed lifts
    /// (the orientation of the four lifted points, exact): the highest-ranked of the four raised
    /// by 2^-14, the next by 2^-28, the next by 2^-42, far enough apart for coordinates of
    /// magnitude below 16 that each dominates the ones below. It flips with any swap of two
    /// points, so of the two diagonals of four cocircular points exactly one is Delaunay.
    #[test]
    fn ties_are_decided_by_perturbed_lifts() {
        let lift = |p: Point, raise: f64| robust::Coord3D {
            x: p[0],
            y: p[1],
            z: p[0] * p[0] + p[1] * p[1] + raise,
        };
        // The orientation of the lifted points is the in-circle determinant.
        let (a, b, c, d) = ([0.0, 0.0], [3.0, 0.0], [0.0, 2.0], [1.0, 1.0]);
        assert!(Exact::incircle(a, b, c, d) > 0.0);
        assert!(robust::orient3d(lift(a, 0.0), lift(b, 0.0), lift(c, 0.0), lift(d, 0.0)) > 0.0);
        let circle: Vec<Point> = [(3, 4), (4, 3), (5, 0), (0, 5)]
            .iter()
            .flat_map(|&(x, y): &(i32, i32)| [[x, y], [-x, y], [x, -y], [-x, -y]])
            .collect::<std::collections::BTreeSet<[i32; 2]>>()
            .into_iter()
            .map(|[x, y]| [x as f64, y as f64])
            .collect();
        let mut s = 5u64;
        let mut below =
            |n: usize| (crate::algorithms::delaunay::order::splitmix64(&mut s) % n as u64) as usize;
        for round in 0..3_000 {
            let centre = [below(7) as f64 - 3.0, below(7) as f64 - 3.0];
            let mut picks: Vec<usize> = Vec::new();
            while picks.len() < 4 {
                let k = below(circle.len());
                if !picks.contains(&k) {
                    picks.push(k);
                }
            }
            let q: Vec<Point> = picks
                .iter()
                .map(|&k| [circle[k][0] + centre[0], circle[k][1] + centre[1]])
                .collect();
            assert_eq!(Exact::incircle(q[0], q[1], q[2], q[3]), 0.0);
            let raise = |p: Point| {
                let above = q.iter().filter(|&&o| ranks_above(o, p)).count();
                [2f64.powi(-14), 2f64.powi(-28), 2f64.powi(-42), 0.0][above]
            };
            let perturbed = robust::orient3d(
                lift(q[0], raise(q[0])),
                lift(q[1], raise(q[1])),
                lift(q[2], raise(q[2])),
                lift(q[3], raise(q[3])),
            );
            assert_ne!(perturbed, 0.0);
            let inside = Exact::incircle_positive(q[0], q[1], q[2], q[3]);
            assert_eq!(inside, perturbed > 0.0, "round {round}: {q:?}");
            assert_eq!(inside, Inexact::incircle_positive(q[0], q[1], q[2], q[3]));
            // Any swap of two points flips the answer.
            assert_eq!(Exact::incircle_positive(q[1], q[0], q[2], q[3]), !inside);
            assert_eq!(Exact::incircle_positive(q[0], q[1], q[3], q[2]), !inside);
            assert_eq!(Exact::incircle_positive(q[3], q[1], q[2], q[0]), !inside);
        }
        // The square: its lexicographically last corner, (1, 1), is raised, so it lies outside
        // the circle of the other three, and the diagonal is (1, 0)–(0, 1).
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(!Exact::incircle_positive(
            square[0], square[1], square[3], square[2]
        ));
        assert!(Exact::incircle_positive(
            square[1], square[2], square[0], square[3]
        ));
        // Collinear points (no circle): never inside.
        let line = [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]];
        assert!(!Exact::incircle_positive(
            line[0], line[1], line[2], line[3]
        ));
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

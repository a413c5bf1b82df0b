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

impl Predicates for Exact {
    /// The floating-point filter is evaluated here, inline; only when it cannot decide the sign
    /// does `robust` run the adaptive exact stages. The filter decides nearly every test.
    #[inline(always)]
    fn orient2d(a: Point, b: Point, c: Point) -> f64 {
        let detleft = (a[0] - c[0]) * (b[1] - c[1]);
        let detright = (a[1] - c[1]) * (b[0] - c[0]);
        let det = detleft - detright;
        let detsum = if detleft > 0.0 {
            if detright <= 0.0 {
                return det;
            }
            detleft + detright
        } else if detleft < 0.0 {
            if detright >= 0.0 {
                return det;
            }
            -detleft - detright
        } else {
            return det;
        };
        let errbound = CCW_ERRBOUND_A * detsum;
        if det >= errbound || -det >= errbound {
            return det;
        }
        robust::orient2d(coord(a), coord(b), coord(c))
    }

    #[inline(always)]
    fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64 {
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
        if det > errbound || -det > errbound {
            return det;
        }
        robust::incircle(coord(a), coord(b), coord(c), coord(d))
    }
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
        alift * (bdx * cdy - cdx * bdy) + blift * (cdx * ady - adx * cdy) + clift * (adx * bdy - bdx * ady)
    }
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

    #[test]
    fn circumcenter_frame_reproduces_centre() {
        let (o, d, a) = ([0.0, 0.0], [2.0, 0.0], [0.5, 1.5]);
        let (c, xi, eta) = circumcenter(o, d, a);
        let r = |p: Point| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).sqrt();
        assert!((r(o) - r(d)).abs() < 1e-12 && (r(o) - r(a)).abs() < 1e-12);
        let back = [o[0] + xi * (d[0] - o[0]) + eta * (a[0] - o[0]), o[1] + xi * (d[1] - o[1]) + eta * (a[1] - o[1])];
        assert!((back[0] - c[0]).abs() < 1e-12 && (back[1] - c[1]).abs() < 1e-12);
    }
}

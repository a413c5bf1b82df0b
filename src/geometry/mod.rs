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

impl Predicates for Exact {
    #[inline(always)]
    fn orient2d(a: Point, b: Point, c: Point) -> f64 {
        robust::orient2d(coord(a), coord(b), coord(c))
    }
    #[inline(always)]
    fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64 {
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

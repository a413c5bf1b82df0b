//! The test that switch `u` applies when the caller registered none.

/// Triangle's built-in `u` test, as observed on the reference (Debian's `triangle` program and
/// library, and the PyPI `triangle` package, which all compile it in): a triangle is unsuitable
/// when the square of its longest edge exceeds `0.02 + 0.05 · (ox² + oy²)`, where `(ox, oy)` is its
/// origin, the first vertex the test is given. The area is not looked at. In effect the mesh is
/// graded from edges of about 0.14 around the point (0, 0) to longer ones away from it, edge
/// length growing as about 0.22 times the distance from (0, 0).
///
/// Derived by probing the reference only (a refinement with `u` of one triangle: split or not):
/// the threshold is the longest edge (any shape, acute or obtuse, from equilateral to slivers),
/// it depends on the position of one corner only (with `r`, the first corner of the input
/// triangle; with `p` on a lone triangle, its leftmost corner, the origin Triangle's
/// triangulation gives it), the comparison is strict, and this expression agrees with the
/// reference bit for bit at the threshold (edges a few units in the last place either side).
///
/// Coordinates and area are the caller's: the test sees what a registered test would see.
pub fn builtin_unsuitable(
    ox: f64,
    oy: f64,
    dx: f64,
    dy: f64,
    ax: f64,
    ay: f64,
    _area: f64,
) -> bool {
    let square = |x: f64, y: f64| x * x + y * y;
    let longest = square(dx - ox, dy - oy)
        .max(square(ax - dx, ay - dy))
        .max(square(ox - ax, oy - ay));
    longest > 0.05 * square(ox, oy) + 0.02
}

#[cfg(test)]
mod tests {
    use super::builtin_unsuitable;

    #[test]
    fn the_threshold_grows_with_the_origins_distance_from_zero() {
        // A right isosceles triangle whose hypotenuse, from the origin, is `length` long.
        let edge = |ox: f64, oy: f64, length: f64| {
            builtin_unsuitable(
                ox,
                oy,
                ox + length,
                oy,
                ox + 0.5 * length,
                oy + 0.5 * length,
                0.0,
            )
        };
        // At (0, 0) the bound is 0.02: an edge of 0.1415 splits, 0.1414 does not.
        assert!(edge(0.0, 0.0, 0.1415));
        assert!(!edge(0.0, 0.0, 0.1414));
        // At distance 5: 0.02 + 0.05 · 25 = 1.27.
        assert!(edge(3.0, 4.0, 1.27f64.sqrt() * 1.0001));
        assert!(!edge(3.0, 4.0, 1.27f64.sqrt() * 0.9999));
        // Only the origin counts: the same triangle (longest edge² 4.66) is unsuitable from
        // (9, 0) (bound 4.07) and not from (10, 0) (bound 5.02).
        assert!(builtin_unsuitable(9.0, 0.0, 10.0, 0.0, 9.5, 2.1, 1.05));
        assert!(!builtin_unsuitable(10.0, 0.0, 9.5, 2.1, 9.0, 0.0, 1.05));
    }
}

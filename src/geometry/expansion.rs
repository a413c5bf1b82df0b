//! Exact arithmetic on floating-point expansions (Shewchuk, "Adaptive Precision Floating-Point
//! Arithmetic and Fast Robust Geometric Predicates", 1997): a number held exactly as a sum of
//! doubles of increasing magnitude that do not overlap, built from error-free sums and products.
//!
//! Here for the in-circle test of points whose coordinate differences are exact (the points of
//! an in-circle tie are near one another, and the difference of two doubles within a factor two
//! of each other is exact: Sterbenz's lemma). Then the determinant is a polynomial in doubles,
//! and its exact value takes a few short expansions: a few hundred instructions, against the
//! thousands of the `robust` crate's general adaptive stages (which clear some 20 KiB of
//! buffers per call for the worst case of inexact differences).

/// `a + b` and its rounding error, exactly (Knuth's two-sum).
#[inline(always)]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    let b_virtual = x - a;
    let a_virtual = x - b_virtual;
    (x, (a - a_virtual) + (b - b_virtual))
}

/// `a + b` and its rounding error where `|a| ≥ |b|` (Dekker's fast two-sum).
#[inline(always)]
fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    (x, b - (x - a))
}

/// `a - b` and its rounding error, exactly.
#[inline(always)]
fn two_diff(a: f64, b: f64) -> (f64, f64) {
    let x = a - b;
    let b_virtual = a - x;
    let a_virtual = x + b_virtual;
    (x, (a - a_virtual) + (b_virtual - b))
}

/// `a · b` and its rounding error, exactly (the fused multiply-add computes the error).
#[inline(always)]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let x = a * b;
    (x, a.mul_add(b, -x))
}

/// `e · b` into `h`, zero components left out (Scale-Expansion); returns the length. `h` must
/// hold `2 · e.len()` components.
fn scale(e: &[f64], b: f64, h: &mut [f64]) -> usize {
    let mut n = 0;
    let mut push = |h: &mut [f64], x: f64| {
        if x != 0.0 {
            h[n] = x;
            n += 1;
        }
    };
    let Some((&first, rest)) = e.split_first() else {
        return 0;
    };
    let (mut q, low) = two_product(first, b);
    push(h, low);
    for &component in rest {
        let (high, low) = two_product(component, b);
        let (sum, error) = two_sum(q, low);
        push(h, error);
        let (next, error) = fast_two_sum(high, sum);
        push(h, error);
        q = next;
    }
    push(h, q);
    n
}

/// `e + f` into `h`, zero components left out (Fast-Expansion-Sum, valid under round-to-even);
/// returns the length. `h` must hold `e.len() + f.len()` components.
fn sum(e: &[f64], f: &[f64], h: &mut [f64]) -> usize {
    // Both inputs are in increasing magnitude: merged, they are the sum's terms in that order.
    let (mut i, mut j) = (0, 0);
    let mut next = || {
        let take_e = j == f.len() || (i < e.len() && e[i].abs() < f[j].abs());
        if take_e {
            i += 1;
            e[i - 1]
        } else {
            j += 1;
            f[j - 1]
        }
    };
    let total = e.len() + f.len();
    let mut n = 0;
    if total == 0 {
        return 0;
    }
    let mut q = next();
    for k in 1..total {
        let g = next();
        let (s, error) = if k == 1 {
            fast_two_sum(g, q)
        } else {
            two_sum(q, g)
        };
        if error != 0.0 {
            h[n] = error;
            n += 1;
        }
        q = s;
    }
    if q != 0.0 {
        h[n] = q;
        n += 1;
    }
    n
}

/// `lift · minor` summed over the three rows of the in-circle determinant, each row's lift
/// `x² + y²` applied as two scalings (Shewchuk's `incircleadapt` evaluates the same terms).
fn row_term(x: f64, y: f64, minor: &[f64], out: &mut [f64; 32]) -> usize {
    let (mut xm, mut xxm) = ([0.0; 8], [0.0; 16]);
    let (mut ym, mut yym) = ([0.0; 8], [0.0; 16]);
    let n = scale(minor, x, &mut xm);
    let n = scale(&xm[..n], x, &mut xxm);
    let m = scale(minor, y, &mut ym);
    let m = scale(&ym[..m], y, &mut yym);
    sum(&xxm[..n], &yym[..m], out)
}

/// The 2×2 minor `p·s − q·r` as an expansion of at most four components; returns the length.
fn minor(p: f64, s: f64, q: f64, r: f64, out: &mut [f64; 4]) -> usize {
    let (ps1, ps0) = two_product(p, s);
    let (qr1, qr0) = two_product(q, r);
    sum(&[ps0, ps1], &[-qr0, -qr1], out)
}

/// The sign of the in-circle determinant of `a`, `b`, `c`, `d` (positive when `d` lies inside
/// the circle through the counter-clockwise `a`, `b`, `c`), exactly, as a double of that sign —
/// or `None` when a coordinate difference `a − d`, `b − d`, `c − d` is not exact in double
/// precision (then the general adaptive stages decide).
pub fn incircle_of_exact_differences(
    a: [f64; 2],
    b: [f64; 2],
    c: [f64; 2],
    d: [f64; 2],
) -> Option<f64> {
    let mut differences = [0.0; 6];
    for (k, (p, axis)) in [(a, 0), (a, 1), (b, 0), (b, 1), (c, 0), (c, 1)]
        .into_iter()
        .enumerate()
    {
        let (x, error) = two_diff(p[axis], d[axis]);
        if error != 0.0 {
            return None;
        }
        differences[k] = x;
    }
    let [adx, ady, bdx, bdy, cdx, cdy] = differences;
    let mut m = [0.0; 4];
    let (mut rows, mut lengths) = ([[0.0; 32]; 3], [0; 3]);
    let n = minor(bdx, cdy, cdx, bdy, &mut m);
    lengths[0] = row_term(adx, ady, &m[..n], &mut rows[0]);
    let n = minor(cdx, ady, adx, cdy, &mut m);
    lengths[1] = row_term(bdx, bdy, &m[..n], &mut rows[1]);
    let n = minor(adx, bdy, bdx, ady, &mut m);
    lengths[2] = row_term(cdx, cdy, &m[..n], &mut rows[2]);
    let mut ab = [0.0; 64];
    let n = sum(&rows[0][..lengths[0]], &rows[1][..lengths[1]], &mut ab);
    let mut det = [0.0; 96];
    let n = sum(&ab[..n], &rows[2][..lengths[2]], &mut det);
    // Nonoverlapping and in increasing magnitude: the last component carries the sign.
    Some(if n == 0 { 0.0 } else { det[n - 1] })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn robust_sign(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
        let coord = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
        sign(robust::incircle(coord(a), coord(b), coord(c), coord(d)))
    }

    fn sign(x: f64) -> f64 {
        if x == 0.0 {
            0.0
        } else {
            x.signum()
        }
    }

    #[test]
    fn agrees_with_the_adaptive_predicate_on_ties_and_near_ties() {
        let mut state = 11u64;
        let mut uniform =
            || crate::algorithms::delaunay::order::splitmix64(&mut state) as f64 / u64::MAX as f64;
        let (mut decided, mut ties) = (0, 0);
        for case in 0..40_000 {
            // Points near one another around a centre of any magnitude (their differences
            // mostly exact), on a circle (rounded: ties and near ties) or a grid of decimal
            // steps (cocircular squares whose coordinates are not dyadic), or anywhere.
            let centre = [
                (uniform() - 0.5) * 10f64.powi(case % 9 - 4),
                (uniform() - 0.5) * 10f64.powi(case % 7 - 3),
            ];
            let radius = centre[0].abs().max(centre[1].abs()).max(1e-3) * 0.3;
            let points: Vec<[f64; 2]> = (0..4)
                .map(|_| match case % 3 {
                    0 => {
                        let t = uniform() * std::f64::consts::TAU;
                        [centre[0] + radius * t.cos(), centre[1] + radius * t.sin()]
                    }
                    1 => {
                        let step = 0.1111 * radius;
                        let (i, j) = ((uniform() * 3.0).floor(), (uniform() * 3.0).floor());
                        [centre[0] + i * step, centre[1] + j * step]
                    }
                    _ => [
                        centre[0] + radius * uniform(),
                        centre[1] + radius * uniform(),
                    ],
                })
                .collect();
            let [a, b, c, d] = [points[0], points[1], points[2], points[3]];
            if let Some(det) = incircle_of_exact_differences(a, b, c, d) {
                decided += 1;
                let distinct = (0..4).all(|i| (0..i).all(|j| points[i] != points[j]));
                ties += usize::from(det == 0.0 && distinct);
                assert_eq!(
                    sign(det),
                    robust_sign(a, b, c, d),
                    "{a:?} {b:?} {c:?} {d:?}"
                );
            }
        }
        assert!(
            decided > 10_000,
            "only {decided} cases had exact differences"
        );
        assert!(
            ties > 100,
            "only {ties} exact ties of four distinct points among them"
        );
    }

    #[test]
    fn expansions_are_exact_sums() {
        // 2^60 + 1 - 2^60 = 1: lost by plain doubles, kept by the expansions.
        let big = 2f64.powi(60);
        let mut h = [0.0; 4];
        let n = sum(&[1.0, big], &[-big], &mut h);
        assert_eq!(&h[..n], &[1.0]);
        let mut s = [0.0; 4];
        let n = scale(&[1.0, big], 3.0, &mut s);
        assert_eq!(s[..n].iter().sum::<f64>(), 3.0 * big + 3.0);
        assert_eq!(s[..n].len(), 2);
    }
}

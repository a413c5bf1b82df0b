//! Exact arithmetic on floating-point expansions (Shewchuk, "Adaptive Precision Floating-Point
//! Arithmetic and Fast Robust Geometric Predicates", 1997): a number held exactly as a sum of
//! doubles of increasing magnitude that do not overlap, built from error-free sums and products.
//!
//! Here for the in-circle test where the floating-point filter cannot decide: first in
//! double-double arithmetic with an error bound of order u² of the permanent
//! ([`incircle_in_double_double`]), which decides near ties; then, for ties of points whose
//! coordinate differences are exact (the points of an in-circle tie are near one another, and
//! the difference of two doubles within a factor two of each other is exact: Sterbenz's lemma),
//! exactly: the determinant is a polynomial in doubles, and its value takes a few short
//! expansions, against the `robust` crate's general adaptive stages (which clear some 20 KiB of
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

/// `a · b` and its rounding error, exactly: by the fused multiply-add where the build targets
/// it, else by Dekker's product of Veltkamp's halves (Shewchuk's Two-Product), seventeen
/// operations inline — `f64::mul_add` without the target feature is a call into a routine that
/// tests the processor, and spills every live double around it (SysV has no callee-saved
/// vector registers): measured, 600 instructions per double-double in-circle stage, not 250.
#[inline(always)]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let x = a * b;
    #[cfg(target_feature = "fma")]
    {
        (x, a.mul_add(b, -x))
    }
    #[cfg(not(target_feature = "fma"))]
    {
        let (a_high, a_low) = split(a);
        let (b_high, b_low) = split(b);
        let error = x - a_high * b_high - a_low * b_high - a_high * b_low;
        (x, a_low * b_low - error)
    }
}

/// Veltkamp's split of `a` into two halves of 26 significant bits each, `a = high + low`
/// exactly for `|a|` below 2⁹⁹⁶ (above, NaNs: [`incircle_in_double_double`] then decides
/// nothing; the engine's frame keeps coordinates below 2¹⁰¹, `crate::scaling`).
#[cfg(not(target_feature = "fma"))]
#[inline(always)]
fn split(a: f64) -> (f64, f64) {
    const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
    let c = SPLITTER * a;
    let high = c - (c - a);
    (high, a - high)
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
/// the circle through the counter-clockwise `a`, `b`, `c`), as a double of that sign, where the
/// floating-point filter could not decide it: in double-double arithmetic where that decides
/// ([`incircle_in_double_double`]: near ties), else exactly in expansions where the coordinate
/// differences `a − d`, `b − d`, `c − d` are exact ([`incircle_of_exact_differences`]: ties);
/// `None` otherwise (then the general adaptive stages decide).
pub fn incircle(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Option<f64> {
    let differences = differences(a, b, c, d);
    incircle_in_double_double(differences).or_else(|| incircle_of_exact_differences(differences))
}

/// The in-circle determinant's rows relative to `d`: `a − d`, `b − d`, `c − d`, each coordinate
/// exactly, as its rounded difference and that rounding's error.
fn differences(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> [Difference; 6] {
    [(a, 0), (a, 1), (b, 0), (b, 1), (c, 0), (c, 1)].map(|(p, axis)| two_diff(p[axis], d[axis]))
}

/// The in-circle determinant's sign from its coordinate `differences`, exactly, as a double of
/// that sign — or `None` when a difference is not exact in double precision.
fn incircle_of_exact_differences(differences: [Difference; 6]) -> Option<f64> {
    if differences.iter().any(|&(_, error)| error != 0.0) {
        return None;
    }
    let [adx, ady, bdx, bdy, cdx, cdy] = differences.map(|(x, _)| x);
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

/// The error bound of [`incircle_in_double_double`] relative to the permanent: 128 u² (u = 2⁻⁵³,
/// the unit roundoff), about twice what its steps can lose (~72 u², see there).
const DOUBLE_DOUBLE_ERRBOUND: f64 = 128.0 * (f64::EPSILON / 2.0) * (f64::EPSILON / 2.0);

/// A coordinate difference `a − b` exactly, as the rounded difference and its rounding error
/// (at most u of it; zero where the difference is exact).
type Difference = (f64, f64);

/// `(x + ξ)² + (y + ψ)²` for differences `(x, ξ)`, `(y, ψ)` as `hi + lo` (`|lo| ≤ u |hi|`),
/// within 21 u² of it (relative): the squares of the rounded differences exact, their sum's
/// high part exact, the six small terms (together at most 4 u of the lift) in doubles, and
/// `ξ² + ψ²` (at most u² of it) left out.
#[inline(always)]
fn lift((x, xi): Difference, (y, psi): Difference) -> (f64, f64) {
    let (xx, xx_error) = two_product(x, x);
    let (yy, yy_error) = two_product(y, y);
    let (s, s_error) = two_sum(xx, yy);
    let tails = 2.0 * (x * xi + y * psi);
    two_sum(s, ((s_error + xx_error) + yy_error) + tails)
}

/// `p·s − q·r` for differences as `hi + lo` (`|lo| ≤ u |hi|`), within 28 u² Q of it (Q =
/// |p·s| + |q·r| of the rounded differences): as [`lift`], the tails' cross terms in doubles,
/// their products (at most 2 u² Q) left out.
#[inline(always)]
fn minor_double_double(
    (p, p_tail): Difference,
    (s, s_tail): Difference,
    (q, q_tail): Difference,
    (r, r_tail): Difference,
) -> (f64, f64) {
    let (ps, ps_error) = two_product(p, s);
    let (qr, qr_error) = two_product(q, r);
    let (d, d_error) = two_diff(ps, qr);
    let tails = (p * s_tail + p_tail * s) - (q * r_tail + q_tail * r);
    two_sum(d, ((d_error + ps_error) - qr_error) + tails)
}

/// `l · m` as a pair `hi + lo` (not renormalized), within 8.1 u² |l|·|m| of the product of the
/// pairs: the high parts' product exact, the cross terms in doubles, `l.lo · m.lo` (≤ u² of it)
/// left out.
#[inline(always)]
fn product_double_double(l: (f64, f64), m: (f64, f64)) -> (f64, f64) {
    let (p, p_error) = two_product(l.0, m.0);
    (p, p_error + (l.0 * m.1 + l.1 * m.0))
}

/// The sign of the in-circle determinant (as [`incircle`]) computed in double-double arithmetic
/// from its exact coordinate `differences`, as a double of that sign when that decides it: `None` for a tie or a near tie within
/// [`DOUBLE_DOUBLE_ERRBOUND`] of the permanent, or where the magnitudes leave the range this
/// bound holds in (the exact stages decide then). A stage between the floating-point filter
/// (error ~10 u of the permanent) and the exact ones, in the manner of Shewchuk's stage C (1997):
/// rounded points in near-cocircular position (on a circle's arc, on a curve's samples) are
/// typically some u of the permanent from a tie, which the filter cannot decide and this stage
/// does, for a tenth of the expansions' work and a fiftieth of `robust`'s.
///
/// Error: each lift within 21 u² L, each minor within 28 u² Q (L a row's lift, Q the sum of
/// its minor's two products' magnitudes), each row's product within 8.1 u² L·Q of theirs, so
/// within 57 u² L·Q of the exact row term; the three rows' high parts are summed exactly and
/// the five small parts (at most 5 u of the permanent P = Σ L·Q) in doubles, losing at most
/// 15 u² P; in all under 72 u² P (a review found 51 u² to first order, and 12 u² at most by
/// search). Underflow: with every difference 0 or at least 2⁻⁴⁸⁰ (else `None`), the products of
/// two differences are exact (multiples of 2⁻¹⁰⁶⁴ of at least 2⁻⁹⁶⁰) and the tails' products
/// lose at most 2⁻¹¹⁵ of Q or L, nothing against u²; what underflows later is absolute, a few
/// 2⁻¹⁰⁷⁴, against a bound of at least 2⁻⁹⁹⁹ for P ≥ 2⁻⁹⁰⁰. Without that guard, differences
/// some 2⁻⁵⁰⁰ apart beside a far point gave wrong signs (the minors' rounding in the subnormal
/// range, multiplied by the far point's lift). Below P = 2⁹⁰⁰ an overflow gives NaNs, rejected.
/// Inside the engine every coordinate is a multiple of 2⁻²⁴⁰ ([`crate::scaling`]): the guard
/// never refuses.
fn incircle_in_double_double(differences: [Difference; 6]) -> Option<f64> {
    let [adx, ady, bdx, bdy, cdx, cdy] = differences;
    // Differences far below the normal range's square root: their products' roundings would
    // be absolute, not relative (see the error bound above).
    let tiny = |(x, _): Difference| x != 0.0 && x.abs() < 2f64.powi(-480);
    if [adx, ady, bdx, bdy, cdx, cdy].into_iter().any(tiny) {
        return None;
    }
    let (alift, blift, clift) = (lift(adx, ady), lift(bdx, bdy), lift(cdx, cdy));
    let bc = minor_double_double(bdx, cdy, cdx, bdy);
    let ca = minor_double_double(cdx, ady, adx, cdy);
    let ab = minor_double_double(adx, bdy, bdx, ady);
    let permanent = ((bdx.0 * cdy.0).abs() + (cdx.0 * bdy.0).abs()) * alift.0
        + ((cdx.0 * ady.0).abs() + (adx.0 * cdy.0).abs()) * blift.0
        + ((adx.0 * bdy.0).abs() + (bdx.0 * ady.0).abs()) * clift.0;
    // Also false for a NaN or an infinity (an overflowed lift).
    if !(2f64.powi(-900)..=2f64.powi(900)).contains(&permanent) {
        return None;
    }
    let a = product_double_double(alift, bc);
    let b = product_double_double(blift, ca);
    let c = product_double_double(clift, ab);
    let (s, s_error) = two_sum(a.0, b.0);
    let (det, det_error) = two_sum(s, c.0);
    let det = det + (((s_error + det_error) + (a.1 + b.1)) + c.1);
    let bound = DOUBLE_DOUBLE_ERRBOUND * permanent;
    (det > bound || -det > bound).then_some(det)
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

    /// Uniform numbers in [0, 1] from `seed`.
    fn uniform_from(mut state: u64) -> impl FnMut() -> f64 {
        move || crate::algorithms::delaunay::order::splitmix64(&mut state) as f64 / u64::MAX as f64
    }

    #[test]
    fn agrees_with_the_adaptive_predicate_on_ties_and_near_ties() {
        let mut uniform = uniform_from(11u64);
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
            if let Some(det) = incircle_of_exact_differences(differences(a, b, c, d)) {
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
    fn the_double_double_stage_decides_near_ties_as_the_adaptive_predicate_does() {
        // Four points on a circle's arc (rounded: some u of the permanent from a tie), at any
        // magnitude and spread, the same points shifted by a tiny step along one axis, and
        // grid squares' corners.
        let mut uniform = uniform_from(38u64);
        let (mut tried, mut decided) = (0, 0);
        for case in 0..40_000usize {
            let scale = 10f64.powi((case % 13) as i32 - 6);
            let spread = 10f64.powi(-((case % 5) as i32));
            let start = uniform() * std::f64::consts::PI;
            let mut points = [[0.0; 2]; 4];
            for p in points.iter_mut() {
                let t = start + spread * uniform();
                *p = [scale * t.cos(), scale * t.sin()];
            }
            if case % 4 == 3 {
                points[3][case % 2] += points[3][case % 2] * f64::EPSILON * (case % 7) as f64;
            }
            if case % 8 == 2 {
                // Corners of decimal grid squares: exact ties the stage must leave undecided.
                let step = 0.1111 * scale;
                for p in points.iter_mut() {
                    let (i, j) = ((uniform() * 3.0).floor(), (uniform() * 3.0).floor());
                    *p = [scale + i * step, scale + j * step];
                }
            }
            let [a, b, c, d] = points;
            tried += 1;
            if let Some(det) = incircle_in_double_double(differences(a, b, c, d)) {
                decided += 1;
                assert_eq!(
                    sign(det),
                    robust_sign(a, b, c, d),
                    "{a:?} {b:?} {c:?} {d:?}"
                );
            }
        }
        assert!(
            decided * 10 > tried * 8,
            "the stage decided only {decided} of {tried} near ties"
        );
    }

    #[test]
    fn the_double_double_stage_leaves_differences_near_underflow_undecided() {
        // A review's counterexample: three points some 2^-500 apart and a far one; the minors'
        // roundings in the subnormal range, times the far point's lift, flipped the sign.
        let h = |s: &str| -> f64 {
            let (mantissa, exponent) = s.split_once('p').unwrap();
            let negative = mantissa.starts_with('-');
            let digits = mantissa.trim_start_matches('-').trim_start_matches("0x1.");
            let bits = u64::from_str_radix(digits, 16).unwrap() as f64 / 2f64.powi(52);
            let value = (1.0 + bits) * 2f64.powi(exponent.parse().unwrap());
            if negative {
                -value
            } else {
                value
            }
        };
        let a = [h("0x1.0000000000000p200"), h("0x1.8000000000000p198")];
        let b = [h("0x1.5eb561bd4f6b8p-501"), h("0x1.9a9a80ef2b725p-501")];
        let c = [h("0x1.d9c278241a0a3p-502"), h("0x1.1555b7f6bc860p-501")];
        let d = [h("-0x1.0c5300342457cp-561"), h("0x1.495efd10bdedap-555")];
        // The exact determinant (rational arithmetic) is +5.0e-215; the stage, unguarded, gave
        // -1.5e-203 (and `robust`, which underflows too, gives a negative sign as well).
        assert_eq!(incircle_in_double_double(differences(a, b, c, d)), None);
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

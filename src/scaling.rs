//! The engine's frame: the caller's coordinates translated to a local origin (where that is
//! exact) and scaled by a power of two, so that the exact predicates stay exact for coordinates of
//! any magnitude and refinement's new vertices are not rounded at the coordinates' magnitude.
//!
//! Translation (refinement only). Far from the origin (georeferenced data: 10^6 m offsets, a
//! survey of 100 m) a double's rounding is large against the features: a split point rounded
//! at 10^6 lands 10^-10 off its segment, which against a 10^-5-high triangle is a sliver that
//! refinement must refuse. So each axis whose coordinates all lie within a factor of two of the
//! one nearest zero, `o` (same sign, `|o| ≤ |x| ≤ 2|o|`), is translated by `o`: by Sterbenz's
//! lemma `x - o` is then exact, and the engine meshes exactly the translated input, with
//! rounding at the scale of the features. New vertices are moved onto the caller's grid before
//! the outputs (see `pipeline::grid`), so that the way back, `x + o`, is exact too.
//!
//! Shewchuk's adaptive predicates are exact only while no product overflows or underflows, and
//! `incircle` multiplies four coordinate differences. Multiplying every coordinate by the same
//! power of two changes no bit of any mantissa (it is exact unless it overflows or underflows,
//! which the choice below rules out) and no sign of any predicate, so the engine works on scaled
//! coordinates and the outputs are scaled back: input vertices are given back bit for bit (the
//! caller's own values), new vertices, Voronoi points and ray directions are scaled back
//! (exact, unless they fall below the smallest normal numbers of a tiny input, see
//! [`Scaling::on_caller_grid`]).
//!
//! The bounds. Let `2^hi` be the largest coordinate magnitude rounded down to a power of two and
//! `2^lo` the finest bit set in any coordinate (every coordinate is an integer multiple of
//! `2^lo`). After scaling by `2^k`:
//! - every coordinate difference, and every term of the adaptive stages (differences, their
//!   rounding tails, Veltkamp halves), is an integer multiple of `2^(lo+k)`, so a product of up
//!   to four of them is a multiple of `2^(4(lo+k))`. With `lo + k ≥ -240` that is at least
//!   `2^-960`: every product is exact or rounds in the normal range, where the predicates' error
//!   bounds hold (and the filters' bounds, about `2^-50` of a permanent, stay normal too);
//! - every coordinate is below `2^(hi+k+1)`; with `hi + k ≤ 100`, degree-four terms (below
//!   `2^(4·102+8)`), circumcentres of the thinnest possible triangles (a degree-three numerator
//!   over a degree-two denominator of at least `2^-480`) and the refinement's degree-four
//!   quality tests stay far below the overflow threshold `2^1024`.
//!
//! `k` is 0 when the input already meets both bounds (every input of ordinary magnitude);
//! otherwise `-hi` (the largest magnitude between 1 and 2, like a unit-size input) unless the
//! finest bit needs more room, then as small as `lo + k ≥ -240` allows. An input with `hi - lo > 340`
//! cannot meet both bounds and is refused with [`Error::CoordinateRange`].

use crate::data::UnsuitableFn;
use crate::error::Error;
use crate::geometry::{Grid, Point};

/// The finest bit that a scaled coordinate may have (see the module documentation).
pub const FINEST_SCALED_BIT: i32 = -240;
/// The largest binary exponent of a scaled coordinate's magnitude.
pub const LARGEST_SCALED_EXPONENT: i32 = 100;
/// The largest `hi - lo` that scaling can accommodate.
pub const LARGEST_BIT_SPAN: i32 = LARGEST_SCALED_EXPONENT - FINEST_SCALED_BIT;

/// `floor(log2 |x|)` of a finite non-zero `x`.
fn exponent(x: f64) -> i32 {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    if biased == 0 {
        let mantissa = bits & ((1 << 52) - 1);
        -1074 + 63 - mantissa.leading_zeros() as i32
    } else {
        biased - 1023
    }
}

/// The largest and the smallest nonzero magnitude of a set of coordinates, gathered one value
/// at a time (by the pass that copies the input, so that the screen costs no pass of its own):
/// a cheap sufficient test that no scaling is needed ([`Magnitudes::within_bounds`]), and
/// whether every value is finite. Finite doubles of one sign order as their bit patterns do,
/// so both are integer minima and maxima of the magnitudes' bits (infinities and NaNs have
/// patterns above every finite one).
#[derive(Clone, Copy, Debug)]
pub struct Magnitudes {
    largest: u64,
    /// The smallest magnitude less one: a zero wraps to the largest pattern and leaves the
    /// minimum alone.
    smallest_less_one: u64,
}

impl Default for Magnitudes {
    fn default() -> Self {
        Magnitudes {
            largest: 0,
            smallest_less_one: u64::MAX,
        }
    }
}

impl Magnitudes {
    const MAGNITUDE: u64 = !(1 << 63);

    /// The magnitudes of `values`.
    pub fn of(values: &[f64]) -> Magnitudes {
        let mut m = Magnitudes::default();
        for &x in values {
            m.add(x);
        }
        m
    }

    /// Takes `x` into account.
    #[inline(always)]
    pub fn add(&mut self, x: f64) {
        let bits = x.to_bits() & Self::MAGNITUDE;
        self.largest = self.largest.max(bits);
        self.smallest_less_one = self.smallest_less_one.min(bits.wrapping_sub(1));
    }

    /// The magnitudes of both sets together.
    pub fn merge(self, other: Magnitudes) -> Magnitudes {
        Magnitudes {
            largest: self.largest.max(other.largest),
            smallest_less_one: self.smallest_less_one.min(other.smallest_less_one),
        }
    }

    /// Whether every value is finite.
    pub fn all_finite(&self) -> bool {
        self.largest < f64::INFINITY.to_bits()
    }

    /// A cheap sufficient test that no scaling is needed, from the largest and the smallest
    /// nonzero magnitude alone (of finite values). A coordinate's lowest bit is at least its
    /// exponent − 52, so the smallest magnitude bounds every lowest bit from below; when that
    /// bound and the largest exponent are within the limits, so are the exact values
    /// [`Scaling::for_points`] would compute, and it would return no scaling.
    fn within_bounds(&self) -> bool {
        if self.largest == 0 {
            return false; // all zero: the exact pass says so
        }
        let smallest = self.smallest_less_one.wrapping_add(1);
        let (hi, lo) = (
            exponent(f64::from_bits(self.largest)),
            exponent(f64::from_bits(smallest)) - 52,
        );
        hi <= LARGEST_SCALED_EXPONENT && lo >= FINEST_SCALED_BIT && hi - lo <= LARGEST_BIT_SPAN
    }
}

/// The exponent of the lowest set bit of a finite non-zero `x`.
fn lowest_bit(x: f64) -> i32 {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let mantissa = bits & ((1 << 52) - 1);
    if biased == 0 {
        -1074 + mantissa.trailing_zeros() as i32
    } else {
        biased - 1075 + (mantissa | 1 << 52).trailing_zeros() as i32
    }
}

/// `2^e` for `e` from -1074 (the smallest subnormal) to 1023.
fn power_of_two(e: i32) -> f64 {
    debug_assert!((-1074..=1023).contains(&e));
    if e >= -1022 {
        f64::from_bits(((e + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (e + 1074))
    }
}

/// `x · 2^k` for any `k` (area scaling doubles the exponent, beyond one power's range), rounded
/// once: `x` is first brought to [1, 2) exactly, then moved to its place by one multiplication
/// (two, both exact, while the result is normal; the last one rounds when it is subnormal).
fn times_power_of_two(x: f64, k: i32) -> f64 {
    if k == 0 || x == 0.0 || !x.is_finite() {
        return x;
    }
    let e = exponent(x);
    // Exact: the result lies in [1, 2).
    let unit = if e >= -1023 {
        x * power_of_two(-e)
    } else {
        x * power_of_two(1023) * power_of_two(-e - 1023)
    };
    let target = e + k;
    if target > 1023 {
        return unit * f64::INFINITY;
    }
    if target >= -1022 {
        return unit * power_of_two(target);
    }
    if target + 1022 < -1074 {
        return 0.0f64.copysign(x);
    }
    unit * power_of_two(-1022) * power_of_two(target + 1022)
}

/// The origin of one axis whose coordinates span `[low, high]`: the end nearest zero when every
/// coordinate lies within a factor of two of it (then `x - origin` is exact for each, by
/// Sterbenz's lemma), else 0.
fn exact_origin(low: f64, high: f64) -> f64 {
    let (near, far) = if low > 0.0 {
        (low, high)
    } else if high < 0.0 {
        (high, low)
    } else {
        return 0.0;
    };
    if far.abs() <= 2.0 * near.abs() {
        near
    } else {
        0.0
    }
}

/// Engine coordinate = (caller's coordinate − `origin`) · `2^exponent`, per axis.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Scaling {
    pub exponent: i32,
    /// The local origin, in the caller's units; 0 on an axis that is not translated.
    pub origin: Point,
}

impl Scaling {
    /// The scaling for the points (x, y pairs), or the error that no scaling makes them safe.
    pub fn for_points(points: &[Point]) -> Result<Scaling, Error> {
        Scaling::for_screened_points(points, Magnitudes::of(points.as_flattened()), false)
    }

    /// The frame for finite points whose [`Magnitudes`] are known already: translated to an
    /// exact local origin where `translate` asks for it and one exists (see the module
    /// documentation), scaled so that the translated coordinates are safe.
    pub fn for_screened_points(
        points: &[Point],
        magnitudes: Magnitudes,
        translate: bool,
    ) -> Result<Scaling, Error> {
        let origin = if translate {
            let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
            for p in points {
                for i in 0..2 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
            [exact_origin(lo[0], hi[0]), exact_origin(lo[1], hi[1])]
        } else {
            [0.0; 2]
        };
        if origin == [0.0; 2] {
            return Scaling::for_local_points(points, magnitudes).map(|s| Scaling { origin, ..s });
        }
        // Exact (Sterbenz), so the bounds are the translated points' own.
        let local: Vec<Point> = points
            .iter()
            .map(|p| [p[0] - origin[0], p[1] - origin[1]])
            .collect();
        let magnitudes = Magnitudes::of(local.as_flattened());
        Scaling::for_local_points(&local, magnitudes).map(|s| Scaling { origin, ..s })
    }

    /// The power of two for points already in the local frame.
    fn for_local_points(points: &[Point], magnitudes: Magnitudes) -> Result<Scaling, Error> {
        if magnitudes.within_bounds() {
            return Ok(Scaling::default());
        }
        // The largest magnitude's exponent and the finest bit, in one pass without branches on
        // the data (a zero has no bits: it leaves both alone).
        let (mut hi, mut lo) = (i32::MIN, i32::MAX);
        for &x in points.as_flattened() {
            let nonzero = x != 0.0;
            hi = hi.max(if nonzero { exponent(x) } else { i32::MIN });
            lo = lo.min(if nonzero { lowest_bit(x) } else { i32::MAX });
        }
        if hi == i32::MIN {
            return Ok(Scaling::default());
        }
        if hi - lo > LARGEST_BIT_SPAN {
            // The first vertices that have them, for the message.
            let first_with = |has: &dyn Fn(f64) -> bool| {
                points
                    .iter()
                    .position(|p| p.iter().any(|&x| x != 0.0 && has(x)))
                    .unwrap_or(0)
            };
            let big = first_with(&|x| exponent(x) == hi);
            let fine = first_with(&|x| lowest_bit(x) == lo);
            return Err(Error::CoordinateRange(format!(
                "The vertex coordinates span too many binary orders of magnitude for exact arithmetic: \
                 vertex {big} has a coordinate of magnitude 2^{hi} and vertex {fine} one whose lowest bit is 2^{lo}, \
                 {} binary orders apart; at most {LARGEST_BIT_SPAN} are supported (scaled by a power of two, the \
                 largest magnitude must stay below 2^{} and the lowest bit at or above 2^{FINEST_SCALED_BIT}, so \
                 that no degree-four term of the in-circle test overflows or underflows).",
                hi - lo,
                LARGEST_SCALED_EXPONENT + 1
            )));
        }
        if hi <= LARGEST_SCALED_EXPONENT && lo >= FINEST_SCALED_BIT {
            // Already within both bounds: no scaling (ordinary inputs keep the fast paths that
            // work in the caller's units, and every result is the same as scaled anyway).
            return Ok(Scaling::default());
        }
        let exponent = (-hi).max(FINEST_SCALED_BIT - lo);
        Ok(Scaling {
            exponent,
            origin: [0.0; 2],
        })
    }

    /// Whether engine coordinates are the caller's.
    pub fn is_identity(&self) -> bool {
        self.exponent == 0 && !self.translates()
    }

    /// Whether some axis is translated to a local origin.
    pub fn translates(&self) -> bool {
        self.origin != [0.0; 2]
    }

    /// A caller's point in the engine's frame (exact for the input vertices).
    pub fn to_engine(&self, p: Point) -> Point {
        [
            self.scale(p[0] - self.origin[0]),
            self.scale(p[1] - self.origin[1]),
        ]
    }

    /// An engine point in the caller's units: exact for a point on the caller's grid
    /// ([`Scaling::on_caller_grid`]), else rounded to it.
    pub fn to_caller(&self, p: Point) -> Point {
        [
            self.unscale(p[0]) + self.origin[0],
            self.unscale(p[1]) + self.origin[1],
        ]
    }

    /// The engine point nearest to `p` that the caller's units can represent exactly (which
    /// [`Scaling::to_caller`] then gives back without rounding): `p` itself for an
    /// untranslated frame of ordinary magnitude; else rounded to the caller's doubles (at
    /// the translation's magnitude, or below the normal range of a tiny input). Exact back
    /// into the engine's frame for points within the input's box (Sterbenz again).
    pub fn on_caller_grid(&self, p: Point) -> Point {
        if self.is_identity() {
            return p;
        }
        self.to_engine(self.to_caller(p))
    }

    pub fn scale(&self, x: f64) -> f64 {
        times_power_of_two(x, self.exponent)
    }

    pub fn unscale(&self, x: f64) -> f64 {
        times_power_of_two(x, -self.exponent)
    }

    /// An area bound in scaled units. A positive bound stays positive (an underflow would
    /// turn it into "unconstrained"); an overflow gives infinity, which constrains nothing, as
    /// a bound larger than the domain.
    pub fn scale_area(&self, area: f64) -> f64 {
        let scaled = times_power_of_two(area, 2 * self.exponent);
        if area > 0.0 && scaled == 0.0 {
            f64::MIN_POSITIVE
        } else {
            scaled
        }
    }

    pub fn unscale_area(&self, area: f64) -> f64 {
        times_power_of_two(area, -2 * self.exponent)
    }

    /// A hole or region point in the engine's frame, each coordinate kept within `±limit`, a
    /// bound beyond every engine vertex coordinate: a point outside that box is outside every
    /// triangle, and stays so, while the predicates see no overflowing value.
    pub fn seed_to_engine(&self, p: Point, limit: f64) -> Point {
        self.to_engine(p).map(|x| x.clamp(-limit, limit))
    }

    /// The user's test (`u`), called with the caller's coordinates and area.
    pub fn unscaled_test<'a>(
        self,
        test: &'a UnsuitableFn<'a>,
    ) -> impl Fn(f64, f64, f64, f64, f64, f64, f64) -> bool + Sync + 'a {
        move |ox, oy, dx, dy, ax, ay, area| {
            let [[ox, oy], [dx, dy], [ax, ay]] =
                [[ox, oy], [dx, dy], [ax, ay]].map(|p| self.to_caller(p));
            test(ox, oy, dx, dy, ax, ay, self.unscale_area(area))
        }
    }
}

/// The caller's grid ([`Scaling::on_caller_grid`]) for the engine's algorithms.
impl Grid for Scaling {
    fn round(&self, p: Point) -> Point {
        self.on_caller_grid(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling_by_any_power_of_two_rounds_once() {
        let tiniest = f64::from_bits(1);
        assert_eq!(times_power_of_two(1.0, -1074), tiniest);
        assert_eq!(times_power_of_two(1.0, -1075), 0.0);
        assert_eq!(times_power_of_two(1.5, -1075), tiniest);
        assert_eq!(times_power_of_two(tiniest, 2100), f64::INFINITY);
        assert_eq!(times_power_of_two(tiniest, 2000), power_of_two(926));
        assert_eq!(
            times_power_of_two(f64::MAX, -2000),
            f64::MAX * power_of_two(-1000) * power_of_two(-1000)
        );
        assert_eq!(times_power_of_two(-3.0, -2148), -0.0);
        assert_eq!(times_power_of_two(0.75, 10), 768.0);
        // Subnormal results: one rounding, to even (3 · 2^-1076 is 0.75 ulp: rounds to 1 ulp).
        assert_eq!(times_power_of_two(3.0, -1076), tiniest);
        assert_eq!(times_power_of_two(7.0, -1076), 2.0 * tiniest);
    }

    #[test]
    fn exponents_and_lowest_bits() {
        assert_eq!((exponent(1.0), lowest_bit(1.0)), (0, 0));
        assert_eq!((exponent(-3.0), lowest_bit(-3.0)), (1, 0));
        assert_eq!((exponent(0.75), lowest_bit(0.75)), (-1, -2));
        let tiniest = f64::from_bits(1);
        assert_eq!((exponent(tiniest), lowest_bit(tiniest)), (-1074, -1074));
        assert_eq!(exponent(f64::MAX), 1023);
        assert_eq!(lowest_bit(f64::MAX), 1023 - 52);
        assert_eq!(exponent(f64::MIN_POSITIVE), -1022);
    }

    #[test]
    fn scaling_is_exact_both_ways() {
        for x in [1e300, -1e-300, 3.0e-310, 1.5, 1e150] {
            let s = Scaling::for_points(&[[x, 0.0]]).unwrap();
            let scaled = s.scale(x);
            assert!((1.0..2.0).contains(&scaled.abs()), "{x} → {scaled}");
            assert_eq!(s.unscale(scaled).to_bits(), x.to_bits());
        }
    }

    #[test]
    fn translation_is_exact_or_not_made() {
        // Within a factor of two of the end nearest zero, on either side of it.
        assert_eq!(exact_origin(1e6, 1e6 + 0.001), 1e6);
        assert_eq!(exact_origin(-5e6 - 0.01, -5e6), -5e6);
        assert_eq!(exact_origin(1.0, 2.0), 1.0);
        assert_eq!(exact_origin(1.0, 2.0000000000000004), 0.0);
        assert_eq!(exact_origin(-1.0, 1.0), 0.0);
        assert_eq!(exact_origin(0.0, 1.0), 0.0);
        let points = [[1e12 + 0.25, -3.0], [1e12 + 999.5, -2.5], [1e12, -2.0]];
        let s = Scaling::for_screened_points(&points, Magnitudes::of(points.as_flattened()), true)
            .unwrap();
        assert_eq!(s.origin, [1e12, -2.0]);
        for p in points {
            let local = s.to_engine(p);
            assert_eq!(local[0], p[0] - 1e12);
            assert_eq!(s.to_caller(local), p);
            assert_eq!(s.on_caller_grid(local), local);
        }
        // A point between the caller's doubles is moved onto them, exactly in both frames.
        let between = [s.to_engine(points[0])[0] + 2f64.powi(-30), 0.5];
        let on = s.on_caller_grid(between);
        assert_ne!(on, between);
        assert_eq!(s.to_engine(s.to_caller(on)), on);
    }

    #[test]
    fn too_wide_a_span_is_refused_and_a_wide_one_moves_up() {
        assert!(matches!(
            Scaling::for_points(&[[1e300, 1e-300]]),
            Err(Error::CoordinateRange(_))
        ));
        // 1 and 2^-300: span 300, the lowest bit goes to 2^-240, the top to 2^60.
        let s = Scaling::for_points(&[[1.0, power_of_two(-300)]]).unwrap();
        assert_eq!(s.exponent, 60);
        assert!(Scaling::for_points(&[[0.0, 0.0]]).unwrap().is_identity());
    }
}

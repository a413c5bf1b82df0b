//! Insertion orders for incremental Delaunay triangulation.
//!
//! Inserting points along a Hilbert curve keeps consecutive points close, so the walk that
//! locates each point is short and its memory accesses hit the cache (PERFORMANCE-NOTES.md).
//! Both orders here insert the points in random rounds of growing size, each round in Hilbert
//! order: the biased randomized insertion order (BRIO) of Amenta, Choi and Rote, "Incremental
//! constructions con BRIO" (2003). With rounds that double (`i`), it keeps the expected
//! O(n log n) bound of randomized insertion. The default grows the rounds eightfold (a
//! multiscale order, as in CGAL's spatial sorting): a coarse sketch of the whole point set comes
//! first, so the triangulation never grows as one long Hilbert snake with a ragged hull that
//! each new point must flip its way into; at 10^6 uniform points this takes a third off the time
//! of inserting in plain Hilbert order.

use crate::geometry::Point;

const HILBERT_BITS: u32 = 16;

/// Position of cell `(x, y)` along the Hilbert curve filling a `2^HILBERT_BITS` square grid.
///
/// Four bits of each coordinate at a time through [`HILBERT_TABLE`]: no branches, whose
/// outcomes (the coordinates' bits) would be unpredictable.
fn hilbert_index(x: u32, y: u32) -> u32 {
    let mut d: u32 = 0;
    let mut state = 0usize;
    let mut shift = HILBERT_BITS;
    while shift > 0 {
        shift -= 4;
        let entry = HILBERT_TABLE[state][(((x >> shift) & 15) << 4 | ((y >> shift) & 15)) as usize];
        d = (d << 8) | u32::from(entry & 0xff);
        state = usize::from(entry >> 8);
    }
    d
}

/// The Hilbert curve one level (one bit of x and y) at a time: the sub-square's orientation is
/// one of four transformations of the cell coordinates — 0: as is, 1: transposed (x and y
/// swapped), 2: anti-transposed (swapped and complemented), 3: both complemented (turned by
/// 180°). In the sub-square's frame, quadrant (rx, ry) comes at position (3·rx) xor ry, and
/// the next level is transposed when ry = 0 and rx = 0, anti-transposed when ry = 0 and rx = 1.
/// Returns (position, next orientation).
const fn hilbert_step(state: usize, bx: u32, by: u32) -> (u32, usize) {
    let (rx, ry) = match state {
        0 => (bx, by),
        1 => (by, bx),
        2 => (1 - by, 1 - bx),
        _ => (1 - bx, 1 - by),
    };
    // Composing the orientation with a transposition or an anti-transposition.
    const TRANSPOSED: [usize; 4] = [1, 0, 3, 2];
    const ANTI_TRANSPOSED: [usize; 4] = [2, 3, 0, 1];
    let next = match (rx, ry) {
        (0, 0) => TRANSPOSED[state],
        (1, 0) => ANTI_TRANSPOSED[state],
        _ => state,
    };
    ((3 * rx) ^ ry, next)
}

/// Four levels of [`hilbert_step`] at once: per orientation and 4 bits of x, 4 bits of y (x
/// high), the 8 bits of position (low byte) and the orientation after them (high byte).
const HILBERT_TABLE: [[u16; 256]; 4] = {
    let mut table = [[0u16; 256]; 4];
    let mut start = 0;
    while start < 4 {
        let mut xy = 0;
        while xy < 256 {
            let (mut state, mut d, mut level) = (start, 0u32, 4);
            while level > 0 {
                level -= 1;
                let (digit, next) = hilbert_step(
                    state,
                    (xy as u32 >> (4 + level)) & 1,
                    (xy as u32 >> level) & 1,
                );
                d = (d << 2) | digit;
                state = next;
            }
            table[start][xy] = (d as u16) | ((state as u16) << 8);
            xy += 1;
        }
        start += 1;
    }
    table
};

/// Every point's Hilbert-curve key (over the points' bounding box) in the high half of a word
/// whose low half is the point's index.
fn hilbert_keyed_indices(points: &[Point]) -> Vec<u64> {
    let (mut xmin, mut ymin, mut xmax, mut ymax) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for p in points {
        xmin = xmin.min(p[0]);
        xmax = xmax.max(p[0]);
        ymin = ymin.min(p[1]);
        ymax = ymax.max(p[1]);
    }
    let cells = ((1u32 << HILBERT_BITS) - 1) as f64;
    let scale_x = if xmax > xmin {
        cells / (xmax - xmin)
    } else {
        0.0
    };
    let scale_y = if ymax > ymin {
        cells / (ymax - ymin)
    } else {
        0.0
    };
    points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let x = ((p[0] - xmin) * scale_x) as u32;
            let y = ((p[1] - ymin) * scale_y) as u32;
            let key = hilbert_index(x.min(cells as u32), y.min(cells as u32));
            (u64::from(key) << 32) | i as u64
        })
        .collect()
}

/// The points' indices with their Hilbert keys, sorted by key (among points with equal keys the
/// earlier input point first): the index is each word's low half.
fn hilbert_sorted_keys(points: &[Point]) -> Vec<u64> {
    radix_sort_by_high_half(hilbert_keyed_indices(points))
}

/// All point indices in Hilbert-curve order (among points with equal keys the earlier input
/// point first).
pub fn hilbert_order(points: &[Point]) -> Vec<u32> {
    hilbert_sorted_keys(points)
        .into_iter()
        .map(|k| k as u32)
        .collect()
}

/// Sorts words whose low halves are already increasing by their high halves, keeping the
/// order of equal high halves (so the result is the plain sorted order). A least-significant-
/// digit radix sort (three stable counting passes of 11, 11 and 10 bits) is linear, and at 10^6
/// keys several times faster than a comparison sort.
fn radix_sort_by_high_half(mut keys: Vec<u64>) -> Vec<u64> {
    const PASSES: [(u32, u32); 3] = [(32, 11), (43, 11), (54, 10)];
    if keys.len() < 1 << 10 {
        keys.sort_unstable();
        return keys;
    }
    let mut counts = [[0usize; 1 << 11]; 3];
    for &k in &keys {
        for (pass, &(shift, bits)) in PASSES.iter().enumerate() {
            counts[pass][((k >> shift) & ((1 << bits) - 1)) as usize] += 1;
        }
    }
    let mut other = vec![0u64; keys.len()];
    for (pass, &(shift, bits)) in PASSES.iter().enumerate() {
        let counts = &mut counts[pass];
        if counts.contains(&keys.len()) {
            continue; // one digit value for all keys: this pass would not move anything
        }
        let mut start = 0;
        for c in counts.iter_mut() {
            let n = *c;
            *c = start;
            start += n;
        }
        for &k in &keys {
            let digit = ((k >> shift) & ((1 << bits) - 1)) as usize;
            other[counts[digit]] = k;
            counts[digit] += 1;
        }
        std::mem::swap(&mut keys, &mut other);
    }
    keys
}

/// The default insertion order: rounds growing eightfold, each in Hilbert order.
pub fn multiscale_order(points: &[Point]) -> Vec<u32> {
    rounds_in_hilbert_order(points, 0x6D75_6C74_6973_6361, 3)
}

/// The order of `i`: a biased randomized insertion order, rounds doubling in size.
pub fn brio_order(points: &[Point], seed: u64) -> Vec<u32> {
    rounds_in_hilbert_order(points, seed, 1)
}

/// All point indices in random rounds, each in Hilbert order; the last round holds a fraction
/// 1 − 2^−`growth_bits` of the points, the one before it that fraction of the rest, and so on.
/// Deterministic for a given `seed`. Linear time: the Hilbert order by radix sort, then a
/// stable counting sort by round.
fn rounds_in_hilbert_order(points: &[Point], seed: u64, growth_bits: u32) -> Vec<u32> {
    const ROUNDS: usize = 32;
    let mut state = seed;
    // Round r from the last takes each point with probability (1 − q)·q^r, q = 2^−growth_bits:
    // the number of trailing zero bits of a uniform random word, in steps of `growth_bits`.
    let round_of: Vec<u8> = (0..points.len())
        .map(|_| {
            let from_last =
                (splitmix64(&mut state).trailing_zeros() / growth_bits).min(ROUNDS as u32 - 1);
            (ROUNDS as u32 - 1 - from_last) as u8
        })
        .collect();
    let mut starts = [0usize; ROUNDS + 1];
    for &r in &round_of {
        starts[r as usize + 1] += 1;
    }
    for r in 1..=ROUNDS {
        starts[r] += starts[r - 1];
    }
    let mut order = vec![0u32; points.len()];
    for key in hilbert_sorted_keys(points) {
        let v = key as u32;
        let r = round_of[v as usize] as usize;
        order[starts[r]] = v;
        starts[r] += 1;
    }
    order
}

/// SplitMix64 (Steele, Lea and Flood 2014): a tiny, good-quality seeded generator.
pub fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hilbert_curve_visits_neighbouring_cells() {
        // Consecutive positions are adjacent cells: in the first 64×64 sub-square (which the
        // curve fills before leaving it), and on the coarse grid of 16×16 blocks of 4096² cells.
        for (n, scale) in [(64u32, 0u32), (16, HILBERT_BITS - 4)] {
            let mut by_position = vec![(0u32, 0u32); (n * n) as usize];
            for x in 0..n {
                for y in 0..n {
                    let d = hilbert_index(x << scale, y << scale) >> (2 * scale);
                    assert!(d < n * n, "cells of the first sub-square come first");
                    by_position[d as usize] = (x, y);
                }
            }
            for w in by_position.windows(2) {
                let dist = w[0].0.abs_diff(w[1].0) + w[0].1.abs_diff(w[1].1);
                assert_eq!(dist, 1, "{w:?}");
            }
        }
    }

    #[test]
    fn radix_sort_sorts() {
        let mut s = 3;
        for n in [0usize, 5, 1000, 5000, 100_000] {
            // Few distinct high halves (ties) and a full range, with increasing low halves.
            for spread in [7u64, u32::MAX as u64] {
                let keys: Vec<u64> = (0..n as u64)
                    .map(|i| ((splitmix64(&mut s) % (spread + 1)) << 32) | i)
                    .collect();
                let mut expected = keys.clone();
                expected.sort_unstable();
                assert_eq!(radix_sort_by_high_half(keys), expected);
            }
        }
    }

    #[test]
    fn orders_are_permutations() {
        let mut s = 7;
        let pts: Vec<Point> = (0..1000)
            .map(|_| {
                [
                    splitmix64(&mut s) as f64 / u64::MAX as f64,
                    splitmix64(&mut s) as f64 / u64::MAX as f64,
                ]
            })
            .collect();
        for order in [
            hilbert_order(&pts),
            brio_order(&pts, 42),
            multiscale_order(&pts),
        ] {
            let mut seen = order.clone();
            seen.sort_unstable();
            assert_eq!(seen, (0..1000).collect::<Vec<u32>>());
        }
    }
}
